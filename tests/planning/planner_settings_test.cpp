#include <gtest/gtest.h>

#include <string>
#include <utility>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "model/model_test_support.hpp"
#include "lang2manip/planning/planner_registry.hpp"
#include "lang2manip/planning/planner_settings.hpp"

namespace lang2manip {
namespace {

TEST(PlannerRegistry, CoversOmplGeometricPlannersAndKauthamNames) {
  const std::vector<std::string> names = plannerNames();
  for (const char* expected : {"RRT", "RRTConnect", "RRTstar", "InformedRRTstar", "BITstar", "ABITstar",
                               "AITstar", "LazyRRT", "PRM", "PRMstar", "LazyPRM", "LazyPRMstar", "SPARS",
                               "SPARStwo", "KPIECE1", "BKPIECE1", "LBKPIECE1", "EST", "BiEST", "ProjEST",
                               "SBL", "STRIDE", "FMT", "BFMT", "TRRT", "BiTRRT", "LBTRRT", "pRRT", "pSBL"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
  EXPECT_EQ(canonicalPlannerName("omplRRTConnect"), "RRTConnect");
  EXPECT_EQ(canonicalPlannerName("omplRRTStar"), "RRTstar");
  EXPECT_EQ(canonicalPlannerName("omplKPIECE"), "KPIECE1");
  EXPECT_EQ(canonicalPlannerName("omplPRM"), "PRM");
  EXPECT_EQ(canonicalPlannerName("RRT*"), "RRTstar");
  EXPECT_EQ(canonicalPlannerName("rrtconnect"), "RRTConnect");
}

TEST(PlannerRegistry, UnknownAndUnsupportedPlannersAreClearErrors) {
  const std::string unknown = test::errorMessage([] { (void)canonicalPlannerName("RRTFast"); });
  EXPECT_NE(unknown.find("unknown planner \"RRTFast\"; valid planners: RRTConnect, RRT,"), std::string::npos)
      << unknown;
  EXPECT_THROW((void)canonicalPlannerName("omplconstr"), NotSupportedError);
  EXPECT_NE(test::errorMessage([] { (void)canonicalPlannerName("omplcRRTcar"); }).find("control-based"),
            std::string::npos);
}

TEST(PlannerRegistry, KauthamPlannersWeDoNotHaveSayWhatTheyNeed) {
  for (const auto& [name, needs] : std::vector<std::pair<std::string, std::string>>{
           {"KPIECECarPlanner", "Open Dynamics Engine"},
           {"KnowledgeOrientedKPIECE2DPlanner", "Open Dynamics Engine"},
           {"HFPlanner", "grid discretization"},
           {"NF1Planner", "grid discretization"},
           {"omplFOSRRT", "synergy tree"},
           {"PRM Hand IROS", "robot-hand sampling"},
           {"omplcSSTf16", "control-based"}}) {
    const std::string message = test::errorMessage([&] { (void)canonicalPlannerName(name); });
    EXPECT_NE(message.find("planner \"" + name + "\" is not supported: it needs"), std::string::npos) << message;
    EXPECT_NE(message.find(needs), std::string::npos) << message;
    EXPECT_THROW((void)canonicalPlannerName(name), NotSupportedError);
  }
  EXPECT_EQ(canonicalPlannerName("omplEST"), "EST");
  EXPECT_EQ(canonicalPlannerName("omplBKPIECE"), "BKPIECE1");
}

TEST(PlannerSettings, KauthamOnlyParametersSetTheirOmplCounterpartOrSayTheyHaveNoEffect) {
  PlannerSettings prm;
  prm.setPlanner("omplPRM");
  prm.setParameter("DistanceThreshold", "0.5");
  prm.setParameter("MinGrowTime", "0.2");
  prm.setParameter("Sampler 0(r) 1(h) 2(sdk) 3(g)", "0");  // uniform random: what lang2manip does
  prm.setParameter("MaxNearestNeighbors", "7");
  ASSERT_EQ(prm.ignoredParameters().size(), 2u);
  EXPECT_EQ(prm.ignoredParameters()[0].name, "DistanceThreshold");
  EXPECT_EQ(prm.ignoredParameters()[0].value, "0.5");
  EXPECT_NE(prm.ignoredParameters()[0].reason.find("max_nearest_neighbors"), std::string::npos);
  prm.setParameter("Sampler 0(r) 1(h) 2(sdk) 3(g)", "1");  // Halton: not implemented
  EXPECT_EQ(prm.ignoredParameters().size(), 3u);
  prm.setParameter("DistanceThreshold", "0.7");  // set again: listed once, with the new value
  EXPECT_EQ(prm.ignoredParameters().size(), 3u);
  EXPECT_EQ(prm.omplParameters(), (std::vector<std::pair<std::string, std::string>>{{"max_nearest_neighbors", "7"}}));
  // A Kautham value is a number; a parameter of another planner is still unknown.
  EXPECT_THROW(prm.setParameter("BounceSteps", "many"), InputError);
  EXPECT_THROW(prm.setParameter("maxNumSteps", "4"), InputError);
  prm.setPlanner("PRM");
  EXPECT_TRUE(prm.ignoredParameters().empty());

  PlannerSettings kpiece;
  kpiece.setPlanner("omplKPIECE");
  kpiece.setParameter("failedExpansionScoreFactor", "0.4");
  kpiece.setParameter("maxNumSteps", "4");
  EXPECT_EQ(kpiece.omplParameters(),
            (std::vector<std::pair<std::string, std::string>>{{"failed_expansion_score_factor", "0.4"}}));
  EXPECT_EQ(kpiece.ignoredParameters().size(), 1u);

  PlannerSettings star;
  star.setPlanner("omplRRTStar");
  star.setParameter("DelayCC (0/1)", "1");
  star.setParameter("K-Neigh Factor", "1.5");
  star.setParameter("Optimize none(0)/dist(1)/clear(2)/PMD(3)", "1");
  star.setParameter("_Range", "0.2");
  EXPECT_EQ(star.omplParameters(), (std::vector<std::pair<std::string, std::string>>{
                                       {"delay_collision_checking", "1"}, {"rewire_factor", "1.5"}, {"range", "0.2"}}));
  EXPECT_TRUE(star.ignoredParameters().empty());
  star.setParameter("Optimize none(0)/dist(1)/clear(2)/PMD(3)", "2");
  EXPECT_EQ(star.ignoredParameters().size(), 1u);
}

TEST(PlannerSettings, ValidStateSamplerByNameOrByKauthamsSamplerNumber) {
  PlannerSettings settings;
  EXPECT_EQ(settings.validStateSampler(), ValidStateSampler::kUniform);
  settings.setParameter("_Valid State Sampler", "obstacle_based");
  EXPECT_EQ(settings.validStateSampler(), ValidStateSampler::kObstacleBased);
  settings.setParameter("_Valid State Sampler", "bridge_test");
  EXPECT_EQ(validStateSamplerName(settings.validStateSampler()), "bridge_test");
  try {
    settings.setParameter("_Valid State Sampler", "halton");
    ADD_FAILURE() << "accepted an unknown sampler";
  } catch (const InputError& error) {
    EXPECT_NE(std::string(error.what()).find("uniform, gaussian, obstacle_based, bridge_test"), std::string::npos)
        << error.what();
  }
  PlannerSettings prm;
  prm.setPlanner("omplPRM");
  prm.setParameter("Sampler 0(r) 1(h) 2(sdk) 3(g)", "3");  // Kautham's Gaussian sampler
  EXPECT_EQ(prm.validStateSampler(), ValidStateSampler::kGaussian);
  EXPECT_TRUE(prm.ignoredParameters().empty());
  prm.setParameter("Sampler 0(r) 1(h) 2(sdk) 3(g) 4(gl)", "4");
  EXPECT_EQ(prm.validStateSampler(), ValidStateSampler::kGaussian);
  prm.setParameter("Sampler 0(r) 1(h) 2(sdk) 3(g)", "0");
  EXPECT_EQ(prm.validStateSampler(), ValidStateSampler::kUniform);
  prm.setParameter("Sampler 0(r) 1(h) 2(sdk) 3(g)", "2");  // SDK: not implemented, said so
  EXPECT_EQ(prm.validStateSampler(), ValidStateSampler::kUniform);
  ASSERT_EQ(prm.ignoredParameters().size(), 1u);
  EXPECT_NE(prm.ignoredParameters()[0].reason.find("SDK"), std::string::npos);
}

TEST(PlannerSettings, CommonParametersUnderKauthamNames) {
  PlannerSettings settings;
  settings.setPlanner("omplRRTConnect");
  settings.setParameter("_Max Planning Time", "2.5");
  settings.setParameter("_Simplify Solution", "1");
  settings.setParameter("_Incremental (0/1)", "1");
  settings.setParameter("_Speed Factor", "10");
  settings.setParameter("Speed Factor", "1");  // Kautham demos misspell it this way
  settings.setParameter("_Path Drawn (0/1)", "0");
  EXPECT_EQ(settings.planner(), "RRTConnect");
  EXPECT_DOUBLE_EQ(settings.maxPlanningTime(), 2.5);
  EXPECT_EQ(settings.simplifyLevel(), SimplifyLevel::kSmooth);
  EXPECT_TRUE(settings.incremental());
}

TEST(PlannerSettings, PlannerParametersUnderOmplAndKauthamNames) {
  PlannerSettings settings;
  settings.setPlanner("RRT");
  settings.setParameter("Range", "0.1");
  settings.setParameter("Goal Bias", "0.05");
  settings.setParameter("goal_bias", "0.1");
  ASSERT_EQ(settings.omplParameters().size(), 3u);
  EXPECT_EQ(settings.omplParameters()[1], (std::pair<std::string, std::string>{"goal_bias", "0.05"}));
  settings.setPlanner("PRM");
  EXPECT_TRUE(settings.omplParameters().empty());
  settings.setParameter("MaxNearestNeighbors", "8");
  EXPECT_EQ(settings.omplParameters()[0].first, "max_nearest_neighbors");
}

TEST(PlannerSettingsBadInput, UnknownNamesWrongTypesAndRanges) {
  PlannerSettings settings;
  settings.setPlanner("RRT");
  const std::string unknown = test::errorMessage([&] { settings.setParameter("Cell Size", "0.1"); });
  EXPECT_NE(unknown.find("unknown parameter \"Cell Size\" for planner RRT; valid parameters: "
                         "_Max Planning Time"),
            std::string::npos)
      << unknown;
  EXPECT_NE(unknown.find("goal_bias"), std::string::npos);
  EXPECT_NE(test::errorMessage([&] { settings.setParameter("Goal Bias", "lots"); }).find("\"Goal Bias\""),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { settings.setParameter("Goal Bias", "1.5"); }).find("outside its range"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { settings.setParameter("_Max Planning Time", "0"); }).find("positive"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { settings.setParameter("_Max Planning Time", "nan"); }).find("Max Planning Time"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { settings.setParameter("_Simplify Solution", "3"); }).find("0 (none)"),
            std::string::npos);
  EXPECT_NE(test::errorMessage([&] { settings.setParameter("_Incremental (0/1)", "maybe"); }).find("Incremental"),
            std::string::npos);
  EXPECT_THROW(settings.setPlanner("nope"), InputError);
  EXPECT_EQ(settings.planner(), "RRT");
}

}  // namespace
}  // namespace lang2manip
