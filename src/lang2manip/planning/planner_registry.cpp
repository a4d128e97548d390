#include "lang2manip/planning/planner_registry.hpp"

#include <algorithm>
#include <cctype>
#include <functional>

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

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/planning/motion_planner.hpp"

namespace lang2manip {
namespace {

namespace og = ompl::geometric;
using Factory = std::function<ompl::base::PlannerPtr(const ompl::base::SpaceInformationPtr&)>;

struct RegisteredPlanner {
  PlannerDescription description;
  Factory create;
};

template <typename PlannerType>
Factory factory() {
  return [](const ompl::base::SpaceInformationPtr& si) {
    return std::make_shared<PlannerType>(si);
  };
}

const std::vector<RegisteredPlanner>& registry() {
  static const std::vector<RegisteredPlanner> planners = {
      {{"RRTConnect", {"omplRRTConnect", "omplDefault", "RRT-Connect"}, false, false}, factory<og::RRTConnect>()},
      {{"RRT", {"omplRRT"}, false, false}, factory<og::RRT>()},
      {{"RRTstar", {"omplRRTStar", "RRT*"}, true, false}, factory<og::RRTstar>()},
      {{"InformedRRTstar", {"Informed RRT*", "InformedRRT*"}, true, false}, factory<og::InformedRRTstar>()},
      {{"SORRTstar", {"SORRT*"}, true, false}, factory<og::SORRTstar>()},
      {{"RRTsharp", {"RRT#"}, true, false}, factory<og::RRTsharp>()},
      {{"RRTXstatic", {"RRTX"}, true, false}, factory<og::RRTXstatic>()},
      {{"LazyRRT", {"omplLazyRRT"}, false, false}, factory<og::LazyRRT>()},
      {{"TRRT", {"omplTRRT", "T-RRT"}, false, false}, factory<og::TRRT>()},
      {{"BiTRRT", {"omplTRRTConnect", "Bi-TRRT"}, false, false}, factory<og::BiTRRT>()},
      {{"LBTRRT", {}, true, false, true}, factory<og::LBTRRT>()},
      {{"pRRT", {"omplpRRT"}, false, true}, factory<og::pRRT>()},
      {{"BITstar", {"BIT*"}, true, false}, factory<og::BITstar>()},
      {{"ABITstar", {"ABIT*"}, true, false}, factory<og::ABITstar>()},
      {{"AITstar", {"AIT*"}, true, false}, factory<og::AITstar>()},
      {{"PRM", {"omplPRM"}, false, false}, factory<og::PRM>()},
      {{"PRMstar", {"PRM*"}, true, false}, factory<og::PRMstar>()},
      // A 0.5 rad connection radius leaves a 7-DOF roadmap too sparse to cross a desk scene.
      {{"LazyPRM", {}, false, false, false, false}, factory<og::LazyPRM>()},
      {{"LazyPRMstar", {"LazyPRM*"}, true, false}, factory<og::LazyPRMstar>()},
      {{"SPARS", {}, true, false}, factory<og::SPARS>()},
      {{"SPARStwo", {"SPARS2"}, true, false}, factory<og::SPARStwo>()},
      {{"KPIECE1", {"omplKPIECE", "KPIECE"}, false, false}, factory<og::KPIECE1>()},
      {{"BKPIECE1", {"BKPIECE", "omplBKPIECE"}, false, false}, factory<og::BKPIECE1>()},
      {{"LBKPIECE1", {"LBKPIECE"}, false, false}, factory<og::LBKPIECE1>()},
      {{"EST", {"omplEST"}, false, false}, factory<og::EST>()},
      {{"BiEST", {}, false, false}, factory<og::BiEST>()},
      {{"ProjEST", {"omplProjEST"}, false, false}, factory<og::ProjEST>()},
      {{"SBL", {"omplSBL"}, false, false}, factory<og::SBL>()},
      {{"pSBL", {}, false, true, false, true, true}, factory<og::pSBL>()},
      {{"STRIDE", {}, false, false}, factory<og::STRIDE>()},
      {{"PDST", {}, false, false}, factory<og::PDST>()},
      {{"FMT", {"FMT*"}, true, false}, factory<og::FMT>()},
      {{"BFMT", {"BFMT*"}, true, false}, factory<og::BFMT>()},
      {{"RLRT", {}, false, false, false, false}, factory<og::RLRT>()},
      {{"BiRLRT", {}, false, false, false, false}, factory<og::BiRLRT>()},
  };
  return planners;
}

constexpr const char* kOde = "physics-based planning with the Open Dynamics Engine (Kautham's ODE planners)";
constexpr const char* kGrid = "a grid discretization of the controls (Kautham's IOC grid planners)";
constexpr const char* kSynergy = "a synergy tree or PCA data of a hand (Kautham's FOS/PCA planners)";
constexpr const char* kHand = "Kautham's robot-hand sampling (its own PRM variants for hands)";

// Planners named by Kautham or OMPL that lang2manip cannot run, with what they would need.
const std::vector<std::pair<std::string, std::string>>& unsupportedKauthamPlanners() {
  static const std::vector<std::pair<std::string, std::string>> planners = {
      {"omplconstr", "constrained planning (OMPL ProjectedStateSpace with <Constraint>s)"},
      {"omplTSRRT", "a task-space projection"},
      {"omplLazyTRRT", "Kautham's own LazyTRRT implementation"},
      {"omplRRTStarPMD", "Kautham's synergy (PMD) sampling"},
      {"omplRRTConnectEUROC", "Kautham's EUROC-specific planner"},
      {"omplcRRT", "control-based planning (ompl::control)"},
      {"omplcRRTcar", "control-based planning (ompl::control)"},
      {"omplcSSTcar", "control-based planning (ompl::control)"},
      {"omplcRRTdualdrive", "control-based planning (ompl::control)"},
      {"omplcSSTdualdrive", "control-based planning (ompl::control)"},
      {"omplcRRTf16", "control-based planning (ompl::control)"},
      {"omplcSSTf16", "control-based planning (ompl::control)"},
      {"KPIECE2DPlanner", kOde},
      {"KPIECECarPlanner", kOde},
      {"KPIECEChainPlanner", kOde},
      {"RRT2DPlanner", kOde},
      {"Syclop2DPlanner", kOde},
      {"KnowledgeOrientedKPIECE2DPlanner", kOde},
      {"KnowledgeOrientedRRT2DPlanner", kOde},
      {"KnowledgeOrientedSyclop2DPlanner", kOde},
      {"omplODERRTPlanner", kOde},
      {"omplODEKPIECEPlanner", kOde},
      {"MyGridPlanner", kGrid},
      {"NF1Planner", kGrid},
      {"HFPlanner", kGrid},
      {"GUIBROgrid", kGrid},
      {"omplFOSRRT", kSynergy},
      {"omplFOSTRRT", kSynergy},
      {"omplFOSRRTConnect", kSynergy},
      {"omplFOSTRRTConnect", kSynergy},
      {"omplFOSVFRRT", kSynergy},
      {"omplMyFOSVFRRT", kSynergy},
      {"omplFOSBKPIECE1", kSynergy},
      {"omplFOSLBKPIECE1", kSynergy},
      {"omplFOSKPIECE1", kSynergy},
      {"omplFOSRRTStar", kSynergy},
      {"omplPCARRT", kSynergy},
      {"omplMyPCARRT", kSynergy},
      {"PRMPCA HandArm", kSynergy},
      {"PRM Hand IROS", kHand},
      {"PRM Hand ICRA", kHand},
      {"PRMAURO HandArm", kHand},
      {"PRM RobotHand-Const ICRA", kHand},
      {"MyPlanner", "Kautham's own example planner (MyPlanner), which is not part of OMPL"},
      {"MyPRMPlanner", "Kautham's own example planner (MyPRMPlanner), which is not part of OMPL"},
      {"LazyLBTRRT", "a working OMPL build: Debian's OMPL 1.5.2 aborts in it (assertion in "
                     "LPAstarOnGraph::removeEdge)"},
      {"SST", "tuning for kinodynamic problems: with its default radii its tree stops growing on "
              "joint-space problems (28 vertices in 5 s on a 2-DOF test arm)"},
  };
  return planners;
}

const RegisteredPlanner* findPlanner(const std::string& name, bool caseSensitive) {
  const auto matches = [&](const std::string& candidate) {
    return caseSensitive ? candidate == name : lowercase(candidate) == lowercase(name);
  };
  for (const RegisteredPlanner& planner : registry()) {
    if (matches(planner.description.name)) return &planner;
    for (const std::string& alias : planner.description.aliases) {
      if (matches(alias)) return &planner;
    }
  }
  return nullptr;
}

std::string joinedPlannerNames() {
  std::string names;
  for (const RegisteredPlanner& planner : registry()) {
    names += (names.empty() ? "" : ", ") + planner.description.name;
  }
  return names;
}

}  // namespace

const std::vector<PlannerDescription>& plannerDescriptions() {
  static const std::vector<PlannerDescription> descriptions = [] {
    std::vector<PlannerDescription> result;
    for (const RegisteredPlanner& planner : registry()) result.push_back(planner.description);
    return result;
  }();
  return descriptions;
}

const PlannerDescription& plannerDescription(const std::string& name) {
  return findPlanner(canonicalPlannerName(name), true)->description;
}

std::vector<std::string> plannerNames() {
  std::vector<std::string> names;
  for (const RegisteredPlanner& planner : registry()) names.push_back(planner.description.name);
  return names;
}

std::string canonicalPlannerName(const std::string& name) {
  const RegisteredPlanner* planner = findPlanner(name, true);
  if (planner == nullptr) planner = findPlanner(name, false);
  if (planner != nullptr) return planner->description.name;
  for (const auto& [kautham, needs] : unsupportedKauthamPlanners()) {
    if (lowercase(kautham) == lowercase(name)) {
      throw NotSupportedError("planner \"" + name + "\" is not supported: it needs " + needs +
                              "; geometric planners: " + joinedPlannerNames());
    }
  }
  throw InputError("unknown planner \"" + name + "\"; valid planners: " + joinedPlannerNames() +
                   " (Kautham's omplRRT, omplRRTConnect, omplRRTStar, omplPRM, omplKPIECE, ... "
                   "are accepted too)");
}

ompl::base::PlannerPtr createOmplPlanner(const std::string& canonicalName,
                                         const ompl::base::SpaceInformationPtr& si) {
  routeOmplMessagesToLog();
  const RegisteredPlanner* planner = findPlanner(canonicalPlannerName(canonicalName), true);
  return planner->create(si);
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
