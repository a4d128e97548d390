#include "lang2manip/planning/planner_catalog.hpp"

#include <utility>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"

namespace lang2manip {
namespace {

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

const PlannerDescription* findPlanner(const std::string& name, bool caseSensitive) {
  const auto matches = [&](const std::string& candidate) {
    return caseSensitive ? candidate == name : lowercase(candidate) == lowercase(name);
  };
  for (const PlannerDescription& planner : plannerDescriptions()) {
    if (matches(planner.name)) return &planner;
    for (const std::string& alias : planner.aliases) {
      if (matches(alias)) return &planner;
    }
  }
  return nullptr;
}

std::string joinedPlannerNames() {
  std::string names;
  for (const PlannerDescription& planner : plannerDescriptions()) names += (names.empty() ? "" : ", ") + planner.name;
  return names;
}

}  // namespace

const std::vector<PlannerDescription>& plannerDescriptions() {
  static const std::vector<PlannerDescription> planners = {
      {"RRTConnect", {"omplRRTConnect", "omplDefault", "RRT-Connect"}, false, false},
      {"RRT", {"omplRRT"}, false, false},
      {"RRTstar", {"omplRRTStar", "RRT*"}, true, false},
      {"InformedRRTstar", {"Informed RRT*", "InformedRRT*"}, true, false},
      {"SORRTstar", {"SORRT*"}, true, false},
      {"RRTsharp", {"RRT#"}, true, false},
      {"RRTXstatic", {"RRTX"}, true, false},
      {"LazyRRT", {"omplLazyRRT"}, false, false},
      {"TRRT", {"omplTRRT", "T-RRT"}, false, false},
      {"BiTRRT", {"omplTRRTConnect", "Bi-TRRT"}, false, false},
      {"LBTRRT", {}, true, false, true},
      {"pRRT", {"omplpRRT"}, false, true},
      {"BITstar", {"BIT*"}, true, false},
      {"ABITstar", {"ABIT*"}, true, false},
      {"AITstar", {"AIT*"}, true, false},
      {"PRM", {"omplPRM"}, false, false},
      {"PRMstar", {"PRM*"}, true, false},
      // A 0.5 rad connection radius leaves a 7-DOF roadmap too sparse to cross a desk scene.
      {"LazyPRM", {}, false, false, false, false},
      {"LazyPRMstar", {"LazyPRM*"}, true, false},
      {"SPARS", {}, true, false},
      {"SPARStwo", {"SPARS2"}, true, false},
      {"KPIECE1", {"omplKPIECE", "KPIECE"}, false, false},
      {"BKPIECE1", {"BKPIECE", "omplBKPIECE"}, false, false},
      {"LBKPIECE1", {"LBKPIECE"}, false, false},
      {"EST", {"omplEST"}, false, false},
      {"BiEST", {}, false, false},
      {"ProjEST", {"omplProjEST"}, false, false},
      {"SBL", {"omplSBL"}, false, false},
      {"pSBL", {}, false, true, false, true, true},
      {"STRIDE", {}, false, false},
      {"PDST", {}, false, false},
      {"FMT", {"FMT*"}, true, false},
      {"BFMT", {"BFMT*"}, true, false},
      {"RLRT", {}, false, false, false, false},
      {"BiRLRT", {}, false, false, false, false},
  };
  return planners;
}

const PlannerDescription& plannerDescription(const std::string& name) {
  return *findPlanner(canonicalPlannerName(name), true);
}

std::vector<std::string> plannerNames() {
  std::vector<std::string> names;
  for (const PlannerDescription& planner : plannerDescriptions()) names.push_back(planner.name);
  return names;
}

std::string canonicalPlannerName(const std::string& name) {
  const PlannerDescription* planner = findPlanner(name, true);
  if (planner == nullptr) planner = findPlanner(name, false);
  if (planner != nullptr) return planner->name;
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

}  // namespace lang2manip
