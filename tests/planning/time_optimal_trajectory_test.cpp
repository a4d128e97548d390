#include "lang2manip/planning/time_optimal_trajectory.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/planning/blended_path.hpp"
#include "lang2manip/planning/jerk_limiting.hpp"
#include "lang2manip/planning/planning_session.hpp"
#include "lang2manip/planning/trajectory.hpp"
#include "planning_test_support.hpp"

namespace lang2manip::test {
namespace {

// Relative slack of the limit checks: the integration keeps each step's constant path
// acceleration within the bounds at both ends (and the middle, near the limit curve); between
// them the bounds can move by a little.
constexpr double kVelocitySlack = 1e-4;
constexpr double kAccelerationSlack = 2e-3;

VectorX pandaVelocity() { return (VectorX(7) << 2.175, 2.175, 2.175, 2.175, 2.61, 2.61, 2.61).finished(); }
VectorX pandaAcceleration() { return (VectorX(7) << 15, 7.5, 10, 12.5, 15, 20, 20).finished(); }

std::vector<VectorX> randomPandaPath(std::uint64_t seed, int waypoints) {
  Random random(seed);
  std::vector<VectorX> path;
  for (int i = 0; i < waypoints; ++i) path.push_back(random.uniformVector(VectorX::Constant(7, -2), VectorX::Constant(7, 2)));
  return path;
}

struct LimitRatios {
  double velocity = 0.0;
  double acceleration = 0.0;
};

// The largest |value| / limit over every point and joint.
LimitRatios worstRatios(const JointTrajectory& trajectory, const VectorX& velocity, const VectorX& acceleration) {
  LimitRatios worst;
  for (const TrajectoryPoint& point : trajectory.points) {
    worst.velocity = std::max(worst.velocity, point.velocities.cwiseAbs().cwiseQuotient(velocity).maxCoeff());
    worst.acceleration = std::max(worst.acceleration, point.accelerations.cwiseAbs().cwiseQuotient(acceleration).maxCoeff());
  }
  return worst;
}

// Finite differences of the sampled positions (at the regular interval, before the end point).
LimitRatios finiteDifferenceRatios(const JointTrajectory& trajectory, const VectorX& velocity,
                                   const VectorX& acceleration, double interval) {
  LimitRatios worst;
  const auto& points = trajectory.points;
  for (std::size_t i = 1; i < points.size(); ++i) {
    const double dt = points[i].time - points[i - 1].time;
    const VectorX speed = (points[i].positions - points[i - 1].positions) / dt;
    worst.velocity = std::max(worst.velocity, speed.cwiseAbs().cwiseQuotient(velocity).maxCoeff());
    if (i + 1 >= points.size() - 1) continue;  // the last interval is shorter
    const VectorX second = (points[i + 1].positions - 2.0 * points[i].positions + points[i - 1].positions) / (interval * interval);
    worst.acceleration = std::max(worst.acceleration, second.cwiseAbs().cwiseQuotient(acceleration).maxCoeff());
  }
  return worst;
}

double distanceToPolyline(const std::vector<VectorX>& path, const VectorX& point) {
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i + 1 < path.size(); ++i) {
    const VectorX step = path[i + 1] - path[i];
    const double t = std::clamp((point - path[i]).dot(step) / step.squaredNorm(), 0.0, 1.0);
    best = std::min(best, (path[i] + t * step - point).norm());
  }
  return best;
}

// Rest to rest along a line of `length` at most `speed` and `acceleration` along it.
double restToRestDuration(double length, double speed, double acceleration) {
  if (speed * speed / acceleration >= length) return 2.0 * std::sqrt(length / acceleration);
  return length / speed + speed / acceleration;
}

template <typename Call>
std::string timeOptimalError(Call call) {
  try {
    call();
  } catch (const InputError& error) {
    return error.what();
  }
  return "";
}

TEST(TimeOptimal, StraightLineIsTheAnalyticTrapezoidOrTriangle) {
  const VectorX velocity = (VectorX(2) << 1.0, 2.0).finished();
  const VectorX acceleration = (VectorX(2) << 3.0, 4.0).finished();
  const VectorX direction = (VectorX(2) << 2.0, 1.0).finished().normalized();
  // Along the line, joint 0 limits both: speed 1 / 0.894, acceleration 3 / 0.894.
  const double speed = 1.0 / direction[0];
  const double pathAcceleration = 3.0 / direction[0];
  for (const double length : {std::sqrt(5.0), 0.1}) {  // a trapezoid, then a triangle
    const std::vector<VectorX> path{VectorX::Zero(2), direction * length};
    const JointTrajectory trajectory = timeOptimalParameterize(path, velocity, acceleration);
    EXPECT_NEAR(trajectory.duration(), restToRestDuration(length, speed, pathAcceleration), 1e-9);
    EXPECT_LE(worstRatios(trajectory, velocity, acceleration).velocity, 1.0 + 1e-12);
  }
  // The rest-to-rest trapezoid of timeParameterize is the same on a single segment.
  const auto space = planarArmSpace();
  const std::vector<VectorX> line{planarStart(), planarGoal()};
  EXPECT_NEAR(timeOptimalParameterize(*space, line).duration(), timeParameterize(*space, line).duration(), 1e-9);
}

TEST(TimeOptimal, RandomPathsStayWithinTheLimits) {
  const VectorX velocity = pandaVelocity();
  const VectorX acceleration = pandaAcceleration();
  for (std::uint64_t seed = 1; seed <= 8; ++seed) {
    SCOPED_TRACE("seed " + std::to_string(seed));
    const JointTrajectory trajectory = timeOptimalParameterize(randomPandaPath(seed, 10), velocity, acceleration);
    const LimitRatios sampled = worstRatios(trajectory, velocity, acceleration);
    EXPECT_LE(sampled.velocity, 1.0 + kVelocitySlack);
    EXPECT_LE(sampled.acceleration, 1.0 + kAccelerationSlack);
    EXPECT_GT(sampled.velocity, 0.99);  // time-optimal: some joint reaches its limits
    EXPECT_GT(sampled.acceleration, 0.99);
    const LimitRatios differences = finiteDifferenceRatios(trajectory, velocity, acceleration, 0.02);
    EXPECT_LE(differences.velocity, 1.0 + kVelocitySlack);
    EXPECT_LE(differences.acceleration, 1.0 + 1e-2);
    for (std::size_t i = 1; i < trajectory.points.size(); ++i) {
      ASSERT_GT(trajectory.points[i].time, trajectory.points[i - 1].time);
    }
  }
  // Through a planning space, with the space's own check.
  const auto space = planarArmSpace();
  Random random(5);
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<VectorX> path;
    for (int i = 0; i < 6; ++i) path.push_back(random.uniformVector(space->lower() * 0.9, space->upper() * 0.9));
    const JointTrajectory trajectory = timeOptimalParameterize(*space, path);
    EXPECT_EQ(trajectory.jointNames, space->trajectoryJointNames());
    EXPECT_EQ(checkTrajectoryLimits(*space, trajectory, kAccelerationSlack), "");
  }
}

