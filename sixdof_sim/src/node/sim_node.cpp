#include "sim_node.h"

#include <geometry_msgs/TransformStamped.h>
#include <ros/callback_queue.h>
#include <ros/console.h>
#include <rosgraph_msgs/Clock.h>
#include <sensor_msgs/JointState.h>
#include <sixdof_msgs/GraspEvent.h>
#include <sixdof_msgs/ObjectStates.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "conversions.h"
#include "sixdof_control/controller_params.h"
#include "sixdof_sim/suction.h"
#include "sixdof_sim/world_file.h"
#include "world_parameter.h"

namespace sixdof_sim {

namespace {

// package:// URIs in the URDF and the world resolve against the ROS package path.
std::vector<std::string> packageRoots() {
  std::vector<std::string> roots;
  const char* env = std::getenv("ROS_PACKAGE_PATH");
  std::stringstream paths(env != nullptr ? env : "");
  std::string path;
  while (std::getline(paths, path, ':')) {
    if (!path.empty()) {
      roots.push_back(path);
    }
  }
  return roots;
}

template <class T>
void readParam(const ros::NodeHandle& pnh, const std::string& key, T* value) {
  if (pnh.hasParam(key) && !pnh.getParam(key, *value)) {
    throw std::runtime_error("parameter '" + pnh.resolveName(key) + "' has the wrong type");
  }
}

}  // namespace

SimNodeOptions SimNode::readOptions(const ros::NodeHandle& pnh) {
  SimNodeOptions o;
  readParam(pnh, "world_file", &o.world_file);
  readParam(pnh, "physics_step", &o.physics_step);
  readParam(pnh, "real_time_factor", &o.real_time_factor);
  readParam(pnh, "grasp_fix", &o.grasp_fix);
  readParam(pnh, "publish_rate", &o.publish_rate);
  if (!(o.physics_step > 0.0) || !std::isfinite(o.physics_step)) {
    throw std::runtime_error("~physics_step must be > 0 (seconds)");
  }
  if (!(o.real_time_factor >= 0.0) || !std::isfinite(o.real_time_factor)) {
    throw std::runtime_error("~real_time_factor must be >= 0 (0 = as fast as possible)");
  }
  if (!(o.publish_rate > 0.0) || !std::isfinite(o.publish_rate)) {
    throw std::runtime_error("~publish_rate must be > 0 (Hz)");
  }
  return o;
}

SimNode::SimNode(ros::NodeHandle nh, ros::NodeHandle pnh) : nh_(nh), pnh_(pnh), options_(readOptions(pnh)) {
  // A simulator restarted under the same master (roslaunch respawn) continues the clock of the one before it
  // instead of starting again at 0: every node would otherwise see time jump back, and actionlib servers
  // (e.g. move_group's) cancel goals stamped before the last goal they saw.
  double checkpoint = 0.0;
  if (pnh_.getParam("clock_checkpoint", checkpoint) && std::isfinite(checkpoint) && checkpoint > 0.0) {
    clock_offset_ = checkpoint;
    ROS_INFO_STREAM("[sixdof_sim] resuming /clock at " << checkpoint << " s (a previous simulator's checkpoint)");
  }
  std::string urdf;
  if (!nh_.getParam("robot_description", urdf) || urdf.empty()) {
    throw std::runtime_error("no URDF in parameter '" + nh_.resolveName("robot_description") + "'");
  }
  WorldSpec spec;
  if (!options_.world_file.empty()) {
    spec = loadWorldFile(options_.world_file);
  }
  WorldOptions world_options;
  world_options.time_step = options_.physics_step;
  world_options.package_search_roots = packageRoots();
  // The grasp fix and the suction cup: the URDF's gazebo_grasp_fix and sixdof_suction blocks, else the grasp_fix and
  // suction of the config package's grasping.yaml (robot_description_grasping; the World lets the blocks win).
  std::string grasping;
  if (nh_.getParam("robot_description_grasping", grasping) && !grasping.empty()) {
    const GraspingConfig config =
        parseGraspingConfig(grasping, "parameter " + nh_.resolveName("robot_description_grasping"));
    world_options.grasp_fix_config = config.grasp_fix;
    world_options.suction_config = config.suction;
  }
  world_options.grasp_fix_enabled = false;
  world_ = std::make_unique<World>(urdf, spec, world_options);
  // The world as loaded (defaults applied), for the Python nodes and scripts: they never parse the file.
  pnh_.setParam("world", worldParameter(spec));
  // grasp_fix defaults to true in every launch file; a robot with neither (no gripper, or one that is not set up
  // for it) simply runs without it.
  if (options_.grasp_fix && !world_->graspFixAvailable()) {
    ROS_INFO_STREAM("[sixdof_sim] grasp fix off: neither a <gazebo><plugin name=\"gazebo_grasp_fix\"> block in the "
                    "URDF nor a grasp_fix in " << nh_.resolveName("robot_description_grasping"));
  } else if (options_.grasp_fix) {
    world_->setGraspFixEnabled(true);
  }
  // docs/design.md: the world frame is the robot's (fixed) root link; a robot whose root is `world` (an arm on
  // a mount joint) publishes that frame itself.
  const std::string& root_link = world_->robotModel().rootLink();
  if (root_link != "world") {
    geometry_msgs::TransformStamped world_to_root;
    world_to_root.header.frame_id = "world";
    world_to_root.child_frame_id = root_link;
    world_to_root.transform.rotation.w = 1.0;
    static_tf_broadcaster_.sendTransform(world_to_root);
  }

  // The controllers config says which controllers exist (controller_list), so any robot's config package runs as
  // it is: no gripper is required.
  const sixdof_control::ControllerSetup setup = sixdof_control::readControllerSetup(nh_, pnh_, robotJoints(*world_));
  controllers_ = std::make_unique<SimControllers>(setup, *world_, [this] { return now(); });
  actions_ = std::make_unique<sixdof_control::ControllerActions>(nh_, setup, *controllers_);
  cameras_ = std::make_unique<CameraPublisher>(nh_, *world_, spec, static_tf_broadcaster_);
  world_->setPreStepCallback([this](double sim_time) {
    controllers_->update(clock_offset_ + sim_time);
    cameras_->update(clock_offset_ + sim_time);
  });

  const ros::NodeHandle sim_nh(nh_, "sixdof_sim");
  object_services_ = std::make_unique<ObjectServices>(sim_nh, *world_);
  SimControl control;
  control.reset = [this] { reset(); };
  control.set_paused = [this](bool p) { setPaused(p); };
  control.paused = [this] { return paused_; };
  control.step = [this](std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i) {
      stepOnce();
    }
    publishClock(true);
    publishState();  // steps run faster than the wall-clock bound on the state's rate: the last one goes out
  };
  control_services_ = std::make_unique<SimControlServices>(sim_nh, control);
  if (world_->suctionAvailable() && setup.gripper && setup.gripper->name == world_->suctionConfig()->controller) {
    throw std::runtime_error("suction: controller '" + setup.gripper->name +
                             "' already serves gripper_cmd for a finger joint; give the suction another 'controller'");
  }
  conveyor_services_ = std::make_unique<ConveyorServices>(sim_nh, nh_, *world_);

