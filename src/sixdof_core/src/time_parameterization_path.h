#pragma once
// The path of the time-optimal parameterization (time_parameterization.cpp): straight lines between the waypoints
// with a circular blend at each interior corner, parameterized by arc length.

#include <Eigen/Core>
#include <cmath>
#include <vector>

namespace sixdof_core::blended_path {

// Waypoints closer than this (joint-space norm) are the same point.
constexpr double kSamePoint = 1e-9;

// One piece of the path: a straight line or a circular arc in joint space, parameterized by arc length.
struct Segment {
  bool circular = false;
  double start = 0.0;  // arc length at the segment's start
  double length = 0.0;
  Eigen::VectorXd a;  // the segment's start point
  Eigen::VectorXd x;  // line: unit direction; arc: unit normal from the arc start towards the centre
  Eigen::VectorXd y;  // arc: unit tangent at the arc start
  double radius = 0.0;

  // An arc is written from its start point, not its centre: a nearly straight corner has a huge radius, and
  // centre + radius * (...) would lose every digit of the small difference (positions went astray by 10^4).
  // The point, tangent and curvature at s, written into `point`, `tangent` and `curvature` (x.size() values each).
  void state(double s, Eigen::Ref<Eigen::VectorXd> point, Eigen::Ref<Eigen::VectorXd> tangent,
             Eigen::Ref<Eigen::VectorXd> curvature) const {
    if (!circular) {
      point = a + x * s;
      tangent = x;
      curvature.setZero();
      return;
    }
    const double angle = s / radius;
    const double c = std::cos(angle), sn = std::sin(angle);
    const double half_sin = std::sin(0.5 * angle);
    point = a + y * (radius * sn) + x * (2.0 * radius * half_sin * half_sin);
    tangent = y * c + x * sn;
    curvature = (x * c - y * sn) / radius;
  }
  // Tangent and curvature at s, written into `tangent` and `curvature` (x.size() values each).
  void derivatives(double s, Eigen::Ref<Eigen::VectorXd> tangent, Eigen::Ref<Eigen::VectorXd> curvature) const {
    if (!circular) {
      tangent = x;
      curvature.setZero();
      return;
    }
    const double angle = s / radius;
    const double c = std::cos(angle), sn = std::sin(angle);
    tangent = y * c + x * sn;
    curvature = (x * c - y * sn) / radius;
  }
};

// Lines between waypoints with a circular blend at each interior corner (Kunz & Stilman's construction),
// and the arc-length positions where the path must stop (corners that cannot be blended).
void buildPath(const std::vector<Eigen::VectorXd>& points, double max_deviation, std::vector<Segment>* segments,
               std::vector<double>* stops);

}  // namespace sixdof_core::blended_path