TEST(TimeOptimal, FollowsTheBlendedPathThroughBothEnds) {
  for (const double deviation : {0.001, 0.01, 0.2}) {
    TimeOptimalOptions options;
    options.maxDeviation = deviation;
    options.sampleInterval = 1e-3;  // samples on every arc
    const std::vector<VectorX> path = randomPandaPath(11, 8);
    const JointTrajectory trajectory = timeOptimalParameterize(path, pandaVelocity(), pandaAcceleration(), options);
    EXPECT_TRUE((trajectory.points.front().positions.array() == path.front().array()).all());
    EXPECT_TRUE((trajectory.points.back().positions.array() == path.back().array()).all());
    EXPECT_TRUE(trajectory.points.front().velocities.isZero(0.0));
    EXPECT_TRUE(trajectory.points.back().velocities.isZero(0.0));
    double farthest = 0.0;
    for (const TrajectoryPoint& point : trajectory.points) farthest = std::max(farthest, distanceToPolyline(path, point.positions));
    EXPECT_LE(farthest, deviation * (1.0 + 1e-9));
    EXPECT_GT(farthest, 0.5 * deviation);  // corners are cut
  }
}

TEST(TimeOptimal, VelocitiesAndAccelerationsMatchThePositions) {
  TimeOptimalOptions options;
  options.sampleInterval = 1e-3;
  const VectorX velocity = pandaVelocity();
  const VectorX acceleration = pandaAcceleration();
  const JointTrajectory trajectory = timeOptimalParameterize(randomPandaPath(4, 6), velocity, acceleration, options);
  const auto& points = trajectory.points;
  const double dt = options.sampleInterval;
  for (std::size_t i = 1; i + 2 < points.size(); ++i) {
    const VectorX speed = (points[i + 1].positions - points[i - 1].positions) / (2.0 * dt);
    ASSERT_LT((speed - points[i].velocities).cwiseQuotient(velocity).cwiseAbs().maxCoeff(), 1e-2) << "point " << i;
    // Where the acceleration does not switch between the neighbours, it is the velocities' slope.
    if ((points[i + 1].accelerations - points[i - 1].accelerations).cwiseQuotient(acceleration).cwiseAbs().maxCoeff() > 0.05) continue;
    const VectorX slope = (points[i + 1].velocities - points[i - 1].velocities) / (2.0 * dt);
    ASSERT_LT((slope - points[i].accelerations).cwiseQuotient(acceleration).cwiseAbs().maxCoeff(), 2e-2) << "point " << i;
  }
}