  clock_pub_ = nh_.advertise<rosgraph_msgs::Clock>("/clock", 10);
  joint_state_pub_ = nh_.advertise<sensor_msgs::JointState>("joint_states", 10);
  object_state_pub_ = nh_.advertise<sixdof_msgs::ObjectStates>("sixdof_sim/object_states", 10);
  grasp_event_pub_ = nh_.advertise<sixdof_msgs::GraspEvent>("grasp_events", 10);
  ROS_INFO_STREAM("[sixdof_sim] " << world_->joints().size() << " joints, " << world_->objectNames().size()
                                  << " objects, step " << options_.physics_step << " s, real-time factor "
                                  << options_.real_time_factor << ", grasp fix "
                                  << (world_->graspFixEnabled() ? "on" : "off") << ", controllers "
                                  << sixdof_control::controllerSummary(setup));
}

SimNode::~SimNode() = default;

void SimNode::publishClock(bool force) {
  // At most 1 kHz of wall time: free-running simulations would otherwise flood /clock subscribers.
  const auto wall = std::chrono::steady_clock::now();
  if (!force && wall - last_clock_wall_ < std::chrono::milliseconds(1)) {
    return;
  }
  last_clock_wall_ = wall;
  rosgraph_msgs::Clock msg;
  msg.clock = ros::Time(now());
  clock_pub_.publish(msg);
}

void SimNode::checkpointClock() {
  constexpr auto kCheckpointPeriod = std::chrono::milliseconds(100);
  const auto wall = std::chrono::steady_clock::now();
  if (wall - last_checkpoint_wall_ < kCheckpointPeriod) {
    return;
  }
  // Ahead of the clock by twice what it advanced since the last checkpoint: the clock will not have reached it by
  // the next one, so a simulator dying in between leaves a checkpoint past every stamp it published.
  const double t = now();
  pnh_.setParam("clock_checkpoint", t + 2.0 * std::max(t - last_checkpoint_sim_, 0.1));
  last_checkpoint_wall_ = wall;
  last_checkpoint_sim_ = t;
}

