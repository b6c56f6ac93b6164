#include "sixdof_control/period_statistics.h"

#include <algorithm>
#include <cmath>

namespace sixdof_control {
namespace {

// The q-quantile (0..1) of the values, nearest rank.
double quantile(std::vector<double> values, double q) {
  if (values.empty()) return 0.0;
  const auto k = static_cast<std::size_t>(std::max(1.0, std::ceil(q * static_cast<double>(values.size()))));
  const std::size_t rank = std::min(values.size(), k) - 1;
  std::nth_element(values.begin(), values.begin() + static_cast<std::ptrdiff_t>(rank), values.end());
  return values[rank];
}

}  // namespace

PeriodStatistics::PeriodStatistics(double nominal_period, std::size_t window)
    : nominal_(nominal_period), window_(window) {
  periods_.reserve(window_);
  cycles_.reserve(window_);
}

void PeriodStatistics::add(double period, double cycle_duration) {
  if (periods_.size() < window_) {
    periods_.push_back(period);
    cycles_.push_back(cycle_duration);
  } else {
    periods_[next_] = period;
    cycles_[next_] = cycle_duration;
  }
  next_ = (next_ + 1) % window_;
}

PeriodSummary PeriodStatistics::summary() const {
  PeriodSummary s;
  s.count = periods_.size();
  s.nominal = nominal_;
  if (periods_.empty()) return s;
  std::vector<double> errors;
  errors.reserve(periods_.size());
  for (double p : periods_) {
    errors.push_back(std::abs(p - nominal_));
    if (p > 2.0 * nominal_) ++s.overruns;
  }
  s.period_p50 = quantile(periods_, 0.5);
  s.period_p99 = quantile(periods_, 0.99);
  s.error_p50 = quantile(errors, 0.5);
  s.error_p99 = quantile(errors, 0.99);
  s.error_max = *std::max_element(errors.begin(), errors.end());
  s.cycle_p50 = quantile(cycles_, 0.5);
  s.cycle_p99 = quantile(cycles_, 0.99);
  return s;
}

void PeriodStatistics::clear() {
  periods_.clear();
  cycles_.clear();
  next_ = 0;
}

}  // namespace sixdof_control
