#pragma once

#include <cstddef>
#include <vector>

namespace sixdof_control {

// Percentiles of the control loop's periods over a window of recent cycles (diagnostics, the jitter benchmark).
struct PeriodSummary {
  std::size_t count = 0;     // periods in the window
  double nominal = 0.0;      // s, 1 / rate
  double period_p50 = 0.0;   // s
  double period_p99 = 0.0;   // s
  double error_p50 = 0.0;    // s, |period - nominal|
  double error_p99 = 0.0;    // s
  double error_max = 0.0;    // s
  double cycle_p50 = 0.0;    // s, read + update + write
  double cycle_p99 = 0.0;    // s
  std::size_t overruns = 0;  // periods longer than twice the nominal one
};

// A ring buffer of the last `window` periods and cycle durations.
class PeriodStatistics {
 public:
  PeriodStatistics(double nominal_period, std::size_t window);

  void add(double period, double cycle_duration);
  PeriodSummary summary() const;
  void clear();

 private:
  double nominal_;
  std::size_t window_;
  std::size_t next_ = 0;
  std::vector<double> periods_;
  std::vector<double> cycles_;
};

}  // namespace sixdof_control