void SimNode::stepOnce() {
  world_->step(1);
  conveyor_services_->afterStep();
  const ros::Time stamp(now());
  for (const GraspEvent& e : world_->takeGraspEvents()) {
    sixdof_msgs::GraspEvent msg;
    msg.header.stamp = ros::Time(clock_offset_ + e.sim_time);
    msg.header.frame_id = "world";
    msg.event = e.type == GraspEvent::Type::kAttached ? sixdof_msgs::GraspEvent::ATTACHED
                                                      : sixdof_msgs::GraspEvent::DETACHED;
    msg.arm = e.arm;
    msg.object = e.object;
    msg.palm_link = e.palm_link;
    msg.gripper_links = e.gripper_links;
    grasp_event_pub_.publish(msg);
    const bool attached = msg.event == sixdof_msgs::GraspEvent::ATTACHED;
    ROS_INFO_STREAM("[sixdof_sim] " << (attached ? "attached '" : "detached '") << e.object << "' "
                                    << (attached ? "to " : "from ") << e.palm_link);
  }
  // The state goes out at publish_rate of simulated time and at most about publish_rate per wall-clock second: a
  // simulator running many times faster than real time (headless) flooded its consumers, and robot_state_publisher
  // and tf listeners fell seconds of simulated time behind it. The newest state is what goes out, so consumers are
  // never more than about 1 / publish_rate of wall time behind. (0.9: wall-clock jitter must not halve the rate of
  // a simulator in real time.)
  const auto wall = std::chrono::steady_clock::now();
  if (now() + 1e-9 >= next_state_ && wall >= next_state_wall_) {
    next_state_ = now() + 1.0 / options_.publish_rate;
    next_state_wall_ = wall + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                  std::chrono::duration<double>(0.9 / options_.publish_rate));
    publishState();
  }
  if (now() + 1e-9 >= next_publish_) {
    next_publish_ = now() + 1.0 / options_.publish_rate;
    actions_->publish(stamp);
  }
  publishClock(false);
}

void SimNode::publishState() {
  const ros::Time stamp(now());
  sensor_msgs::JointState js;
  js.header.stamp = stamp;
  js.name = world_->jointNames();
  js.position = world_->jointPositions();
  js.velocity = world_->jointVelocities();
  js.effort = world_->jointEfforts();
  joint_state_pub_.publish(js);

  sixdof_msgs::ObjectStates objects;
  objects.header.stamp = stamp;
  objects.header.frame_id = "world";
  std::vector<geometry_msgs::TransformStamped> transforms;
  for (const std::string& name : world_->objectNames()) {
    ObjectState state;
    if (!world_->objectState(name, &state).ok()) {
      continue;
    }
    objects.name.push_back(name);
    objects.pose.push_back(toMsg(state.spec.pose));
    objects.twist.push_back(toMsg(state.twist));
    objects.attached_to.push_back(state.attached_to);
    geometry_msgs::TransformStamped t;
    t.header = objects.header;
    t.child_frame_id = name;
    t.transform.translation.x = objects.pose.back().position.x;
    t.transform.translation.y = objects.pose.back().position.y;
    t.transform.translation.z = objects.pose.back().position.z;
    t.transform.rotation = objects.pose.back().orientation;
    transforms.push_back(t);
  }
  object_state_pub_.publish(objects);
  conveyor_services_->publish(stamp);
  if (!transforms.empty()) {
    tf_broadcaster_.sendTransform(transforms);
  }
}

void SimNode::reset() {
  clock_offset_ += world_->simTime();
  world_->reset();
  controllers_->reset();
  next_publish_ = now();
  next_state_ = now();
  pace_wall_ = std::chrono::steady_clock::now();
  pace_sim_ = now();
}

void SimNode::setPaused(bool paused) {
  paused_ = paused;
  pace_wall_ = std::chrono::steady_clock::now();
  pace_sim_ = now();
}

void SimNode::run() {
  ros::CallbackQueue* queue = ros::getGlobalCallbackQueue();
  pace_wall_ = std::chrono::steady_clock::now();
  pace_sim_ = now();
  last_checkpoint_sim_ = now();
  while (ros::ok()) {
    queue->callAvailable();
    checkpointClock();
    if (paused_) {
      publishClock(false);
      std::this_thread::sleep_for(std::chrono::milliseconds(1));
      continue;
    }
    stepOnce();
    if (options_.real_time_factor > 0.0) {
      const auto due = pace_wall_ + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                                        std::chrono::duration<double>((now() - pace_sim_) / options_.real_time_factor));
      std::this_thread::sleep_until(due);
    }
  }
}

}  // namespace sixdof_sim
