// The world file's conveyors, sources and sinks (worlds/README.md).
#include <cmath>
#include <limits>

#include "sixdof_sim/conveyor.h"
#include "world_file_reader.h"

namespace sixdof_sim {
namespace {

// The entry's name and its context "list[i] (name)".
std::string entryName(const WorldFileReader& reader, const YAML::Node& node, const std::string& context,
                      std::string* named) {
  if (!node.IsMap()) reader.fail(node, context, "must be a mapping");
  if (!node["name"]) reader.fail(node, context, "'name' is required");
  const std::string name = reader.text(node["name"], context, "name");
  *named = context + " (" + name + ")";
  return name;
}

double optionalNumber(const WorldFileReader& reader, const YAML::Node& node, const std::string& named, const char* key,
                      double fallback) {
  return node[key] ? reader.number(node[key], named, key) : fallback;
}

ConveyorSpec conveyor(const WorldFileReader& reader, const YAML::Node& node, const std::string& context) {
  std::string named;
  ConveyorSpec spec;
  spec.name = entryName(reader, node, context, &named);
  reader.checkKeys(node, named, {"name", "size", "position", "rpy", "speed", "direction", "friction", "color"});
  if (!node["size"]) reader.fail(node, named, "'size' [x, y, z] is required (x along the belt, y across)");
  spec.size = reader.vector3(node["size"], named, "size");
  spec.pose = reader.pose(node, named);
  spec.speed = optionalNumber(reader, node, named, "speed", 0.0);
  if (node["direction"]) {
    const std::vector<double> d = reader.numbers(node["direction"], named, "direction", 2);
    spec.direction = Eigen::Vector2d(d[0], d[1]);
  }
  spec.friction = optionalNumber(reader, node, named, "friction", spec.friction);
  if (node["color"]) spec.color = reader.color(node["color"], named);
  const Result valid = validateConveyorSpec(spec);
  if (!valid.ok()) reader.fail(node, named, valid.message);
  return spec;
}

ShapeType shapeNamed(const WorldFileReader& reader, const YAML::Node& node, const std::string& named) {
  const std::string shape = reader.text(node, named, "shapes");
  if (shape == "box") return ShapeType::kBox;
  if (shape == "cylinder") return ShapeType::kCylinder;
  if (shape == "sphere") return ShapeType::kSphere;
  reader.fail(node, named, "unknown shape '" + shape + "' in 'shapes' (box, cylinder or sphere)");
}

SourceSpec source(const WorldFileReader& reader, const YAML::Node& node, const std::string& context) {
  std::string named;
  SourceSpec spec;
  spec.name = entryName(reader, node, context, &named);
  reader.checkKeys(node, named,
                   {"name", "conveyor", "position", "lateral_jitter", "shapes", "size", "colors", "mass", "friction",
                    "start", "period", "interval", "seed", "max_count"});
  if (!node["conveyor"]) reader.fail(node, named, "'conveyor' (the conveyor it feeds) is required");
  spec.conveyor = reader.text(node["conveyor"], named, "conveyor");
  if (!node["position"]) reader.fail(node, named, "'position' [x, y] on the belt (conveyor frame) is required");
  const std::vector<double> position = reader.numbers(node["position"], named, "position", 2);
  spec.position = Eigen::Vector2d(position[0], position[1]);
  spec.lateral_jitter = optionalNumber(reader, node, named, "lateral_jitter", 0.0);
  if (node["shapes"]) {
    if (!node["shapes"].IsSequence() || node["shapes"].size() == 0) {
      reader.fail(node["shapes"], named, "'shapes' must be a non-empty list of box, cylinder, sphere");
    }
    spec.shapes.clear();
    for (const auto& shape : node["shapes"]) spec.shapes.push_back(shapeNamed(reader, shape, named));
  }
  if (node["size"]) {
    const std::vector<double> size = reader.numbers(node["size"], named, "size", 2);
    spec.min_size = size[0];
    spec.max_size = size[1];
  }
  if (node["colors"]) {
    if (!node["colors"].IsSequence()) reader.fail(node["colors"], named, "'colors' must be a list of colours");
    for (const auto& color : node["colors"]) spec.colors.push_back(reader.color(color, named));
  }
  spec.mass = optionalNumber(reader, node, named, "mass", spec.mass);
  spec.friction = optionalNumber(reader, node, named, "friction", spec.friction);
  spec.start = optionalNumber(reader, node, named, "start", 0.0);
  if (node["period"] && node["interval"]) reader.fail(node, named, "give 'period' or 'interval', not both");
  if (node["period"]) {
    spec.period = reader.number(node["period"], named, "period");
    if (!(spec.period > 0.0)) reader.fail(node["period"], named, "'period' must be > 0 (s)");
  } else if (node["interval"]) {
    const std::vector<double> interval = reader.numbers(node["interval"], named, "interval", 2);
    spec.min_interval = interval[0];
    spec.max_interval = interval[1];
  } else {
    reader.fail(node, named, "'period' (s) or 'interval' [min, max] (s) is required");
  }
  if (node["seed"]) {
    const long long seed = reader.integer(node["seed"], named, "seed");
    if (seed < 0) reader.fail(node["seed"], named, "'seed' must be >= 0");
    spec.seed = static_cast<std::uint64_t>(seed);
  }
  if (node["max_count"]) spec.max_count = reader.integer(node["max_count"], named, "max_count");
  const Result valid = validateSourceSpec(spec);
  if (!valid.ok()) reader.fail(node, named, valid.message);
  return spec;
}

SinkSpec sink(const WorldFileReader& reader, const YAML::Node& node, const std::string& context) {
  std::string named;
  SinkSpec spec;
  spec.name = entryName(reader, node, context, &named);
  reader.checkKeys(node, named, {"name", "below", "position", "rpy", "size"});
  if (node["below"]) {
    if (node["position"] || node["size"] || node["rpy"]) {
      reader.fail(node, named, "give either 'below' (a height) or 'position' and 'size' (a box region), not both");
    }
    spec.below_only = true;
    spec.below = reader.number(node["below"], named, "below");
  } else {
    if (!node["size"]) reader.fail(node, named, "'size' [x, y, z] of the region (or 'below': a height) is required");
    spec.size = reader.vector3(node["size"], named, "size");
    spec.pose = reader.pose(node, named);
  }
  const Result valid = validateSinkSpec(spec);
  if (!valid.ok()) reader.fail(node, named, valid.message);
  return spec;
}

// Names must be unique within a list; the node of the duplicate is named.
void unique(const WorldFileReader& reader, const YAML::Node& node, const std::string& context, const std::string& name,
            std::set<std::string>* names) {
  if (!names->insert(name).second) reader.fail(node, context, "duplicate name '" + name + "'");
}

}  // namespace

void readConveyors(const WorldFileReader& reader, const YAML::Node& root, std::set<std::string>* names,
                   WorldSpec* spec) {
  reader.forEachItem(root, "conveyors", [&](const YAML::Node& item, const std::string& context) {
    spec->conveyors.push_back(conveyor(reader, item, context));
    unique(reader, item, context, spec->conveyors.back().name, names);
  });
  std::set<std::string> source_names;
  reader.forEachItem(root, "sources", [&](const YAML::Node& item, const std::string& context) {
    spec->sources.push_back(source(reader, item, context));
    const SourceSpec& s = spec->sources.back();
    unique(reader, item, context, s.name, &source_names);
    bool known = false;
    for (const ConveyorSpec& c : spec->conveyors) known = known || c.name == s.conveyor;
    if (!known) reader.fail(item["conveyor"], context + " (" + s.name + ")", "no conveyor '" + s.conveyor + "'");
  });
  std::set<std::string> sink_names;
  reader.forEachItem(root, "sinks", [&](const YAML::Node& item, const std::string& context) {
    spec->sinks.push_back(sink(reader, item, context));
    unique(reader, item, context, spec->sinks.back().name, &sink_names);
  });
}

}  // namespace sixdof_sim