TEST(TimeOptimal, FasterThanRestToRestThroughNearlyCollinearWaypoints) {
  // 11 waypoints 1 cm apart on a (slightly wavy) line: no stop inside.
  const auto space = planarArmSpace();
  const VectorX start = (VectorX(2) << 0.5, 0.2).finished();
  const VectorX along = (VectorX(2) << 0.6, 0.8).finished();
  const VectorX across = (VectorX(2) << -0.8, 0.6).finished();
  std::vector<VectorX> path;
  for (int i = 0; i <= 10; ++i) path.push_back(start + along * (0.01 * i) + across * (i % 2 == 0 ? 0.0 : 1e-4));
  const JointTrajectory fast = timeOptimalParameterize(*space, path);
  const JointTrajectory restToRest = timeParameterize(*space, path);
  EXPECT_LT(fast.duration(), 0.6 * restToRest.duration());
  EXPECT_EQ(checkTrajectoryLimits(*space, fast, kAccelerationSlack), "");
  for (std::size_t i = 1; i + 1 < fast.points.size(); ++i) EXPECT_GT(fast.points[i].velocities.norm(), 1e-3);
}

TEST(TimeOptimal, NeverStopsInsideAPathWithoutReversal) {
  const std::vector<VectorX> path = randomPandaPath(21, 12);
  const BlendedPath blended(path, 0.01);
  ASSERT_TRUE(blended.stopPoints().empty());
  const JointTrajectory trajectory = timeOptimalParameterize(path, pandaVelocity(), pandaAcceleration());
  for (std::size_t i = 1; i + 1 < trajectory.points.size(); ++i) {
    EXPECT_GT(trajectory.points[i].velocities.norm(), 1e-6) << "point " << i;
  }
}

