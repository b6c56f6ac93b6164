#include "sixdof_core/time_parameterization.h"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <memory>

#include "time_parameterization_inputs.h"
#include "time_parameterization_lines.h"
#include "time_parameterization_path.h"

namespace sixdof_core {
namespace {

using blended_path::kSamePoint;
using blended_path::Segment;
using feasible_lines::ActivePair;
using feasible_lines::largestFeasible;
using feasible_lines::Lines;

// Limits used internally are this fraction of the requested ones, so that the curvature error of the
// grid on blends (evaluated at interval ends only) cannot push a sampled state over a limit.
constexpr double kLimitMargin = 0.999;

struct PathPoint {
  double s = 0.0;
  int segment = 0;    // segment of the interval that starts here (the last point: the last segment)
  bool stop = false;  // path speed must be zero here (ends, sharp corners)
};

// The time-optimal motion along a straight segment (one interval) between squared path speeds x0 and x1, with
// path acceleration limit a and squared speed limit xl: x(s) = min(x0 + 2 a s, xl, x1 + 2 a (length - s)), i.e.
// full acceleration to the peak speed, cruise, full deceleration (any of the three may be empty).
struct LineMotion {
  double v0 = 0.0, peak = 0.0, a = 0.0;   // start path speed, highest path speed, path acceleration
  double accelerate = 0.0, cruise = 0.0;  // arc lengths of the first two phases
  double t1 = 0.0, t2 = 0.0, t3 = 0.0;    // durations of the three phases

  LineMotion() = default;
  LineMotion(double x0, double x1, double length, double acceleration, double speed_limit) : a(acceleration) {
    // The passes keep |x1 - x0| <= 2 a length and both ends under the segment's limit, so the peak is above both.
    const double x_peak = std::max({std::min(speed_limit, 0.5 * (x0 + x1) + a * length), x0, x1});
    const double inverse_2a = 0.5 / a;
    accelerate = std::min(length, (x_peak - x0) * inverse_2a);
    const double decelerate = std::min(length - accelerate, (x_peak - x1) * inverse_2a);
    cruise = std::max(0.0, length - accelerate - decelerate);
    v0 = std::sqrt(x0);
    peak = std::sqrt(x_peak);
    t1 = (peak - v0) / a;
    t2 = cruise > 0.0 ? cruise / peak : 0.0;
    t3 = (peak - std::sqrt(x1)) / a;
  }
  double duration() const { return t1 + t2 + t3; }
  // Arc length from the segment's start, path speed and path acceleration at time tau into the motion.
  void at(double tau, double* s, double* speed, double* acceleration) const {
    if (tau < t1) {
      *s = v0 * tau + 0.5 * a * tau * tau;
      *speed = v0 + a * tau;
      *acceleration = a;
    } else if (tau < t1 + t2) {
      *s = accelerate + peak * (tau - t1);
      *speed = peak;
      *acceleration = 0.0;
    } else {
      const double t = std::min(tau - t1 - t2, t3);
      *s = accelerate + cruise + peak * t - 0.5 * a * t * t;
      *speed = std::max(0.0, peak - a * t);
      *acceleration = -a;
    }
  }
};

// Joint velocities are q' * sd and accelerations q' * sdd + q'' * sd^2 with x = sd^2 and u = sdd.
struct Limits {
  Eigen::VectorXd velocity;
  Eigen::VectorXd acceleration;
};

// The largest x <= hi with -limit <= c0 + c1 * x <= limit (hi itself when c1 is about 0: no bound on x).
double boundAbove(double c0, double c1, double limit, double hi) {
  if (std::abs(c1) < 1e-14) return hi;
  return std::min(hi, ((c1 > 0.0 ? limit : -limit) - c0) * (1.0 / c1));
}

class Solver {
 public:
  Solver(std::vector<Segment> segments, std::vector<PathPoint> grid, Limits limits)
      : segments_(std::move(segments)),
        grid_(std::move(grid)),
        limits_(std::move(limits)),
        joints_(limits_.velocity.size()),
        slots_(grid_.size() - 1),
        lower_lines_(2 * static_cast<std::size_t>(joints_) + 1),
        upper_lines_(2 * static_cast<std::size_t>(joints_) + 1) {
    // On a straight segment every interval has the segment's direction as tangent and no curvature: the speed
    // limit is the segment's, and the constraints need only the direction. Arcs store the tangent and curvature at
    // both ends of each of their intervals, on the interval's own segment (a point on a segment boundary has one
    // curvature per side).
    line_limits_.reserve(segments_.size());
    line_accelerations_.reserve(segments_.size());
    for (const Segment& seg : segments_) {
      line_limits_.push_back(seg.circular ? 0.0 : directionSpeedLimit(seg.x));
      line_accelerations_.push_back(seg.circular ? 0.0 : directionAccelerationLimit(seg.x));
    }
    // Inside an arc an interval starts where the previous one ends: both read the same record.
    std::size_t records = 0;
    for (std::size_t i = 0; i + 1 < grid_.size(); ++i) {
      if (!segmentOf(i).circular) continue;
      const bool continues = i > 0 && grid_[i - 1].segment == grid_[i].segment;
      const std::size_t start = continues ? slots_[i - 1][1] : records++;
      slots_[i] = {start, records++};
    }
    // Every value is written below before it is read: no initial values.
    ends_.reset(new double[2 * joints_ * records]);
    for (std::size_t i = 0; i + 1 < grid_.size(); ++i) {
      const Segment& seg = segmentOf(i);
      if (!seg.circular) continue;
      if (i == 0 || grid_[i - 1].segment != grid_[i].segment) {
        seg.derivatives(std::clamp(grid_[i].s - seg.start, 0.0, seg.length), slot(i, 0, kTangent),
                        slot(i, 0, kCurvature));
      }
      seg.derivatives(std::clamp(grid_[i + 1].s - seg.start, 0.0, seg.length), slot(i, 1, kTangent),
                      slot(i, 1, kCurvature));
    }
  }

