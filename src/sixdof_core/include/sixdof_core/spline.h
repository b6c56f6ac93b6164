#pragma once
// Joint-space polynomial segments with ros_control's joint_trajectory_controller rules: linear between points
// with positions only, cubic with velocities, quintic with velocities and accelerations. The segments of
// TrajectorySampler (trajectory.h). Header only (no library to link).

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>

namespace sixdof_core {

// How a segment is interpolated; chosen from the derivatives both of its end points carry
// (joint_trajectory_controller's LINEAR, CUBIC and QUINTIC).
enum class InterpolationType { kLinear, kCubic, kQuintic };

// Polynomial p(t) = sum c[k] t^k, t in [0, duration], for one joint over one segment.
class JointSpline {
 public:
  // Linear: positions only. Cubic: positions and velocities. Quintic: positions, velocities, accelerations.
  // Throws std::invalid_argument unless duration > 0.
  JointSpline(InterpolationType type, double duration, double p0, double v0, double a0, double p1, double v1,
              double a1)
      : duration_(duration) {
    if (!(duration > 0.0)) {
      throw std::invalid_argument("JointSpline: duration must be positive, got " + std::to_string(duration));
    }
    const double t = duration;
    const double dp = p1 - p0;
    c_[0] = p0;
    switch (type) {
      case InterpolationType::kLinear:
        c_[1] = dp / t;
        break;
      case InterpolationType::kCubic:
        c_[1] = v0;
        c_[2] = (3.0 * dp - (2.0 * v0 + v1) * t) / (t * t);
        c_[3] = (-2.0 * dp + (v0 + v1) * t) / (t * t * t);
        break;
      case InterpolationType::kQuintic: {
        const double t2 = t * t;
        const double t3 = t2 * t;
        c_[1] = v0;
        c_[2] = 0.5 * a0;
        c_[3] = (20.0 * dp - (8.0 * v1 + 12.0 * v0) * t - (3.0 * a0 - a1) * t2) / (2.0 * t3);
        c_[4] = (-30.0 * dp + (14.0 * v1 + 16.0 * v0) * t + (3.0 * a0 - 2.0 * a1) * t2) / (2.0 * t3 * t);
        c_[5] = (12.0 * dp - 6.0 * (v1 + v0) * t - (a0 - a1) * t2) / (2.0 * t3 * t2);
        break;
      }
    }
  }

  // t is clamped to [0, duration]: the segment holds its end points outside its time span.
  void sample(double t, double& position, double& velocity, double& acceleration) const {
    t = std::clamp(t, 0.0, duration_);
    // Horner evaluation of the polynomial and its first two derivatives.
    position = ((((c_[5] * t + c_[4]) * t + c_[3]) * t + c_[2]) * t + c_[1]) * t + c_[0];
    velocity = (((5.0 * c_[5] * t + 4.0 * c_[4]) * t + 3.0 * c_[3]) * t + 2.0 * c_[2]) * t + c_[1];
    acceleration = ((20.0 * c_[5] * t + 12.0 * c_[4]) * t + 6.0 * c_[3]) * t + 2.0 * c_[2];
  }

 private:
  std::array<double, 6> c_{};
  double duration_;
};

}  // namespace sixdof_core