TEST(TimeOptimal, StopsAtAReversal) {
  const VectorX velocity = (VectorX(2) << 1.0, 1.0).finished();
  const VectorX acceleration = (VectorX(2) << 2.0, 2.0).finished();
  const std::vector<VectorX> path{(VectorX(2) << 0.0, 0.0).finished(), (VectorX(2) << 1.0, 0.5).finished(),
                                  (VectorX(2) << 0.4, 0.2).finished()};
  TimeOptimalOptions options;
  options.sampleInterval = 1e-3;
  const JointTrajectory trajectory = timeOptimalParameterize(path, velocity, acceleration, options);
  // It reaches the corner, never overshoots it, and is at rest there.
  std::size_t turn = 0;
  for (std::size_t i = 0; i < trajectory.points.size(); ++i) {
    EXPECT_LE(trajectory.points[i].positions[0], 1.0 + 1e-12);
    if (trajectory.points[i].positions[0] > trajectory.points[turn].positions[0]) turn = i;
  }
  EXPECT_NEAR(trajectory.points[turn].positions[0], 1.0, 1e-5);
  EXPECT_LT(trajectory.points[turn].velocities.norm(), 2.0 * options.sampleInterval * acceleration.norm());
  // Both moves are rest to rest along lines.
  const double along = 1.0 / (2.0 / std::sqrt(5.0));
  EXPECT_NEAR(trajectory.duration(),
              restToRestDuration(std::sqrt(1.25), along, 2.0 * along) + restToRestDuration(std::sqrt(0.45), along, 2.0 * along),
              1e-9);
}

TEST(TimeOptimal, ScalingSlowsItDownWithinTheScaledLimits) {
  const std::vector<VectorX> path = randomPandaPath(7, 8);
  const JointTrajectory full = timeOptimalParameterize(path, pandaVelocity(), pandaAcceleration());
  TimeOptimalOptions options;
  options.velocityScaling = 0.5;
  options.accelerationScaling = 0.5;
  const JointTrajectory half = timeOptimalParameterize(path, pandaVelocity(), pandaAcceleration(), options);
  EXPECT_GT(half.duration(), 1.3 * full.duration());
  const LimitRatios ratios = worstRatios(half, 0.5 * pandaVelocity(), 0.5 * pandaAcceleration());
  EXPECT_LE(ratios.velocity, 1.0 + kVelocitySlack);
  EXPECT_LE(ratios.acceleration, 1.0 + kAccelerationSlack);
}

TEST(TimeOptimal, KauthamControlsThroughTheSpaceJacobian) {
  // The paper's desk problem plans normalized controls; the Panda's joint limits apply through
  // the controls-to-joints map.
  PlanningSession session;
  session.openProblem(resolveProblem("panda_desk"));
  const auto space = session.planningSpace();
  ASSERT_FALSE(space->trajectoryJacobian().isIdentity());
  const KauthamQuery& query = session.problem().queries.front();
  const VectorX init = Eigen::Map<const VectorX>(query.init.data(), static_cast<Eigen::Index>(query.init.size()));
  const VectorX goal = Eigen::Map<const VectorX>(query.goal.data(), static_cast<Eigen::Index>(query.goal.size()));
  const VectorX middle = (0.5 * (init + goal) + VectorX::Constant(init.size(), 0.05)).cwiseMin(space->upper());
  const std::vector<VectorX> path{init, middle, goal};
  const JointTrajectory trajectory = timeOptimalParameterize(*space, path);
  EXPECT_EQ(trajectory.jointNames, space->trajectoryJointNames());
  EXPECT_EQ(checkTrajectoryLimits(*space, trajectory, kAccelerationSlack), "");
  EXPECT_TRUE(trajectory.points.front().positions.isApprox(space->trajectoryPositions(init), 0.0));
  EXPECT_TRUE(trajectory.points.back().positions.isApprox(space->trajectoryPositions(goal), 0.0));
  EXPECT_LT(trajectory.duration(), timeParameterize(*space, path).duration());
}

TEST(TimeOptimal, ZeroDeviationIsRestToRestAtEveryCorner) {
  const auto space = planarArmSpace();
  const std::vector<VectorX> path{planarStart(), (VectorX(2) << 1.2, 2.0).finished(), (VectorX(2) << 0.0, 1.5).finished(),
                                  planarGoal()};
  TimeOptimalOptions options;
  options.maxDeviation = 0.0;
  EXPECT_NEAR(timeOptimalParameterize(*space, path, options).duration(), timeParameterize(*space, path).duration(), 1e-9);
  EXPECT_LT(timeOptimalParameterize(*space, path).duration(), timeParameterize(*space, path).duration());
}

