#include "lang2manip/planning/planner_registry.hpp"

#include <functional>
#include <map>

#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/geometric/planners/est/BiEST.h>
#include <ompl/geometric/planners/est/EST.h>
#include <ompl/geometric/planners/est/ProjEST.h>
#include <ompl/geometric/planners/fmt/BFMT.h>
#include <ompl/geometric/planners/fmt/FMT.h>
#include <ompl/geometric/planners/informedtrees/ABITstar.h>
#include <ompl/geometric/planners/informedtrees/AITstar.h>
#include <ompl/geometric/planners/informedtrees/BITstar.h>
#include <ompl/geometric/planners/kpiece/BKPIECE1.h>
#include <ompl/geometric/planners/kpiece/KPIECE1.h>
#include <ompl/geometric/planners/kpiece/LBKPIECE1.h>
#include <ompl/geometric/planners/pdst/PDST.h>
#include <ompl/geometric/planners/prm/LazyPRM.h>
#include <ompl/geometric/planners/prm/LazyPRMstar.h>
#include <ompl/geometric/planners/prm/PRM.h>
#include <ompl/geometric/planners/prm/PRMstar.h>
#include <ompl/geometric/planners/prm/SPARS.h>
#include <ompl/geometric/planners/prm/SPARStwo.h>
#include <ompl/geometric/planners/rlrt/BiRLRT.h>
#include <ompl/geometric/planners/rlrt/RLRT.h>
#include <ompl/geometric/planners/rrt/BiTRRT.h>
#include <ompl/geometric/planners/rrt/InformedRRTstar.h>
#include <ompl/geometric/planners/rrt/LBTRRT.h>
#include <ompl/geometric/planners/rrt/LazyRRT.h>
#include <ompl/geometric/planners/rrt/RRT.h>
#include <ompl/geometric/planners/rrt/RRTConnect.h>
#include <ompl/geometric/planners/rrt/RRTXstatic.h>
#include <ompl/geometric/planners/rrt/RRTsharp.h>
#include <ompl/geometric/planners/rrt/RRTstar.h>
#include <ompl/geometric/planners/rrt/SORRTstar.h>
#include <ompl/geometric/planners/rrt/TRRT.h>
#include <ompl/geometric/planners/rrt/pRRT.h>
#include <ompl/geometric/planners/sbl/SBL.h>
#include <ompl/geometric/planners/sbl/pSBL.h>
#include <ompl/geometric/planners/stride/STRIDE.h>

#include "lang2manip/core/error.hpp"
#include "lang2manip/planning/motion_planner.hpp"

namespace lang2manip {
namespace {

namespace og = ompl::geometric;
using Factory = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr&)>;

template <typename PlannerType>
Factory factory() {
  return [](const ompl::base::SpaceInformationPtr& si) {
    return std::make_shared<PlannerType>(si);
  };
}

/// How to create each planner of the catalog, by its canonical name.
const std::map<std::string, Factory>& factories() {
  static const std::map<std::string, Factory> planners = {
      {"RRTConnect", factory<og::RRTConnect>()},
      {"RRT", factory<og::RRT>()},
      {"RRTstar", factory<og::RRTstar>()},
      {"InformedRRTstar", factory<og::InformedRRTstar>()},
      {"SORRTstar", factory<og::SORRTstar>()},
      {"RRTsharp", factory<og::RRTsharp>()},
      {"RRTXstatic", factory<og::RRTXstatic>()},
      {"LazyRRT", factory<og::LazyRRT>()},
      {"TRRT", factory<og::TRRT>()},
      {"BiTRRT", factory<og::BiTRRT>()},
      {"LBTRRT", factory<og::LBTRRT>()},
      {"pRRT", factory<og::pRRT>()},
      {"BITstar", factory<og::BITstar>()},
      {"ABITstar", factory<og::ABITstar>()},
      {"AITstar", factory<og::AITstar>()},
      {"PRM", factory<og::PRM>()},
      {"PRMstar", factory<og::PRMstar>()},
      {"LazyPRM", factory<og::LazyPRM>()},
      {"LazyPRMstar", factory<og::LazyPRMstar>()},
      {"SPARS", factory<og::SPARS>()},
      {"SPARStwo", factory<og::SPARStwo>()},
      {"KPIECE1", factory<og::KPIECE1>()},
      {"BKPIECE1", factory<og::BKPIECE1>()},
      {"LBKPIECE1", factory<og::LBKPIECE1>()},
      {"EST", factory<og::EST>()},
      {"BiEST", factory<og::BiEST>()},
      {"ProjEST", factory<og::ProjEST>()},
      {"SBL", factory<og::SBL>()},
      {"pSBL", factory<og::pSBL>()},
      {"STRIDE", factory<og::STRIDE>()},
      {"PDST", factory<og::PDST>()},
      {"FMT", factory<og::FMT>()},
      {"BFMT", factory<og::BFMT>()},
      {"RLRT", factory<og::RLRT>()},
      {"BiRLRT", factory<og::BiRLRT>()},
  };
  return planners;
}

}  // namespace

ompl::base::PlannerPtr createOmplPlanner(const std::string& canonicalName,
                                         const ompl::base::SpaceInformationPtr& si) {
  routeOmplMessagesToLog();
  const std::string name = canonicalPlannerName(canonicalName);
  const auto found = factories().find(name);
  if (found == factories().end()) throw NotSupportedError("planner \"" + name + "\" has no OMPL factory");
  return found->second(si);
}

std::vector<std::string> omplParameterNames(const std::string& canonicalName) {
  auto space = std::make_shared<ompl::base::RealVectorStateSpace>(2);
  space->setBounds(0.0, 1.0);
  auto si = std::make_shared<ompl::base::SpaceInformation>(space);
  std::vector<std::string> names;
  createOmplPlanner(canonicalName, si)->params().getParamNames(names);
  return names;
}

}  // namespace lang2manip
