#pragma once
// Mass properties of solid shapes, and the inertias the setup assistant computes for moving links whose URDF
// <inertial> is missing or unusable (docs/design.md "Setup assistant").

#include <optional>
#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "sixdof_core/geometry.h"
#include "sixdof_core/robot_model.h"

namespace sixdof_core {

// Density (kg/m^3) of computed inertias unless the user gives one: water, roughly a plastic housing.
constexpr double kDefaultInertiaDensity = 1000.0;
// What a moving link without any geometry gets: a small mass at the link origin (that of a 2.7 cm sphere of
// water) with a matching diagonal inertia, enough for a simulator to integrate it.
constexpr double kDefaultLinkMass = 0.01;
constexpr double kDefaultLinkInertia = 1e-6;

// A solid's mass, centre of mass and inertia about it, all in the frame the shape is placed in.
struct MassProperties {
  double volume = 0.0;  // m^3
  double mass = 0.0;    // kg
  Eigen::Vector3d com = Eigen::Vector3d::Zero();
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();  // about com, frame axes
};

// The placed shape as a solid of uniform density (kg/m^3). A mesh is integrated over its triangles (signed
// tetrahedra from the origin); a mesh that encloses no volume (an open surface: less than 1 % of its bounding box,
// or a centre of mass outside that box) counts as its bounding box. Throws std::invalid_argument naming a mesh
// that cannot be loaded or a density that is not > 0.
MassProperties shapeMassProperties(const PlacedShape& placed, double density);

// Several solids as one body (overlaps count twice, as a CAD union would not).
MassProperties combineMassProperties(const std::vector<MassProperties>& parts);

// Why a link's <inertial> cannot be simulated, "" when it can: none, a mass that is not > 0, an inertia that is
// not finite or whose principal moments are not all > 0, or moments that break the triangle inequality (each
// at most the sum of the other two, 1 % slack for rounded values) as no rigid body's can.
std::string inertialProblem(const std::optional<LinkInertial>& inertial);

// An inertia computed for a moving link (one on a joint that is not fixed).
struct InertiaRepair {
  std::string link;
  std::string problem;  // inertialProblem() of the URDF's value
  std::string source;   // "collision", "visual" (no collision geometry) or "default" (no geometry at all)
  double density = 0.0;  // kg/m^3 (0 for "default")
  LinkInertial inertial;  // origin at the centre of mass, link-frame axes
};

// Every moving link whose <inertial> has a problem, in model order, with an inertia computed from its collision
// geometry (its visual geometry where it has no collision geometry) at `density`, or the default mass and
// inertia above where it has neither. Throws std::invalid_argument on a density that is not > 0 or a mesh that
// cannot be loaded (naming the link).
std::vector<InertiaRepair> inertiaRepairs(const RobotModel& model, double density = kDefaultInertiaDensity);

}  // namespace sixdof_core