  // Fills x_ (squared path speed per grid point), per arc interval the path acceleration u_, and per straight
  // segment (one interval) its motion.
  void solve() {
    const std::size_t n = grid_.size();
    std::vector<double> limit(n);
    for (std::size_t i = 0; i < n; ++i) limit[i] = grid_[i].stop ? 0.0 : pointLimit(i);
    // Backward pass: the largest speed at each point from which the end can still be reached.
    std::vector<double> upper(n);
    upper[n - 1] = 0.0;
    for (std::size_t i = n - 1; i-- > 0;) upper[i] = maxStart(i, limit[i], upper[i + 1]);
    // Forward pass: accelerate as hard as allowed below the backward bound.
    x_.assign(n, 0.0);
    u_.assign(n - 1, 0.0);
    lines_.assign(segments_.size(), LineMotion());
    for (std::size_t i = 0; i + 1 < n; ++i) {
      // The feasible set of (x_i, x_i+1) is convex and holds (0, 0) and (upper_i, some x_i+1 <= upper_i+1),
      // so from any x_i <= upper_i the largest x_i+1 is >= 0 (up to rounding).
      x_[i + 1] = std::max(0.0, largestNext(i, x_[i], upper[i + 1]));
      const Segment& seg = segmentOf(i);
      if (seg.circular) {
        u_[i] = (x_[i + 1] - x_[i]) / (2.0 * step(i));
      } else {
        const int k = grid_[i].segment;
        lines_[k] = LineMotion(x_[i], x_[i + 1], step(i), line_accelerations_[k], line_limits_[k]);
      }
    }
  }

