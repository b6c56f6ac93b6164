// Boxes, spheres and cylinders in shape_msgs/SolidPrimitive's dimension order, both ways.
#include <gtest/gtest.h>

#include "sixdof_core/primitive_dimensions.h"

namespace sixdof_core {
namespace {

TEST(PrimitiveDimensions, EachPrimitiveRoundTripsInSolidPrimitiveOrder) {
  const std::vector<std::pair<ShapeType, std::vector<double>>> cases = {
      {ShapeType::kBox, {0.1, 0.2, 0.3}}, {ShapeType::kSphere, {0.4}}, {ShapeType::kCylinder, {0.5, 0.6}}};
  for (const auto& [type, dimensions] : cases) {
    EXPECT_EQ(primitiveDimensionCount(type), dimensions.size());
    const std::optional<Shape> shape = primitiveShape(type, dimensions);
    ASSERT_TRUE(shape);
    EXPECT_EQ(shape->type, type);
    EXPECT_EQ(primitiveDimensions(*shape), dimensions);
  }
  const Shape cylinder = *primitiveShape(ShapeType::kCylinder, {0.5, 0.6});
  EXPECT_EQ(cylinder.length, 0.5);  // height first, as in SolidPrimitive
  EXPECT_EQ(cylinder.radius, 0.6);
}

TEST(PrimitiveDimensions, WrongCountsAndMeshesAreNoPrimitive) {
  EXPECT_FALSE(primitiveShape(ShapeType::kBox, {0.1, 0.2}));
  EXPECT_FALSE(primitiveShape(ShapeType::kSphere, {}));
  EXPECT_FALSE(primitiveShape(ShapeType::kCylinder, {0.1, 0.2, 0.3}));
  EXPECT_FALSE(primitiveShape(ShapeType::kMesh, {}));
  EXPECT_EQ(primitiveDimensionCount(ShapeType::kMesh), 0u);
  Shape mesh;
  mesh.type = ShapeType::kMesh;
  EXPECT_TRUE(primitiveDimensions(mesh).empty());
}

}  // namespace
}  // namespace sixdof_core
