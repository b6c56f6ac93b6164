#pragma once
// World files (YAML, documented in worlds/README.md) -> WorldSpec.

#include <stdexcept>
#include <string>

#include "sixdof_sim/world_types.h"

namespace sixdof_sim {

// A world file that cannot be used. what() names the file, the entry and the problem,
// e.g. "table_top.yaml: objects[2] (red_cube): 'mass' must be > 0 for a dynamic object".
class WorldFileError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Parses YAML text; source_name prefixes error messages.
WorldSpec parseWorldYaml(const std::string& yaml_text, const std::string& source_name = "<string>");
// Reads and parses a world file.
WorldSpec loadWorldFile(const std::string& path);

// A shape in the world file's keys: field(key, value) for "shape" (box, cylinder, sphere or mesh, a std::string),
// then its dimensions: a box's "size", a mesh's "scale" (Eigen::Vector3d), a cylinder's "radius" and "length", a
// sphere's "radius" (double), a mesh's "mesh" (the resource as written, std::string).
template <class Field>
void forEachShapeField(const Shape& shape, Field&& field) {
  const bool box = shape.type == ShapeType::kBox, cylinder = shape.type == ShapeType::kCylinder;
  const bool sphere = shape.type == ShapeType::kSphere, mesh = shape.type == ShapeType::kMesh;
  field("shape", std::string(box ? "box" : cylinder ? "cylinder" : sphere ? "sphere" : "mesh"));
  if (box) field("size", shape.box_size);
  if (cylinder || sphere) field("radius", shape.radius);
  if (cylinder) field("length", shape.length);
  if (mesh) {
    field("mesh", shape.mesh_resource);
    field("scale", shape.mesh_scale);
  }
}

}  // namespace sixdof_sim