  Trajectory sample(const std::vector<std::string>& names, double period) const {
    const std::size_t n = grid_.size();
    std::vector<double> times(n, 0.0);
    double speed = std::sqrt(x_[0]);  // path speed at the start of interval i
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const double next_speed = std::sqrt(x_[i + 1]);
      if (!segmentOf(i).circular) {
        times[i + 1] = times[i] + lines_[grid_[i].segment].duration();
      } else {
        times[i + 1] = times[i] + 2.0 * step(i) / (speed + next_speed);
      }
      speed = next_speed;
    }
    Trajectory trajectory;
    trajectory.joint_names = names;
    const double total = times.back();
    long samples = 0;
    while (samples * period < total - 1e-9) ++samples;
    trajectory.points.resize(samples + 1);
    std::size_t interval = 0;
    for (long k = 0; k <= samples; ++k) {
      const double t = k < samples ? k * period : total;
      while (interval + 2 < n && times[interval + 1] <= t) ++interval;
      state(interval, t - times[interval], t, &trajectory.points[k]);
    }
    std::fill(trajectory.points.back().velocities.begin(), trajectory.points.back().velocities.end(), 0.0);
    return trajectory;
  }

 private:
  double step(std::size_t i) const { return grid_[i + 1].s - grid_[i].s; }

  // Tangent (kTangent) or curvature (kCurvature) at end e (0: start, 1: end) of arc interval i, in ends_ (slot: to
  // fill).
  static constexpr int kTangent = 0;
  static constexpr int kCurvature = 1;
  Eigen::Map<Eigen::VectorXd> slot(std::size_t i, int e, int which) {
    return Eigen::Map<Eigen::VectorXd>(ends_.get() + (2 * slots_[i][e] + which) * joints_, joints_);
  }
  Eigen::Map<const Eigen::VectorXd> end(std::size_t i, int e, int which) const {
    return Eigen::Map<const Eigen::VectorXd>(ends_.get() + (2 * slots_[i][e] + which) * joints_, joints_);
  }

  const Segment& segmentOf(std::size_t interval) const { return segments_[grid_[interval].segment]; }

  // Largest x along tangent d1 within every joint's velocity limit.
  template <class Vector>
  double directionSpeedLimit(const Vector& d1) const {
    double x = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < d1.size(); ++j) {
      if (std::abs(d1[j]) > 1e-12) x = std::min(x, std::pow(limits_.velocity[j] / d1[j], 2));
    }
    return x;
  }

  // Largest path acceleration |u| along direction d1 within every joint's acceleration limit (on a line, where
  // joint j's acceleration is d1[j] u).
  template <class Vector>
  double directionAccelerationLimit(const Vector& d1) const {
    double u = std::numeric_limits<double>::infinity();
    for (Eigen::Index j = 0; j < d1.size(); ++j) {
      if (d1[j] != 0.0) u = std::min(u, limits_.acceleration[j] / std::abs(d1[j]));
    }
    return u;
  }

  // Largest x at grid point p, for one adjacent interval, with some admissible acceleration.
  double speedLimit(std::size_t interval, int end) {
    if (!segmentOf(interval).circular) return line_limits_[grid_[interval].segment];
    const Eigen::Map<const Eigen::VectorXd> d1 = this->end(interval, end, kTangent);
    const Eigen::Map<const Eigen::VectorXd> d2 = this->end(interval, end, kCurvature);
    double x = directionSpeedLimit(d1);
    // On a straight stretch any x allows u = 0.
    if (d2.isZero()) return x;
    // u must lie in every joint's band [(-A - b x) / a, (A - b x) / a], i.e. between the lines -A / |a| - (b / a) x
    // and A / |a| - (b / a) x; bands with a = 0 bound x directly.
    lower_lines_.clear();
    upper_lines_.clear();
    for (Eigen::Index j = 0; j < d1.size(); ++j) {
      const double aj = d1[j], bj = d2[j], Aj = limits_.acceleration[j];
      if (std::abs(aj) <= 1e-12) {
        if (std::abs(bj) > 1e-12) x = std::min(x, Aj / std::abs(bj));
        continue;
      }
      const double inverse = 1.0 / aj;
      const double reach = Aj * std::abs(inverse), slope = -bj * inverse;
      lower_lines_.add(-reach, slope);
      upper_lines_.add(reach, slope);
    }
    return largestFeasible(lower_lines_, upper_lines_, x, 1e-12, &speed_hint_);
  }

