#pragma once
/// Shared helpers of the planning tests: a planar two-link arm behind a wall, whose straight
/// joint-space path from start to goal collides, so every planner has to go around.

#include <memory>
#include <string>

#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "lang2manip/planning/planning_space.hpp"

namespace lang2manip::test {

/// Wall-clock planning limits in tests are budgets of an optimized build; under AddressSanitizer
/// everything runs about ten times slower.
#if defined(__SANITIZE_ADDRESS__)
constexpr bool kSanitizedBuild = true;
constexpr double kTimeLimitScale = 10.0;
#else
constexpr bool kSanitizedBuild = false;
constexpr double kTimeLimitScale = 1.0;
#endif

inline std::string planarArmUrdf() {
  return R"(<?xml version="1.0"?>
<robot name="planar">
  <link name="base"/>
  <link name="upper"><collision><origin xyz="0.25 0 0"/><geometry><box size="0.5 0.04 0.04"/></geometry></collision></link>
  <link name="fore"><collision><origin xyz="0.2 0 0"/><geometry><box size="0.4 0.04 0.04"/></geometry></collision></link>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/><axis xyz="0 0 1"/>
    <limit lower="-3" upper="3" velocity="1.5" effort="10"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="fore"/><origin xyz="0.5 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-2.5" upper="2.5" velocity="2" effort="10"/>
  </joint>
</robot>
)";
}

/// The arm with a post at (0.6, 0, 0): the arm cannot sweep through angle 0 stretched out.
inline Scene planarArmScene() {
  Scene scene;
  SceneRobot robot;
  robot.name = "planar";
  robot.model = readUrdfString(planarArmUrdf(), "planar.urdf", ".");
  robot.configuration = VectorX::Zero(2);
  robot.configuration << 1.2, 0.0;
  scene.addRobot(robot);
  SceneObject post;
  post.name = "post";
  post.kind = "post";
  post.pose = Pose::Identity();
  post.pose.translation() = Vector3(0.7, 0.0, 0.0);
  post.collisions.push_back(Shape{Box{Vector3(0.1, 0.1, 0.4)}, Pose::Identity(), std::nullopt, "post"});
  scene.addObject(post);
  return scene;
}

inline std::shared_ptr<const CollisionChecker> planarArmChecker() {
  return std::make_shared<FclCollisionChecker>(planarArmScene());
}

inline std::shared_ptr<const PlanningSpace> planarArmSpace() {
  return std::make_shared<JointPlanningSpace>(planarArmChecker(), std::vector<std::string>{"planar"});
}

inline VectorX planarStart() { return (VectorX(2) << 1.2, 0.0).finished(); }
inline VectorX planarGoal() { return (VectorX(2) << -1.2, 0.0).finished(); }

}  // namespace lang2manip::test
