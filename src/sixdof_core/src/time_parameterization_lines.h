#pragma once
// The small linear programs of the time-optimal parameterization's phase plane (time_parameterization.cpp): the
// largest x where lines bounding a quantity from below stay under lines bounding it from above.

#include <cstddef>
#include <utility>
#include <vector>

namespace sixdof_core::feasible_lines {

// Lines c + m x, at most a fixed number (scratch space filled again for every grid point, never reallocated).
class Lines {
 public:
  explicit Lines(std::size_t capacity) : lines_(capacity) {}
  void clear() { size_ = 0; }
  void add(double c, double m) { lines_[size_++] = {c, m}; }
  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  const std::pair<double, double>& operator[](std::size_t k) const { return lines_[k]; }

 private:
  std::vector<std::pair<double, double>> lines_;
  std::size_t size_ = 0;
};

// The pair of lines (indices into lower and upper) that bounded the previous answer of a largestFeasible caller:
// neighbouring grid points have nearly the same constraints, so it usually bounds the next one too.
struct ActivePair {
  std::size_t lower = 0, upper = 0;
  bool valid = false;
};

// Largest x in [0, cap] where no line of `lower` (pairs {c, m}: c + m x) is above a line of `upper`, given that
// none is at x = 0: the smallest x where a lower line rising against an upper line (slopes differing by more than
// min_slope) meets it, or cap. max(lower) - min(upper) is convex in x, so Newton's steps from cap, each to where
// the lines highest and lowest at the current x meet, fall onto that x through a few of the pairs, not all. The
// feasible x form [0, answer], so where any rising pair meets is at or above the answer: the steps start from
// where `hint`'s pair meets when that is below cap (one step when the pair still bounds the answer), and `hint`
// becomes the pair of the answer.
inline double largestFeasible(const Lines& lower, const Lines& upper, double cap, double min_slope,
                              ActivePair* hint) {
  double x = cap;
  if (lower.empty() || upper.empty()) return x;
  if (hint->valid && hint->lower < lower.size() && hint->upper < upper.size()) {
    const auto& [lc, lm] = lower[hint->lower];
    const auto& [hc, hm] = upper[hint->upper];
    const double slope = lm - hm;
    if (slope > min_slope) {
      const double meet = (hc - lc) / slope;
      if (meet >= 0.0 && meet < x) x = meet;
    }
  }
  for (;;) {
    std::size_t top = 0, bottom = 0;
    double highest = lower[0].first + lower[0].second * x;
    for (std::size_t k = 1; k < lower.size(); ++k) {
      const double value = lower[k].first + lower[k].second * x;
      if (value > highest) {
        highest = value;
        top = k;
      }
    }
    double lowest = upper[0].first + upper[0].second * x;
    for (std::size_t k = 1; k < upper.size(); ++k) {
      const double value = upper[k].first + upper[k].second * x;
      if (value < lowest) {
        lowest = value;
        bottom = k;
      }
    }
    *hint = ActivePair{top, bottom, true};
    if (highest <= lowest) return x;
    const double slope = lower[top].second - upper[bottom].second;
    if (slope <= min_slope) return x;
    const double meet = (upper[bottom].first - lower[top].first) / slope;
    if (!(meet < x)) return x;
    x = meet;
  }
}

}  // namespace sixdof_core::feasible_lines