  double pointLimit(std::size_t p) {
    // Inside a segment both intervals see the same tangent and curvature at p.
    if (p > 0 && p + 1 < grid_.size() && grid_[p - 1].segment == grid_[p].segment) return speedLimit(p, 0);
    double x = std::numeric_limits<double>::infinity();
    if (p > 0) x = std::min(x, speedLimit(p - 1, 1));
    if (p + 1 < grid_.size()) x = std::min(x, speedLimit(p, 0));
    return x;
  }

  // Largest x_{i+1} <= next_upper that interval i allows after x_i = x: the constant path acceleration
  // u = (x_{i+1} - x) / (2 ds) must respect every joint's acceleration limit at both ends.
  double largestNext(std::size_t i, double x, double next_upper) const {
    const double h = 2.0 * step(i);
    const Segment& seg = segmentOf(i);
    if (!seg.circular) {
      // Both ends read a (x' - x) / h with the direction a: every joint's limit A bounds x' - x by h A / |a|, the
      // segment's acceleration limit times h.
      return std::min(next_upper, x + h * line_accelerations_[grid_[i].segment]);
    }
    const Eigen::Map<const Eigen::VectorXd> a0 = end(i, 0, kTangent);
    const Eigen::Map<const Eigen::VectorXd> b0 = end(i, 0, kCurvature);
    const Eigen::Map<const Eigen::VectorXd> a1 = end(i, 1, kTangent);
    const Eigen::Map<const Eigen::VectorXd> b1 = end(i, 1, kCurvature);
    const double inverse_h = 1.0 / h;
    double hi = next_upper;
    for (Eigen::Index j = 0; j < a0.size(); ++j) {
      const double A = limits_.acceleration[j];
      // Start: a0 (x' - x) / h + b0 x;  end: a1 (x' - x) / h + b1 x'.
      const double p0 = a0[j] * inverse_h, p1 = a1[j] * inverse_h;
      hi = boundAbove(-p0 * x + b0[j] * x, p0, A, hi);
      hi = boundAbove(-p1 * x, p1 + b1[j], A, hi);
    }
    return hi;
  }

  // Largest x_i <= limit from which interval i can reach some x_{i+1} in [0, next_upper]. Every joint
  // constraint reads -A <= p x_{i+1} + r x_i <= A, i.e. bounds x_{i+1} between lines in x_i; the answer
  // is the largest x_i where every lower line stays under every upper line (a 2-D LP solved exactly).
  double maxStart(std::size_t i, double limit, double next_upper) {
    if (limit == 0.0) return 0.0;
    const double h = 2.0 * step(i);
    const Segment& seg = segmentOf(i);
    // On a line every joint's constraint -A <= a (x_{i+1} - x_i) / h <= A lets x_{i+1} fall below x_i by at most h
    // times the segment's acceleration limit, which bounds x_i against x_{i+1} <= next_upper.
    if (!seg.circular) return std::max(0.0, std::min(limit, next_upper + h * line_accelerations_[grid_[i].segment]));
    const Eigen::Map<const Eigen::VectorXd> a0 = end(i, 0, kTangent);
    const Eigen::Map<const Eigen::VectorXd> b0 = end(i, 0, kCurvature);
    const Eigen::Map<const Eigen::VectorXd> a1 = end(i, 1, kTangent);
    const Eigen::Map<const Eigen::VectorXd> b1 = end(i, 1, kCurvature);
    const double inverse_h = 1.0 / h;
    // Lines x_{i+1} = c + m x_i.
    Lines& lower = lower_lines_;
    Lines& upper = upper_lines_;
    lower.clear();
    upper.clear();
    lower.add(0.0, 0.0);
    upper.add(next_upper, 0.0);
    double best = limit;
    auto add = [&](double p, double r, double A) {
      if (std::abs(p) < 1e-14) {
        if (std::abs(r) > 1e-14) best = std::min(best, A / std::abs(r));
        return;
      }
      const double inverse = 1.0 / p;
      const double reach = std::abs(A * inverse), slope = -r * inverse;
      lower.add(-reach, slope);
      upper.add(reach, slope);
    };
    for (Eigen::Index j = 0; j < a0.size(); ++j) {
      const double A = limits_.acceleration[j];
      const double p0 = a0[j] * inverse_h, p1 = a1[j] * inverse_h;
      add(p0, b0[j] - p0, A);
      add(p1 + b1[j], -p1, A);
    }
    return std::max(0.0, largestFeasible(lower, upper, best, 1e-14, &start_hint_));
  }

