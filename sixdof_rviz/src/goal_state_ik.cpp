// GoalStateDisplay's IK worker: the thread that turns the latest dragged pose into GoalIk::solve calls (compute_ik
// and check_state_validity, throttled by "IK Rate"), off rviz's render thread; update() shows the outcome.
#include <chrono>

#include "goal_state_display.h"

namespace sixdof_rviz {

void GoalStateDisplay::ikLoop() {
  using Clock = std::chrono::steady_clock;
  Clock::time_point next_call = Clock::now();
  std::unique_lock<std::mutex> lock(mutex_);
  while (true) {
    wake_.wait(lock, [this] { return stop_ || pending_request_.has_value(); });
    // Throttle: wait out the rest of the period, collecting newer poses meanwhile.
    wake_.wait_until(lock, next_call, [this] { return stop_; });
    if (stop_) return;
    GoalIkRequest request = *pending_request_;
    pending_request_.reset();
    const double period = ik_period_;
    lock.unlock();
    next_call = Clock::now() + std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(period));
    GoalIkOutcome outcome = ik_->solve(request);
    lock.lock();
    outcome_ = outcome;
  }
}

}  // namespace sixdof_rviz
