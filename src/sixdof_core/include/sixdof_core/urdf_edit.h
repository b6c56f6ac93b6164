#pragma once
// Edits of URDF text that leave every other byte as it was: the setup assistant's repairs (computed inertias, a
// grasp frame) stay readable against the user's own description.

#include <map>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/robot_model.h"

namespace sixdof_core {

// A frame to add: link `name` on a fixed joint `joint` below `parent` at `origin` (in the parent's frame).
struct UrdfFrame {
  std::string name;
  std::string joint;
  std::string parent;
  Eigen::Isometry3d origin = Eigen::Isometry3d::Identity();
};

// An <inertial> to write, with the text of an XML comment written before it ("" for none; "--" is written "- -").
struct UrdfInertial {
  LinkInertial inertial;
  std::string note;
};

struct UrdfEdits {
  // Link -> its new <inertial>: it replaces the link's own, or is added as the link's first child.
  std::map<std::string, UrdfInertial> inertials;
  std::vector<UrdfFrame> frames;  // added before </robot>, in this order
};

// The URDF text with the edits applied. Throws RobotModelError when the text is not XML with a <robot> root, or
// names a link of `edits.inertials` that is not one of the robot's <link> elements.
std::string editUrdf(const std::string& urdf_xml, const UrdfEdits& edits);

// Shortest decimal text (at most 9 significant digits) of a number, as the edits write them.
std::string urdfNumber(double value);

}  // namespace sixdof_core