  // The state at time tau into interval i (time t from the start), written into `point`.
  void state(std::size_t i, double tau, double t, TrajectoryPoint* point) const {
    const Segment& seg = segmentOf(i);
    double ds = 0.0, sd = 0.0, u = 0.0;
    if (seg.circular) {
      const double sd0 = std::sqrt(x_[i]);
      ds = sd0 * tau + 0.5 * u_[i] * tau * tau;
      sd = std::max(0.0, sd0 + u_[i] * tau);
      u = u_[i];
    } else {
      lines_[grid_[i].segment].at(tau, &ds, &sd, &u);
    }
    ds = std::clamp(ds, 0.0, step(i));
    const double s = std::clamp(grid_[i].s + ds - seg.start, 0.0, seg.length);
    point->time_from_start = t;
    point->positions.resize(joints_);
    point->velocities.resize(joints_);
    point->accelerations.resize(joints_);
    // The tangent into velocities and the curvature into accelerations, then each scaled in place.
    Eigen::Map<Eigen::VectorXd> d1(point->velocities.data(), joints_);
    Eigen::Map<Eigen::VectorXd> d2(point->accelerations.data(), joints_);
    seg.state(s, Eigen::Map<Eigen::VectorXd>(point->positions.data(), joints_), d1, d2);
    d2 = d1 * u + d2 * sd * sd;
    d1 *= sd;
  }

  std::vector<Segment> segments_;
  std::vector<PathPoint> grid_;
  Limits limits_;
  Eigen::Index joints_;
  std::vector<double> line_limits_;         // per segment: a line's speed limit
  std::vector<double> line_accelerations_;  // per segment: a line's path acceleration limit
  std::vector<std::array<std::size_t, 2>> slots_;  // per interval on an arc: its start's and end's records in ends_
  // Records of a tangent then a curvature (2 * joints_ values, contiguous): an arc's first interval has a start
  // record of its own, every other starts on the previous interval's end record.
  std::unique_ptr<double[]> ends_;
  std::vector<double> x_;
  std::vector<double> u_;                               // per arc interval: its constant path acceleration
  std::vector<LineMotion> lines_;                       // per straight segment (one interval): its motion
  Lines lower_lines_;  // speedLimit's and maxStart's scratch space
  Lines upper_lines_;
  ActivePair speed_hint_, start_hint_;  // speedLimit's and maxStart's last active pairs
};

}  // namespace

