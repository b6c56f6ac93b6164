#pragma once

#include <array>
#include <chrono>
#include <cstddef>
#include <sstream>
#include <string>

namespace sixdof_planning {

// The wall time of each stage of a request, in the order they ran: mark(stage) ends the stage that began at the
// previous mark (or at construction). Marking costs a clock read; text() formats "stage 0.1234, ..." (ms).
class StageTimer {
 public:
  static constexpr std::size_t kMaxStages = 12;

  StageTimer() : last_(Clock::now()) {}

  void mark(const char* stage) {
    const Clock::time_point now = Clock::now();
    add(stage, std::chrono::duration<double, std::milli>(now - last_).count());
    last_ = now;
  }
  // A duration measured elsewhere (a reported time), listed with the stages; the clock is not reset.
  void add(const char* stage, double ms) {
    if (count_ < kMaxStages) stages_[count_++] = {stage, ms};
  }

  std::string text() const {
    std::ostringstream out;
    out.precision(4);
    out << std::fixed;
    for (std::size_t i = 0; i < count_; ++i) out << (i ? ", " : "") << stages_[i].first << ' ' << stages_[i].second;
    return out.str();
  }

 private:
  using Clock = std::chrono::steady_clock;
  Clock::time_point last_;
  std::array<std::pair<const char*, double>, kMaxStages> stages_{};
  std::size_t count_ = 0;
};

}  // namespace sixdof_planning