TEST(TimeOptimal, OnePointOrRepeatedPointsGiveOnePointAtRest) {
  const VectorX q = pandaVelocity() * 0.1;
  for (const std::vector<VectorX>& path : {std::vector<VectorX>{q}, std::vector<VectorX>{q, q, q}}) {
    const JointTrajectory trajectory = timeOptimalParameterize(path, pandaVelocity(), pandaAcceleration());
    ASSERT_EQ(trajectory.points.size(), 1u);
    EXPECT_EQ(trajectory.points[0].time, 0.0);
    EXPECT_TRUE(trajectory.points[0].positions == q);
    EXPECT_TRUE(trajectory.points[0].velocities.isZero(0.0));
    EXPECT_TRUE(trajectory.points[0].accelerations.isZero(0.0));
  }
  // Repeated waypoints inside a path change nothing.
  std::vector<VectorX> path = randomPandaPath(3, 5);
  const double duration = timeOptimalParameterize(path, pandaVelocity(), pandaAcceleration()).duration();
  const VectorX middle = path[2];
  const VectorX last = path.back();
  path.insert(path.begin() + 2, middle);
  path.push_back(last);
  EXPECT_DOUBLE_EQ(timeOptimalParameterize(path, pandaVelocity(), pandaAcceleration()).duration(), duration);
}

TEST(TimeOptimal, BadInputGivesClearErrors) {
  const VectorX velocity = pandaVelocity();
  const VectorX acceleration = pandaAcceleration();
  const std::vector<VectorX> path = randomPandaPath(1, 3);
  const auto error = [](const std::vector<VectorX>& points, const VectorX& maxVelocity, const VectorX& maxAcceleration,
                        const TimeOptimalOptions& options) {
    return timeOptimalError([&] { (void)timeOptimalParameterize(points, maxVelocity, maxAcceleration, options); });
  };
  const auto contains = [](const std::string& text, const std::string& part) {
    return text.find(part) != std::string::npos;
  };
  EXPECT_TRUE(contains(error({}, velocity, acceleration, {}), "empty"));
  std::vector<VectorX> bad = path;
  bad[1][3] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(contains(error(bad, velocity, acceleration, {}), "waypoint 1"));
  bad = path;
  bad[2] = VectorX::Zero(6);
  EXPECT_TRUE(contains(error(bad, velocity, acceleration, {}), "waypoint 2 has 6 values"));
  VectorX limits = velocity;
  limits[3] = 0.0;
  EXPECT_TRUE(contains(error(path, limits, acceleration, {}), "joint joint_3 has velocity limit"));
  limits = acceleration;
  limits[6] = -1.0;
  EXPECT_TRUE(contains(error(path, velocity, limits, {}), "joint joint_6 has acceleration limit"));
  limits[6] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(contains(error(path, velocity, limits, {}), "joint_6"));
  EXPECT_TRUE(contains(error(path, velocity.head(6), acceleration, {}), "6 velocity limits for 7 joints"));
  for (const double scaling : {0.0, 1.5, std::numeric_limits<double>::quiet_NaN()}) {
    TimeOptimalOptions options;
    options.velocityScaling = scaling;
    EXPECT_TRUE(contains(error(path, velocity, acceleration, options), "velocity scaling must be in (0, 1]"));
    options = {};
    options.accelerationScaling = scaling;
    EXPECT_TRUE(contains(error(path, velocity, acceleration, options), "acceleration scaling must be in (0, 1]"));
  }
  TimeOptimalOptions options;
  options.timeStep = 0.0;
  EXPECT_TRUE(contains(error(path, velocity, acceleration, options), "time step"));
  options = {};
  options.sampleInterval = -0.1;
  EXPECT_TRUE(contains(error(path, velocity, acceleration, options), "sample interval"));
  options = {};
  options.maxDeviation = -0.1;
  EXPECT_TRUE(contains(error(path, velocity, acceleration, options), "max deviation"));
  // Through a space: its bounds and sizes.
  const auto space = planarArmSpace();
  EXPECT_THROW((void)timeOptimalParameterize(*space, {planarStart(), VectorX::Constant(2, 10.0)}), InputError);
  EXPECT_THROW((void)timeOptimalParameterize(*space, {VectorX::Zero(3)}), InputError);
  EXPECT_THROW((void)timeOptimalParameterize(*space, {}), InputError);
}

