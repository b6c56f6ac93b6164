#include <malloc.h>
#include <ompl/util/Console.h>
#include <ros/ros.h>

#include <cstdlib>

#include "sixdof_planning/move_group_node.h"

namespace {

// OMPL's messages into rosconsole (logger ros.sixdof_planning.ompl). Its info lines come with every plan
// ("RRTConnect: Created 5 states ...") and go to debug; OMPL formats none of them unless that logger is at debug
// level when move_group starts.
class OmplToRosconsole : public ompl::msg::OutputHandler {
 public:
  void log(const std::string& text, ompl::msg::LogLevel level, const char* /*filename*/, int /*line*/) override {
    switch (level) {
      case ompl::msg::LOG_ERROR:
        ROS_ERROR_STREAM_NAMED("ompl", text);
        break;
      case ompl::msg::LOG_WARN:
        ROS_WARN_STREAM_NAMED("ompl", text);
        break;
      default:
        ROS_DEBUG_STREAM_NAMED("ompl", text);
        break;
    }
  }
};

void routeOmplMessages() {
  static OmplToRosconsole handler;
  ompl::msg::useOutputHandler(&handler);
  // A debug line's arguments are evaluated only when its logger is at debug level.
  bool debug = false;
  ROS_DEBUG_STREAM_NAMED("ompl", "OMPL's messages at debug level" << [&debug] {
    debug = true;
    return "";
  }());
  ompl::msg::setLogLevel(debug ? ompl::msg::LOG_DEBUG : ompl::msg::LOG_WARN);
}

// glibc's malloc gives threads arenas of their own (up to 8 per core) and keeps the memory each arena once held. The
// TCPROS server serves each client connection on a thread of its own: with glibc's default move_group grew by 2.9-3.6
// MB over a 500-trial soak before levelling off, with two arenas by 0.4 MB. Two, unless the environment sets
// MALLOC_ARENA_MAX.
void capMallocArenas() {
  if (std::getenv("MALLOC_ARENA_MAX") == nullptr) mallopt(M_ARENA_MAX, 2);
}

}  // namespace

int main(int argc, char** argv) {
  capMallocArenas();  // before any thread starts
  ros::init(argc, argv, "move_group");
  ros::NodeHandle nh;
  routeOmplMessages();
  ros::NodeHandle private_nh("~");
  std::unique_ptr<sixdof_planning::MoveGroupNode> node;
  try {
    node = std::make_unique<sixdof_planning::MoveGroupNode>(nh, private_nh);
  } catch (const sixdof_planning::ConfigError& e) {
    ROS_FATAL_STREAM("move_group: bad configuration: " << e.what());
    return 1;
  } catch (const std::runtime_error& e) {  // a service that cannot listen or register
    ROS_FATAL_STREAM("move_group: " << e.what());
    return 1;
  }
  // Services are served by threads of their own; goals and topics share these (executions block their action's
  // thread).
  node->start();
  ros::AsyncSpinner spinner(4);
  spinner.start();
  ROS_INFO("move_group: ready");
  ros::waitForShutdown();
  return 0;
}
