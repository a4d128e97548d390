#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <sstream>

#include "lang2manip/core/error.hpp"
#include "lang2manip/planning/benchmark_log.hpp"
#include "lang2manip/planning/trajectory.hpp"
#include "planning_test_support.hpp"

namespace lang2manip::test {
namespace {

TEST(TimeParameterization, RestToRestSegmentsWithinTheLimits) {
  const auto space = planarArmSpace();
  std::vector<VectorX> path{planarStart(), (VectorX(2) << 1.2, 2.0).finished(), planarGoal()};
  const JointTrajectory trajectory = timeParameterize(*space, path);
  EXPECT_EQ(checkTrajectoryLimits(*space, trajectory), "");
  EXPECT_TRUE(trajectory.points.front().positions.isApprox(planarStart()));
  EXPECT_TRUE(trajectory.points.back().positions.isApprox(planarGoal()));
  EXPECT_TRUE(trajectory.points.back().velocities.isZero(1e-12));
  // The first segment moves the elbow 2 rad at 2 rad/s and 4 rad/s^2: 0.5 s ramps, 0.5 s cruise.
  bool foundWaypoint = false;
  for (const TrajectoryPoint& point : trajectory.points) {
    if (std::abs(point.time - 1.5) < 1e-9) {
      foundWaypoint = true;
      EXPECT_TRUE(point.positions.isApprox(path[1]));
      EXPECT_TRUE(point.velocities.isZero(1e-9));
    }
  }
  EXPECT_TRUE(foundWaypoint);
  double peak = 0.0;
  for (const TrajectoryPoint& point : trajectory.points) peak = std::max(peak, point.velocities.cwiseAbs().maxCoeff());
  EXPECT_NEAR(peak, 2.0, 1e-9);
}

TEST(TimeParameterization, LimitCheckCatchesAViolation) {
  const auto space = planarArmSpace();
  JointTrajectory trajectory = timeParameterize(*space, {planarStart(), planarGoal()});
  trajectory.points[1].velocities[0] = 10.0;
  EXPECT_NE(checkTrajectoryLimits(*space, trajectory).find("planar/shoulder velocity 10"), std::string::npos);
  trajectory.points[1].time = -1.0;
  EXPECT_NE(checkTrajectoryLimits(*space, trajectory).find("time does not increase"), std::string::npos);
}

TEST(TimeParameterization, BadInput) {
  const auto space = planarArmSpace();
  EXPECT_THROW((void)timeParameterize(*space, {}), InputError);
  EXPECT_THROW((void)timeParameterize(*space, {VectorX::Zero(3)}), InputError);
  TimeParameterizationOptions options;
  options.velocityScaling = 0.0;
  EXPECT_THROW((void)timeParameterize(*space, {planarStart()}, options), InputError);
  options.velocityScaling = 1.0;
  options.accelerationScaling = 1.5;
  EXPECT_THROW((void)timeParameterize(*space, {planarStart()}, options), InputError);
}

TEST(TrajectoryFiles, JointTrajectoryJsonAndCsv) {
  const auto space = planarArmSpace();
  const JointTrajectory trajectory = timeParameterize(*space, {planarStart(), planarGoal()});
  const nlohmann::json json = trajectoryToJson(trajectory);
  EXPECT_EQ(json["joint_names"], (nlohmann::json{"shoulder", "elbow"})) << "the URDF's names";
  EXPECT_EQ(trajectoryJointRobots(trajectory), (nlohmann::json{"planar", "planar"}));
  for (const auto& [key, value] : json.items()) {
    EXPECT_TRUE(key == "joint_names" || key == "points") << key << ": not a field of trajectory_msgs/JointTrajectory";
  }
  const nlohmann::json& last = json["points"].back();
  EXPECT_EQ(last["positions"].size(), 2u);
  const double seconds = last["time_from_start"]["sec"].get<double>() + last["time_from_start"]["nanosec"].get<double>() * 1e-9;
  EXPECT_NEAR(seconds, trajectory.duration(), 1e-9);
  const std::string csv = trajectoryToCsv(trajectory);
  EXPECT_EQ(csv.substr(0, csv.find('\n')),
            "time,shoulder,elbow,shoulder_velocity,elbow_velocity,shoulder_acceleration,elbow_acceleration");
}

TEST(TrajectoryFiles, JointsOfTwoRobotsWithOneNameKeepTheRobotInTheirLabel) {
  const std::vector<TrajectoryJoint> joints = trajectoryJoints({"left/shoulder", "left/elbow", "right/shoulder", "right/wrist", "base_x"});
  std::vector<std::string> labels;
  for (const TrajectoryJoint& joint : joints) labels.push_back(joint.label);
  EXPECT_EQ(labels, (std::vector<std::string>{"left/shoulder", "elbow", "right/shoulder", "wrist", "base_x"}));
  EXPECT_EQ(joints[2].robot, "right");
  EXPECT_EQ(joints[2].joint, "shoulder");
  EXPECT_EQ(joints[4].robot, "");
}

TEST(BenchmarkLog, OmplFormat) {
  BenchmarkExperiment experiment;
  experiment.name = "test";
  experiment.planners.push_back({"geometric_RRTConnect", {{"range", "0.5"}},
                                 {{{"time REAL", "0.01"}, {"solved BOOLEAN", "1"}}}});
  std::ostringstream out;
  writeOmplBenchmarkLog(experiment, out);
  const std::string text = out.str();
  EXPECT_EQ(text.rfind("OMPL version 1.5.2\nExperiment test\n", 0), 0u);
  EXPECT_NE(text.find("status|"), std::string::npos);
  EXPECT_NE(text.find("geometric_RRTConnect\n1 common properties\nrange = 0.5\n2 properties for each run\n"
                      "solved BOOLEAN\ntime REAL\n1 runs\n1; 0.01; \n"),
            std::string::npos)
      << text;
  EXPECT_NE(std::find(omplStatusNames().begin(), omplStatusNames().end(), "Exact solution"), omplStatusNames().end());
  // Enum types of our own after OMPL's status, and invalid problems logged as OMPL logs them.
  experiment.enumTypes.emplace_back("family", std::vector<std::string>{"bookshelf", "box"});
  BenchmarkRun invalid = invalidBenchmarkRun(true);
  invalid["family ENUM"] = "1";
  experiment.planners.front().runs.push_back(invalid);
  std::ostringstream withEnums;
  writeOmplBenchmarkLog(experiment, withEnums);
  EXPECT_THAT(withEnums.str(), ::testing::HasSubstr("\n2 enum types\nstatus|"));
  EXPECT_THAT(withEnums.str(), ::testing::HasSubstr("\nfamily|bookshelf|box\n1 planners\n"));
  const auto invalidStart = std::find(omplStatusNames().begin(), omplStatusNames().end(), "Invalid start") - omplStatusNames().begin();
  EXPECT_THAT(withEnums.str(), ::testing::HasSubstr("4 properties for each run\nfamily ENUM\nsolved BOOLEAN\nstatus ENUM\ntime REAL\n2 runs\n; 1; ; 0.01; \n1; 0; " +
                                         std::to_string(invalidStart) + "; 0; \n"));
}

}  // namespace
}  // namespace lang2manip::test
