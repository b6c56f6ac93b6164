#include "ompl_setup.h"

#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>

namespace sixdof_core {
namespace detail {

namespace og = ompl::geometric;

double shortestAngle(double from, double to) {
  double d = std::fmod(to - from, kTwoPi);
  if (d > M_PI) d -= kTwoPi;
  if (d < -M_PI) d += kTwoPi;
  return d;
}

double jointDelta(const JointBounds& joint, double from, double to) {
  return joint.continuous ? shortestAngle(from, to) : to - from;
}

namespace {

template <typename T>
ob::PlannerPtr makePlanner(const ob::SpaceInformationPtr& si) {
  return std::make_shared<T>(si);
}

}  // namespace

const std::map<std::string, PlannerFactory>& plannerFactories() {
  static const std::map<std::string, PlannerFactory> factories = {
      {"BiEST", makePlanner<og::BiEST>},         {"BiTRRT", makePlanner<og::BiTRRT>},
      {"BKPIECE1", makePlanner<og::BKPIECE1>},   {"EST", makePlanner<og::EST>},
      {"KPIECE1", makePlanner<og::KPIECE1>},     {"LazyPRM", makePlanner<og::LazyPRM>},
      {"LBKPIECE1", makePlanner<og::LBKPIECE1>}, {"PRM", makePlanner<og::PRM>},
      {"PRMstar", makePlanner<og::PRMstar>},     {"RRT", makePlanner<og::RRT>},
      {"RRTConnect", makePlanner<og::RRTConnect>}, {"RRTstar", makePlanner<og::RRTstar>},
      {"SBL", makePlanner<og::SBL>},             {"TRRT", makePlanner<og::TRRT>},
  };
  return factories;
}

std::string canonicalPlannerId(const std::string& id) {
  static const std::string kMoveItSuffix = "kConfigDefault";
  if (id.size() > kMoveItSuffix.size() && id.compare(id.size() - kMoveItSuffix.size(), std::string::npos,
                                                     kMoveItSuffix) == 0) {
    return id.substr(0, id.size() - kMoveItSuffix.size());
  }
  return id;
}

}  // namespace detail
}  // namespace sixdof_core
