#pragma once
// Something that commands World joints every physics step (an action handler around a controller), and
// the arbiter deciding which driver currently commands a joint: the gripper's trajectory and gripper_cmd
// actions drive the same finger, and the latest goal wins.

#include <ros/time.h>

#include <map>
#include <string>
#include <vector>

namespace sixdof_sim {

class JointDriver {
 public:
  virtual ~JointDriver() = default;
  // One control step at `now` (seconds on the node's clock), before a physics step.
  virtual void update(double now) = 0;
  // Another driver took (some of) this driver's joints: end the active goal as preempted, stop commanding.
  virtual void release() = 0;
  // The world was reset: abort the active goal, hold the current positions.
  virtual void reset() = 0;
  virtual void publishFeedback(const ros::Time& stamp) = 0;
};

class JointArbiter {
 public:
  // `driver` commands `joints` from now on; drivers that owned any of them are released.
  void claim(JointDriver* driver, const std::vector<std::string>& joints) {
    std::vector<JointDriver*> released;
    for (const std::string& j : joints) {
      JointDriver*& owner = owner_[j];
      if (owner != nullptr && owner != driver) {
        released.push_back(owner);
      }
      owner = driver;
    }
    for (JointDriver* d : released) {
      d->release();
    }
  }
  bool owns(const JointDriver* driver, const std::string& joint) const {
    const auto it = owner_.find(joint);
    return it != owner_.end() && it->second == driver;
  }

 private:
  std::map<std::string, JointDriver*> owner_;
};

}  // namespace sixdof_sim
