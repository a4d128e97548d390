#include <gtest/gtest.h>

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
