#pragma once
// The collision scene as Python uses it (sixdof_core.CollisionScene): the core's CollisionScene of one robot
// model's collision geometry with the SRDF's disabled pairs (as move_group builds it), queried with RobotStates.
// PlanningContexts share it. A plan runs without the GIL, so while one runs a change of the scene raises
// instead of racing with it.

#include <atomic>
#include <map>
#include <memory>
#include <utility>
#include <vector>

#include "common.h"
#include "sixdof_core/collision.h"

namespace sixdof_core::python {

class Scene {
 public:
  Scene(ModelPtr model, const CollisionSceneOptions& options);
  // The same robot, a copy of the objects, allowed collisions, padding and scale.
  Scene(const Scene& other);
  Scene& operator=(const Scene&) = delete;

  const ModelPtr& model() const { return model_; }
  std::shared_ptr<const CollisionScene> core() const { return scene_; }
  const CollisionScene& read() const { return *scene_; }
  // The scene to change; throws std::runtime_error while a plan runs in it.
  CollisionScene& edit();

  // Throws std::invalid_argument naming `what` unless the state is of this scene's robot (its model, or a model
  // with the same links and variables).
  void checkState(const RobotState& state, const char* what) const;
  // World poses of the scene's links, in the scene's link order (checks the state).
  std::vector<Eigen::Isometry3d> linkPoses(const RobotState& state) const;

  // Marks the scene in use by a plan for its lifetime.
  class Use {
   public:
    explicit Use(std::shared_ptr<std::atomic<int>> users) : users_(std::move(users)) { ++*users_; }
    ~Use() { --*users_; }
    Use(const Use&) = delete;
    Use& operator=(const Use&) = delete;

   private:
    std::shared_ptr<std::atomic<int>> users_;
  };
  Use use() const { return Use(users_); }

  // The link each attached object hangs on (the core scene does not say), kept by the binding's attach calls.
  std::map<std::string, std::string> attached_links;

 private:
  ModelPtr model_;
  std::shared_ptr<CollisionScene> scene_;
  std::vector<int> link_to_model_;  // model link index of each scene link
  std::shared_ptr<std::atomic<int>> users_ = std::make_shared<std::atomic<int>>(0);
};

}  // namespace sixdof_core::python