TimeParameterizationResult computeTimeOptimalTrajectory(const std::vector<std::string>& joint_names,
                                                        const std::vector<std::vector<double>>& waypoints,
                                                        const TimeParameterizationOptions& options) {
  if (auto rejected = rejectInvalidInput(joint_names, waypoints, options)) return *rejected;
  TimeParameterizationResult result;
  const std::size_t n = joint_names.size();
  std::vector<Eigen::VectorXd> points;
  for (const auto& w : waypoints) {
    const Eigen::VectorXd p = Eigen::Map<const Eigen::VectorXd>(w.data(), static_cast<Eigen::Index>(n));
    // Repeated waypoints add no path: dropping them changes nothing.
    if (points.empty() || (p - points.back()).norm() > kSamePoint) points.push_back(p);
  }
  result.trajectory.joint_names = joint_names;
  if (points.size() == 1) {
    TrajectoryPoint rest;
    rest.positions = waypoints.front();
    rest.velocities.assign(n, 0.0);
    rest.accelerations.assign(n, 0.0);
    result.trajectory.points.push_back(rest);
    return result;
  }

  std::vector<Segment> segments;
  std::vector<double> stops;
  blended_path::buildPath(points, options.max_deviation, &segments, &stops);

  // Grid: a straight segment is one interval (its motion is solved in closed form: the tangent is constant, so the
  // limits read the same all along it); a blend is split into equal steps no longer than the resolution (at least
  // two) that also turn the tangent by at most kMaxStepAngle: the limits hold at interval ends, and between them
  // the error grows with the square of that angle (sampled every 0.2 ms over 300 random paths: 0.01 rad 6e-5 of a
  // limit, 0.02 rad 2e-4, 0.05 rad 1.3e-3; the margin is 1e-3).
  constexpr double kMaxStepAngle = 0.02;
  std::vector<int> steps(segments.size());
  std::size_t grid_size = 1;
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const Segment& seg = segments[k];
    if (!seg.circular) {
      steps[k] = 1;
    } else {
      const double max_step = std::min(options.path_resolution, kMaxStepAngle * seg.radius);
      steps[k] = std::max(2, static_cast<int>(std::ceil(seg.length / max_step)));
    }
    grid_size += steps[k];
  }
  std::vector<PathPoint> grid;
  grid.reserve(grid_size);
  for (std::size_t k = 0; k < segments.size(); ++k) {
    const Segment& seg = segments[k];
    for (int i = 0; i < steps[k]; ++i) {
      grid.push_back(PathPoint{seg.start + seg.length * i / steps[k], static_cast<int>(k)});
    }
  }
  grid.push_back(PathPoint{segments.back().start + segments.back().length, static_cast<int>(segments.size() - 1)});
  grid.front().stop = true;
  grid.back().stop = true;
  // The grid's arc lengths ascend: each stop marks the points within 1e-12 of it, found by bisection.
  for (double stop : stops) {
    auto p = std::lower_bound(grid.begin(), grid.end(), stop,
                              [](const PathPoint& point, double s) { return point.s - s <= -1e-12; });
    for (; p != grid.end() && p->s - stop < 1e-12; ++p) p->stop = true;
  }

  Limits limits;
  limits.velocity = Eigen::Map<const Eigen::VectorXd>(options.max_velocity.data(), static_cast<Eigen::Index>(n)) *
                    (options.velocity_scaling * kLimitMargin);
  limits.acceleration =
      Eigen::Map<const Eigen::VectorXd>(options.max_acceleration.data(), static_cast<Eigen::Index>(n)) *
      (options.acceleration_scaling * kLimitMargin);
  Solver solver(std::move(segments), std::move(grid), std::move(limits));
  solver.solve();
  result.trajectory = solver.sample(joint_names, options.sample_period);
  // The path (straight segments, circular blends inside each corner's triangle) never leaves the waypoints' range
  // per joint; sampled positions beyond it by rounding (a joint held at its limit pi read as pi + 4e-16, which a
  // controller checking its limits refuses) are put back on it.
  Eigen::VectorXd lowest = points.front();
  Eigen::VectorXd highest = points.front();
  for (const Eigen::VectorXd& p : points) {
    lowest = lowest.cwiseMin(p);
    highest = highest.cwiseMax(p);
  }
  for (TrajectoryPoint& point : result.trajectory.points) {
    for (std::size_t j = 0; j < n; ++j) point.positions[j] = std::clamp(point.positions[j], lowest[j], highest[j]);
  }
  // Exact end points (the path's own ends differ by rounding only).
  result.trajectory.points.front().positions = waypoints.front();
  result.trajectory.points.back().positions = std::vector<double>(points.back().data(), points.back().data() + n);
  return result;
}

}  // namespace sixdof_core