TEST(TimeOptimal, TooLongTrajectoriesFailInsteadOfHanging) {
  // Hours along a wide arc at 1e-5 rad/s, in microsecond steps: over the integration budget.
  const std::vector<VectorX> path{VectorX::Zero(2), (VectorX(2) << 1.0, 0.0).finished(), (VectorX(2) << 1.0, 1.0).finished()};
  TimeOptimalOptions options;
  options.maxDeviation = 0.3;
  options.timeStep = 1e-6;
  const std::string slow = timeOptimalError([&] {
    (void)timeOptimalParameterize(path, VectorX::Constant(2, 1e-5), VectorX::Constant(2, 1.0), options);
  });
  EXPECT_NE(slow.find("integration steps"), std::string::npos) << slow;
  // Too many output points for the sample interval.
  options = {};
  options.sampleInterval = 1e-6;
  const std::string dense = timeOptimalError([&] {
    (void)timeOptimalParameterize({VectorX::Zero(1), VectorX::Constant(1, 100.0)}, VectorX::Constant(1, 1.0),
                                  VectorX::Constant(1, 1.0), options);
  });
  EXPECT_NE(dense.find("output points"), std::string::npos) << dense;
}

VectorX pandaJerk() { return (VectorX(7) << 7500, 3750, 5000, 6250, 7500, 10000, 10000).finished(); }

TEST(JerkLimits, TheFilteredTrajectoryMeetsEveryLimitAndKeepsToThePath) {
  TimeOptimalOptions fine;
  fine.sampleInterval = 1e-3;
  fine.maxDeviation = 0.1;
  for (std::uint64_t seed = 1; seed <= 5; ++seed) {
    const JointTrajectory timed = timeOptimalParameterize(randomPandaPath(seed, 6), pandaVelocity(), pandaAcceleration(), fine);
    EXPECT_FALSE(checkJerkLimits(timed, pandaJerk()).empty()) << "bang-bang acceleration jumps at its switches";
    const JerkLimitedTrajectory limited = limitJerk(timed, pandaAcceleration(), pandaJerk(), 1e-3);
    EXPECT_EQ(checkJerkLimits(limited.trajectory, pandaJerk(), 1e-3), "") << "seed " << seed;
    const LimitRatios worst = worstRatios(limited.trajectory, pandaVelocity(), pandaAcceleration());
    EXPECT_LE(worst.velocity, 1.0 + kVelocitySlack);
    EXPECT_LE(worst.acceleration, 1.0 + kAccelerationSlack);
    EXPECT_NEAR(limited.window, 0.004, 1e-3);
    EXPECT_NEAR(limited.trajectory.duration(), timed.duration() + limited.window, 1e-3);
    // Within a T^2 a / 24 of the path (T 4 ms, a at most 20 rad/s^2, seven joints).
    EXPECT_LT(limited.deviation, 1e-4);
    const TrajectoryPoint& first = limited.trajectory.points.front();
    const TrajectoryPoint& last = limited.trajectory.points.back();
    EXPECT_TRUE(first.positions.isApprox(timed.points.front().positions));
    EXPECT_TRUE(last.positions.isApprox(timed.points.back().positions));
    EXPECT_NEAR(first.velocities.norm() + last.velocities.norm() + last.accelerations.norm(), 0.0, 1e-9);
    for (std::size_t k = 1; k < limited.trajectory.points.size(); ++k) {
      ASSERT_GT(limited.trajectory.points[k].time, limited.trajectory.points[k - 1].time);
    }
  }
}

