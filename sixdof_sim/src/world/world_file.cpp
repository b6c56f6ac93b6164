#include "sixdof_sim/world_file.h"

#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include "sixdof_sim/camera.h"
#include "sixdof_sim/world.h"
#include "world_file_reader.h"

namespace sixdof_sim {
namespace {

// A bin's four static walls standing on the surface at position.z, their outer edges the footprint, named
// <bin>_wall_{x_min,x_max,y_min,y_max}, in the bin's colour.
std::vector<ObjectSpec> binWalls(const BinSpec& bin) {
  Eigen::Isometry3d frame = Eigen::Isometry3d::Identity();
  frame.translation() = bin.position;
  frame.linear() = Eigen::AngleAxisd(bin.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  const double hx = bin.size.x() / 2.0, hy = bin.size.y() / 2.0;
  const double t = bin.wall_thickness, h = bin.wall_height;
  // x walls span the full y side; y walls fit between them.
  const struct {
    const char* suffix;
    Eigen::Vector3d centre, extent;
  } sides[] = {
      {"x_min", {-hx + t / 2, 0, h / 2}, {t, bin.size.y(), h}},
      {"x_max", {hx - t / 2, 0, h / 2}, {t, bin.size.y(), h}},
      {"y_min", {0, -hy + t / 2, h / 2}, {bin.size.x() - 2 * t, t, h}},
      {"y_max", {0, hy - t / 2, h / 2}, {bin.size.x() - 2 * t, t, h}},
  };
  std::vector<ObjectSpec> walls;
  for (const auto& side : sides) {
    ObjectSpec wall;
    wall.name = bin.name + "_wall_" + side.suffix;
    wall.shape.type = ShapeType::kBox;
    wall.shape.box_size = side.extent;
    wall.pose = frame * Eigen::Translation3d(side.centre);
    wall.is_static = true;
    wall.collision = true;
    wall.color = bin.color;
    wall.bin = bin.name;
    walls.push_back(wall);
  }
  return walls;
}

class Parser : public WorldFileReader {
 public:
  using WorldFileReader::WorldFileReader;

  ObjectSpec object(const YAML::Node& node, const std::string& context, bool table) const {
    ObjectSpec spec;
    if (!node.IsMap()) fail(node, context, "must be a mapping");
    if (!node["name"]) fail(node, context, "'name' is required");
    spec.name = text(node["name"], context, "name");
    const std::string named = context + " (" + spec.name + ")";
    if (table) {
      checkKeys(node, named, {"name", "size", "position", "rpy", "friction", "restitution", "color"});
    } else {
      checkKeys(node, named,
                {"name", "shape", "size", "radius", "length", "mesh", "scale", "position", "rpy", "mass", "static",
                 "collision", "friction", "restitution", "color"});
    }
    const std::string shape = table ? "box" : (node["shape"] ? text(node["shape"], named, "shape") : "");
    auto require = [&](const char* key) {
      if (!node[key]) fail(node, named, "a " + shape + " needs '" + key + "'");
      return node[key];
    };
    auto forbid = [&](std::initializer_list<const char*> keys) {
      for (const char* key : keys) {
        if (node[key]) fail(node[key], named, "'" + std::string(key) + "' does not apply to a " + shape);
      }
    };
    if (shape == "box") {
      spec.shape.type = ShapeType::kBox;
      spec.shape.box_size = vector3(require("size"), named, "size");
      forbid({"radius", "length", "mesh", "scale"});
    } else if (shape == "cylinder") {
      spec.shape.type = ShapeType::kCylinder;
      spec.shape.radius = number(require("radius"), named, "radius");
      spec.shape.length = number(require("length"), named, "length");
      forbid({"size", "mesh", "scale"});
    } else if (shape == "sphere") {
      spec.shape.type = ShapeType::kSphere;
      spec.shape.radius = number(require("radius"), named, "radius");
      forbid({"size", "length", "mesh", "scale"});
    } else if (shape == "mesh") {
      spec.shape.type = ShapeType::kMesh;
      spec.shape.mesh_resource = meshPath(text(require("mesh"), named, "mesh"));
      if (node["scale"]) spec.shape.mesh_scale = vector3(node["scale"], named, "scale");
      forbid({"size", "radius", "length"});
    } else if (shape.empty()) {
      fail(node, named, "'shape' is required (box, cylinder, sphere or mesh)");
    } else {
      fail(node["shape"], named, "unknown shape '" + shape + "' (box, cylinder, sphere or mesh)");
    }
    spec.pose = pose(node, named);
    spec.is_static = table ? true : (node["static"] ? boolean(node["static"], named, "static") : false);
    spec.collision = table ? true : (node["collision"] ? boolean(node["collision"], named, "collision") : true);
    spec.table = table;
    if (!spec.collision && !node["static"]) spec.is_static = true;  // markers do not fall through the table
    if (node["mass"]) {
      if (spec.is_static) fail(node["mass"], named, "'mass' does not apply to a static object");
      spec.mass = number(node["mass"], named, "mass");
    } else if (!spec.is_static) {
      fail(node, named, "'mass' is required for a dynamic object");
    }
    if (node["friction"]) spec.friction = number(node["friction"], named, "friction");
    if (node["restitution"]) spec.restitution = number(node["restitution"], named, "restitution");
    if (node["color"]) spec.color = color(node["color"], named);
    const Result valid = validateObjectSpec(spec);
    if (!valid.ok()) fail(node, named, valid.message);
    return spec;
  }

  CameraSpec camera(const YAML::Node& node, const std::string& context) const {
    CameraSpec spec;
    if (!node.IsMap()) fail(node, context, "must be a mapping");
    if (!node["name"]) fail(node, context, "'name' is required");
    spec.name = text(node["name"], context, "name");
    const std::string named = context + " (" + spec.name + ")";
    checkKeys(node, named,
              {"name", "parent", "position", "rpy", "width", "height", "horizontal_fov_deg", "rate", "near", "far",
               "depth_noise_stddev", "depth_noise_quadratic", "seed"});
    if (node["parent"]) spec.parent_link = text(node["parent"], named, "parent");
    spec.pose = pose(node, named);
    auto pixels = [&](const char* key, int* out) {
      if (!node[key]) return;
      const long long value = integer(node[key], named, key);
      if (value < INT_MIN || value > INT_MAX) fail(node[key], named, "'" + std::string(key) + "' is out of range");
      *out = static_cast<int>(value);
    };
    pixels("width", &spec.width);
    pixels("height", &spec.height);
    if (node["horizontal_fov_deg"]) {
      spec.horizontal_fov = number(node["horizontal_fov_deg"], named, "horizontal_fov_deg") * M_PI / 180.0;
    }
    if (node["rate"]) spec.rate = number(node["rate"], named, "rate");
    if (node["near"]) spec.near_clip = number(node["near"], named, "near");
    if (node["far"]) spec.far_clip = number(node["far"], named, "far");
    if (node["depth_noise_stddev"]) {
      spec.depth_noise_stddev = number(node["depth_noise_stddev"], named, "depth_noise_stddev");
    }
    if (node["depth_noise_quadratic"]) {
      spec.depth_noise_quadratic = number(node["depth_noise_quadratic"], named, "depth_noise_quadratic");
    }
    if (node["seed"]) {
      const long long seed = integer(node["seed"], named, "seed");
      if (seed < 0) fail(node["seed"], named, "'seed' must be >= 0");
      spec.seed = static_cast<std::uint64_t>(seed);
    }
    const Result valid = validateCameraSpec(spec);
    if (!valid.ok()) fail(node, named, valid.message);
    return spec;
  }

  // A bin: an open box of four static walls (binWalls).
  BinSpec bin(const YAML::Node& node, const std::string& context) const {
    if (!node.IsMap()) fail(node, context, "must be a mapping");
    if (!node["name"]) fail(node, context, "'name' is required");
    const std::string name = text(node["name"], context, "name");
    const std::string named = context + " (" + name + ")";
    checkKeys(node, named, {"name", "color", "position", "yaw", "size", "wall_height", "wall_thickness"});
    if (!node["position"]) fail(node, named, "'position' [x, y, z] (centre of the bottom) is required");
    const Eigen::Vector3d position = vector3(node["position"], named, "position");
    if (!node["size"]) fail(node, named, "'size' [x, y] (the outer footprint) is required");
    const std::vector<double> size = numbers(node["size"], named, "size", 2);
    if (!node["color"]) fail(node, named, "'color' is required (it names the bin's colour class)");
    const Color color = this->color(node["color"], named);
    const double yaw = node["yaw"] ? number(node["yaw"], named, "yaw") : 0.0;
    const double height =
        node["wall_height"] ? number(node["wall_height"], named, "wall_height") : BinSpec().wall_height;
    const double thickness =
        node["wall_thickness"] ? number(node["wall_thickness"], named, "wall_thickness") : BinSpec().wall_thickness;
    if (!position.allFinite() || !std::isfinite(yaw)) fail(node, named, "'position' and 'yaw' must be finite");
    if (!(size[0] > 0.0 && size[1] > 0.0) || !std::isfinite(size[0]) || !std::isfinite(size[1])) {
      fail(node["size"], named, "'size' must be > 0 in x and y");
    }
    if (!(height > 0.0) || !std::isfinite(height)) fail(node["wall_height"], named, "'wall_height' must be > 0");
    if (!(thickness > 0.0) || !(2.0 * thickness < std::min(size[0], size[1]))) {
      fail(node["wall_thickness"] ? node["wall_thickness"] : node, named,
           "'wall_thickness' must be > 0 and less than half the smaller side of 'size'");
    }
    BinSpec bin;
    bin.name = name;
    bin.color = color;
    bin.position = position;
    bin.yaw = yaw;
    bin.size = Eigen::Vector2d(size[0], size[1]);
    bin.wall_height = height;
    bin.wall_thickness = thickness;
    return bin;
  }

  WorldSpec world(const YAML::Node& root) const {
    if (!root.IsDefined() || root.IsNull()) fail(root, "", "the file is empty");
    checkKeys(root, "",
              {"name", "gravity", "ground", "tables", "objects", "bins", "cameras", "conveyors", "sources", "sinks"});
    WorldSpec spec;
    if (root["name"]) spec.name = text(root["name"], "", "name");
    if (root["gravity"]) spec.gravity = vector3(root["gravity"], "", "gravity");
    if (root["ground"]) {
      const YAML::Node ground = root["ground"];
      if (ground.IsScalar()) {
        spec.ground.enabled = boolean(ground, "ground", "ground");
      } else {
        checkKeys(ground, "ground", {"z", "friction", "restitution"});
        if (ground["z"]) spec.ground.z = number(ground["z"], "ground", "z");
        if (ground["friction"]) spec.ground.friction = number(ground["friction"], "ground", "friction");
        if (ground["restitution"]) spec.ground.restitution = number(ground["restitution"], "ground", "restitution");
        if (spec.ground.friction < 0.0) fail(ground["friction"], "ground", "'friction' must be >= 0");
        if (spec.ground.restitution < 0.0 || spec.ground.restitution > 1.0) {
          fail(ground["restitution"], "ground", "'restitution' must be in [0, 1]");
        }
      }
    }
    std::set<std::string> names;
    for (const char* list : {"tables", "objects"}) {
      forEachItem(root, list, [&](const YAML::Node& item, const std::string& context) {
        ObjectSpec object = this->object(item, context, std::string(list) == "tables");
        if (!names.insert(object.name).second) fail(item, context, "duplicate name '" + object.name + "'");
        spec.objects.push_back(object);
      });
    }
    std::set<std::string> bin_names;
    forEachItem(root, "bins", [&](const YAML::Node& item, const std::string& context) {
      if (item.IsMap() && item["name"] && item["name"].IsScalar() && !bin_names.insert(item["name"].Scalar()).second) {
        fail(item, context, "duplicate bin name '" + item["name"].Scalar() + "'");
      }
      const BinSpec bin = this->bin(item, context);
      for (const ObjectSpec& wall : binWalls(bin)) {
        const Result valid = validateObjectSpec(wall);
        if (!valid.ok()) fail(item, context + " (" + bin.name + ")", valid.message);
        if (!names.insert(wall.name).second) fail(item, context, "duplicate name '" + wall.name + "'");
        spec.objects.push_back(wall);
      }
      spec.bins.push_back(bin);
    });
    std::set<std::string> camera_names;
    forEachItem(root, "cameras", [&](const YAML::Node& item, const std::string& context) {
      CameraSpec camera = this->camera(item, context);
      if (!camera_names.insert(camera.name).second) fail(item, context, "duplicate camera name '" + camera.name + "'");
      spec.cameras.push_back(camera);
    });
    readConveyors(*this, root, &names, &spec);
    return spec;
  }

};

WorldSpec parse(const std::string& yaml_text, const std::string& source_name, const std::string& base_dir) {
  const Parser parser(source_name, base_dir);
  YAML::Node root;
  try {
    root = YAML::Load(yaml_text);
  } catch (const YAML::ParserException& e) {
    throw WorldFileError(source_name + ":" + std::to_string(e.mark.line + 1) + ": YAML syntax error: " + e.msg);
  }
  return parser.world(root);
}

}  // namespace

WorldSpec parseWorldYaml(const std::string& yaml_text, const std::string& source_name) {
  return parse(yaml_text, source_name, "");
}

WorldSpec loadWorldFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw WorldFileError(path + ": cannot be read");
  std::stringstream buffer;
  buffer << in.rdbuf();
  return parse(buffer.str(), path, std::filesystem::path(path).parent_path().string());
}

}  // namespace sixdof_sim
