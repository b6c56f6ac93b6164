#include "time_parameterization_path.h"

#include <algorithm>

namespace sixdof_core::blended_path {
namespace {

Segment line(const Eigen::VectorXd& from, const Eigen::VectorXd& to) {
  Segment seg;
  seg.length = (to - from).norm();
  seg.a = from;
  seg.x = (to - from) / seg.length;
  return seg;
}

}  // namespace

void buildPath(const std::vector<Eigen::VectorXd>& points, double max_deviation, std::vector<Segment>* segments,
               std::vector<double>* stops) {
  const std::size_t m = points.size();
  // Trim at each interior corner: how much of each adjacent line the blend replaces.
  std::vector<double> trim(m, 0.0);
  std::vector<Segment> arcs(m);
  std::vector<bool> blended(m, false), sharp(m, false);
  for (std::size_t i = 1; i + 1 < m; ++i) {
    const Eigen::VectorXd in = (points[i] - points[i - 1]).normalized();
    const Eigen::VectorXd out = (points[i + 1] - points[i]).normalized();
    const double angle = std::acos(std::clamp(in.dot(out), -1.0, 1.0));
    if (angle < 1e-9) continue;  // straight through
    const double half = 0.5 * angle;
    // max_deviation * sin(half) / (1 - cos(half)), without the cancellation of 1 - cos for small angles.
    const double by_deviation = max_deviation / std::tan(0.5 * half);
    const double length =
        std::min({0.5 * (points[i] - points[i - 1]).norm(), 0.5 * (points[i + 1] - points[i]).norm(), by_deviation});
    const double radius = length / std::tan(half);
    if (angle > M_PI - 1e-6 || length < 1e-9 || radius < 1e-9) {
      sharp[i] = true;
      continue;
    }
    trim[i] = length;
    Segment& arc = arcs[i];
    arc.circular = true;
    arc.radius = radius;
    arc.a = points[i] - in * length;
    arc.x = (out - in * in.dot(out)).normalized();  // the part of `out` across `in`: towards the centre
    arc.y = in;
    arc.length = radius * angle;
    blended[i] = true;
  }
  double s = 0.0;
  segments->reserve(segments->size() + 2 * m);  // at most a line and a blend per waypoint
  for (std::size_t i = 0; i + 1 < m; ++i) {
    const Eigen::VectorXd dir = (points[i + 1] - points[i]).normalized();
    const Eigen::VectorXd from = points[i] + dir * trim[i];
    const Eigen::VectorXd to = points[i + 1] - dir * trim[i + 1];
    if ((to - from).norm() > kSamePoint) {
      Segment seg = line(from, to);
      seg.start = s;
      s += seg.length;
      segments->push_back(seg);
    }
    if (blended[i + 1]) {
      Segment arc = arcs[i + 1];
      arc.start = s;
      s += arc.length;
      segments->push_back(arc);
    } else if (sharp[i + 1]) {
      stops->push_back(s);
    }
  }
}

}  // namespace sixdof_core::blended_path