TEST(JerkLimits, AJointWithoutAJerkLimitIsLeftAsItIs) {
  TimeOptimalOptions fine;
  fine.sampleInterval = 1e-3;
  const JointTrajectory timed = timeOptimalParameterize(randomPandaPath(3, 4), pandaVelocity(), pandaAcceleration(), fine);
  const JerkLimitedTrajectory unlimited = limitJerk(timed, pandaAcceleration(), VectorX::Zero(7), 0.02);
  EXPECT_EQ(unlimited.window, 0.0);
  EXPECT_EQ(unlimited.trajectory.points.size(), timed.points.size());
  VectorX oneJoint = VectorX::Zero(7);
  oneJoint[1] = 100.0;  // a slow-jerk joint sets the window for all: 2 x 7.5 / 100 = 0.15 s
  const JerkLimitedTrajectory slow = limitJerk(timed, pandaAcceleration(), oneJoint, 0.02);
  EXPECT_NEAR(slow.window, 0.15, 2e-3);
  EXPECT_EQ(checkJerkLimits(slow.trajectory, oneJoint, 1e-3), "");
  // Output every 20 ms and at the end.
  EXPECT_NEAR(slow.trajectory.points[1].time, 0.02, 1e-3);
}

TEST(JerkLimits, BadInputGivesClearErrors) {
  TimeOptimalOptions fine;
  fine.sampleInterval = 1e-3;
  const JointTrajectory timed = timeOptimalParameterize(randomPandaPath(2, 3), pandaVelocity(), pandaAcceleration(), fine);
  const auto error = [&](const JointTrajectory& trajectory, const VectorX& acceleration, const VectorX& jerk, double interval) {
    return timeOptimalError([&] { (void)limitJerk(trajectory, acceleration, jerk, interval); });
  };
  EXPECT_NE(error(timed, pandaAcceleration(), VectorX::Zero(3), 0.02).find("7 joints but 7 acceleration and 3 jerk limits"), std::string::npos);
  VectorX negative = pandaJerk();
  negative[4] = -1.0;
  EXPECT_NE(error(timed, pandaAcceleration(), negative, 0.02).find("joint_4: limits must be finite and not negative"), std::string::npos);
  EXPECT_NE(error(timed, VectorX::Zero(7), pandaJerk(), 0.02).find("has a jerk limit but no acceleration limit"), std::string::npos);
  JointTrajectory moving = timed;
  moving.points.pop_back();
  EXPECT_NE(error(moving, pandaAcceleration(), pandaJerk(), 0.02).find("must start and end at rest"), std::string::npos);
  JointTrajectory single = timed;
  single.points.resize(1);
  EXPECT_NE(error(single, pandaAcceleration(), pandaJerk(), 0.02).find("fewer than two points"), std::string::npos);
  EXPECT_NE(error(timed, pandaAcceleration(), pandaJerk(), 0.0).find("output interval must be positive"), std::string::npos);
  // Work is bounded: a jerk limit in the wrong unit, or a trajectory sampled too finely, is refused.
  VectorX tiny = pandaJerk();
  tiny[2] = 1e-6;
  EXPECT_NE(error(timed, pandaAcceleration(), tiny, 0.02).find("joint_2's jerk limit 1e-06 with acceleration limit"), std::string::npos);
  EXPECT_NE(error(timed, pandaAcceleration(), tiny, 0.02).find("raise max_jerk"), std::string::npos);
  JointTrajectory fineSampled = timed;
  fineSampled.points[1].time = fineSampled.points[0].time + 1e-9;
  EXPECT_NE(error(fineSampled, pandaAcceleration(), pandaJerk(), 0.02).find("filter samples (at most 2000000)"), std::string::npos);
}

}  // namespace
}  // namespace lang2manip::test
