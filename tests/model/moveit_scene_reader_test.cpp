#include "lang2manip/model/moveit_scene_reader.hpp"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <map>
#include <ostream>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/rotation.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using ::testing::HasSubstr;

constexpr double kMoveitTolerance = 1e-12;

fs::path moveitData(const std::string& name) { return test::testDataDirectory() / "moveit" / name; }

Link makeLink(const std::string& name) {
  Link link;
  link.name = name;
  return link;
}

Joint makeJoint(const std::string& name, JointType type, const std::string& parent,
                const std::string& child, double lower, double upper) {
  Joint joint;
  joint.name = name;
  joint.type = type;
  joint.parentLink = parent;
  joint.childLink = child;
  joint.limits = JointLimits{lower, upper, 1.0, 1.0, false};
  return joint;
}

/// Two revolute joints named like the Panda's, a finger with the Panda's limits and a mimic.
RobotModelPtr tinyArm() {
  RobotModelData data;
  data.name = "tiny_model";
  for (const char* name : {"base", "link1", "link2", "left_finger", "right_finger"}) {
    data.links.push_back(makeLink(name));
  }
  data.joints.push_back(makeJoint("panda_joint1", JointType::kRevolute, "base", "link1", -1, 2));
  data.joints.push_back(makeJoint("panda_joint2", JointType::kRevolute, "link1", "link2", -2, 2));
  data.joints.push_back(
      makeJoint("panda_finger_joint1", JointType::kPrismatic, "link2", "left_finger", 0, 0.04));
  Joint mimic =
      makeJoint("panda_finger_joint2", JointType::kPrismatic, "link2", "right_finger", 0, 0.04);
  mimic.mimic = JointMimic{"panda_finger_joint1", 1.0, 0.0};
  data.joints.push_back(mimic);
  Manipulator arm;
  arm.name = "arm";
  arm.armJoints = {"panda_joint1", "panda_joint2"};
  arm.baseLink = "base";
  arm.toolFrame = "link2";
  arm.gripperJoints = {"panda_finger_joint1"};
  arm.gripperOpen = {0.04};
  arm.gripperClosed = {0.0};
  data.semantics.manipulators.push_back(arm);
  data.semantics.inferred = false;
  return std::make_shared<const RobotModel>(std::move(data));
}

MoveItProblem readTestProblem(const std::string& scene, const std::string& request) {
  return readMoveItProblem(moveitData(scene), moveitData(request), tinyArm());
}

/// The message of the InputError `read` throws ("" and a failure when it throws none).
std::string inputErrorOf(const std::function<void()>& read) {
  try {
    read();
  } catch (const InputError& error) {
    return error.what();
  }
  ADD_FAILURE() << "no InputError thrown";
  return "";
}

void expectPose(const Pose& actual, const Vector3& translation, const Quaternion& rotation) {
  EXPECT_TRUE(actual.translation().isApprox(translation, kMoveitTolerance) ||
              (actual.translation() - translation).norm() < kMoveitTolerance)
      << actual.translation().transpose();
  EXPECT_TRUE(actual.linear().isApprox(rotation.normalized().toRotationMatrix(), kMoveitTolerance))
      << actual.linear();
}

double value(const RobotModel& model, const VectorX& q, const std::string& joint) {
  return q[model.variableIndex(joint)];
}

// ---------------------------------------------------------------------------------------------
// Good files

TEST(MoveItSceneReaderTest, ReadsTheRobotAtTheStartState) {
  const MoveItProblem problem = readTestProblem("good_scene.yaml", "good_request.yaml");
  ASSERT_EQ(problem.scene.robots().size(), 1u);
  const SceneRobot& robot = problem.scene.robots().front();
  EXPECT_EQ(robot.name, "tiny_arm");
  EXPECT_EQ(problem.robot, "tiny_arm");
  EXPECT_EQ(robot.model->name(), "tiny_model");
  // The scene's virtual joint: [0, 0, 1, 1] normalized is 90 degrees about z.
  expectPose(robot.basePose, Vector3(0.1, 0.2, 0.3), Quaternion(1, 0, 0, 1));
  const RobotModel& model = *robot.model;
  // panda_joint1: omitted by the request (the scene's 1.5 is not used) -> middle of [-1, 2].
  EXPECT_DOUBLE_EQ(value(model, problem.start, "panda_joint1"), 0.5);
  // panda_joint2: outside [-2, 2], kept as given.
  EXPECT_DOUBLE_EQ(value(model, problem.start, "panda_joint2"), -3.0);
  // The finger: 0.065 clamped to 0.04 and recorded once (the mimic is ignored).
  EXPECT_DOUBLE_EQ(value(model, problem.start, "panda_finger_joint1"), 0.04);
  ASSERT_EQ(problem.clampedJoints.size(), 1u);
  EXPECT_EQ(problem.clampedJoints[0].joint, "panda_finger_joint1");
  EXPECT_DOUBLE_EQ(problem.clampedJoints[0].given, 0.065);
  EXPECT_DOUBLE_EQ(problem.clampedJoints[0].used, 0.04);
  EXPECT_EQ(robot.configuration, problem.start);
}

TEST(MoveItSceneReaderTest, ReadsTheGoalAndRequestSettings) {
  const MoveItProblem problem = readTestProblem("good_scene.yaml", "good_request.yaml");
  const RobotModel& model = *problem.scene.robots().front().model;
  EXPECT_EQ(problem.goalJoints, std::vector<std::string>{"panda_joint2"});
  VectorX expected = problem.start;
  expected[model.variableIndex("panda_joint2")] = 1.25;
  EXPECT_EQ(problem.goal, expected);
  EXPECT_EQ(problem.group, "arm");
  EXPECT_EQ(problem.plannerId, "RRTConnectkConfigDefault");
  EXPECT_DOUBLE_EQ(problem.allowedPlanningTime, 5.0);
  EXPECT_EQ(problem.sceneFile, moveitData("good_scene.yaml"));
  EXPECT_EQ(problem.requestFile, moveitData("good_request.yaml"));
}

TEST(MoveItSceneReaderTest, ReadsOnePrimitiveObjectsInTheirOwnFrame) {
  const MoveItProblem problem = readTestProblem("good_scene.yaml", "good_request.yaml");
  ASSERT_EQ(problem.scene.objects().size(), 5u);
  const SceneObject& crate = problem.scene.object("crate");
  EXPECT_EQ(crate.kind, "box");
  EXPECT_FALSE(crate.movable);
  EXPECT_EQ(crate.role, ObjectRole::kNone);
  EXPECT_EQ(crate.pose.translation(), Vector3(1.25, -2.5, 0.375));
  expectPose(crate.pose, Vector3(1.25, -2.5, 0.375), Quaternion(0.8, 0, 0, 0.6));
  ASSERT_EQ(crate.collisions.size(), 1u);
  EXPECT_TRUE(crate.collisions[0].origin.isApprox(Pose::Identity()));
  EXPECT_EQ(std::get<Box>(crate.collisions[0].geometry).size, Vector3(0.4, 0.5, 0.6));

  const SceneObject& ball = problem.scene.object("ball");  // map form, unnormalized quaternion
  EXPECT_EQ(ball.kind, "sphere");
  expectPose(ball.pose, Vector3(-1, 0.5, 0.125), Quaternion::Identity());
  EXPECT_DOUBLE_EQ(std::get<Sphere>(ball.collisions.at(0).geometry).radius, 0.25);

  const SceneObject& can = problem.scene.object("can");  // type 3, [height, radius]
  EXPECT_EQ(can.kind, "cylinder");
  expectPose(can.pose, Vector3(0.5, 0, 0.07), Quaternion(0, 1, 0, 0));
  const auto& cylinder = std::get<Cylinder>(can.collisions.at(0).geometry);
  EXPECT_DOUBLE_EQ(cylinder.length, 0.14);
  EXPECT_DOUBLE_EQ(cylinder.radius, 0.03);
}

TEST(MoveItSceneReaderTest, ReadsSeveralPrimitivesAsOneObject) {
  const MoveItProblem problem = readTestProblem("good_scene.yaml", "good_request.yaml");
  // No object pose: the identity frame and the primitives at their world poses.
  const SceneObject& table = problem.scene.object("table");
  EXPECT_EQ(table.kind, "obstacle");
  EXPECT_TRUE(table.pose.isApprox(Pose::Identity()));
  ASSERT_EQ(table.collisions.size(), 2u);
  EXPECT_EQ(std::get<Box>(table.collisions[0].geometry).size, Vector3(1, 0.75, 0.05));
  EXPECT_EQ(table.collisions[0].origin.translation(), Vector3(0, 0, 0.725));
  const auto& leg = std::get<Cylinder>(table.collisions[1].geometry);
  EXPECT_DOUBLE_EQ(leg.length, 0.7);
  EXPECT_DOUBLE_EQ(leg.radius, 0.05);
  EXPECT_EQ(table.collisions[1].origin.translation(), Vector3(0.375, 0.25, 0.35));

  // MoveIt 2 object pose: the object frame, primitives relative to it.
  const SceneObject& shelf = problem.scene.object("shelf");
  EXPECT_EQ(shelf.kind, "box");
  expectPose(shelf.pose, Vector3(2, 0, 0), Quaternion(0.8, 0, 0, 0.6));
  ASSERT_EQ(shelf.collisions.size(), 2u);
  expectPose(shelf.collisions[0].origin, Vector3(0, 0, 0.25), Quaternion::Identity());
  expectPose(shelf.collisions[1].origin, Vector3(0, 0, 0.5), Quaternion::Identity());
}

TEST(MoveItSceneReaderTest, ReadsTheAllowedCollisionMatrix) {
  const MoveItProblem problem = readTestProblem("good_scene.yaml", "good_request.yaml");
  const std::vector<std::pair<std::string, std::string>> expected = {{"base", "link1"},
                                                                     {"link1", "link2"}};
  EXPECT_EQ(problem.allowedCollisions, expected);
}

TEST(MoveItSceneReaderTest, StartStateBaseOverridesTheScenes) {
  const MoveItProblem problem = readTestProblem("good_scene.yaml", "base_request.yaml");
  const SceneRobot& robot = problem.scene.robots().front();
  expectPose(robot.basePose, Vector3(1, 2, 0), Quaternion::Identity());
  EXPECT_DOUBLE_EQ(value(*robot.model, problem.start, "panda_joint1"), 0.25);
  EXPECT_DOUBLE_EQ(value(*robot.model, problem.start, "panda_joint2"), 0.0);  // middle
  EXPECT_DOUBLE_EQ(value(*robot.model, problem.goal, "panda_joint1"), -0.5);
  EXPECT_DOUBLE_EQ(value(*robot.model, problem.goal, "panda_joint2"), 0.75);
  EXPECT_DOUBLE_EQ(value(*robot.model, problem.goal, "panda_finger_joint1"), 0.02);
  EXPECT_EQ(problem.goalJoints, (std::vector<std::string>{"panda_joint1", "panda_joint2"}));
  EXPECT_TRUE(problem.clampedJoints.empty());
  EXPECT_TRUE(problem.group.empty());
  EXPECT_DOUBLE_EQ(problem.allowedPlanningTime, 0.0);
}

TEST(MoveItSceneReaderTest, MinimalSceneUsesTheModelName) {
  const MoveItProblem problem = readTestProblem("minimal_scene.yaml", "good_request.yaml");
  ASSERT_EQ(problem.scene.robots().size(), 1u);
  EXPECT_EQ(problem.scene.robots().front().name, "tiny_model");
  EXPECT_TRUE(problem.scene.robots().front().basePose.isApprox(Pose::Identity()));
  EXPECT_TRUE(problem.scene.objects().empty());
  EXPECT_TRUE(problem.allowedCollisions.empty());
}

TEST(MoveItSceneReaderTest, RequestFileForScene) {
  EXPECT_EQ(requestFileForScene("/data/box_panda/scene0042.yaml"),
            fs::path("/data/box_panda/request0042.yaml"));
  EXPECT_EQ(requestFileForScene("scene7.yaml"), fs::path("request7.yaml"));
  for (const char* bad : {"/data/box/scene.yaml", "/data/box/scene12.yml", "/data/scene1a.yaml",
                          "/data/request0001.yaml", "/data/myscene0001.yaml"}) {
    const std::string message = inputErrorOf([&] { (void)requestFileForScene(bad); });
    EXPECT_THAT(message, HasSubstr(bad));
    EXPECT_THAT(message, HasSubstr("expected sceneNNNN.yaml"));
  }
}

TEST(MoveItSceneReaderTest, MissingFileAndModelAreReported) {
  const std::string message =
      inputErrorOf([] { (void)readTestProblem("good_scene.yaml", "no_such_request.yaml"); });
  EXPECT_THAT(message, HasSubstr("no_such_request.yaml: YAML file does not exist"));
  const std::string noModel = inputErrorOf([] {
    (void)readMoveItProblem(moveitData("good_scene.yaml"), moveitData("good_request.yaml"),
                            nullptr);
  });
  EXPECT_THAT(noModel, HasSubstr("no robot model"));
}

// ---------------------------------------------------------------------------------------------
// Bad files: each message names the file, the line, the YAML path and the problem.

struct BadCase {
  std::string file;
  int line;
  std::string path;
  std::string problem;
  /// A bad request is read with the good scene, a bad scene with the good request.
  bool isRequest = false;
};

std::ostream& operator<<(std::ostream& out, const BadCase& bad) { return out << bad.file; }

class MoveItBadInputTest : public ::testing::TestWithParam<BadCase> {};

TEST_P(MoveItBadInputTest, ReportsFileLinePathAndProblem) {
  const BadCase& bad = GetParam();
  const std::string scene = bad.isRequest ? "good_scene.yaml" : bad.file;
  const std::string request = bad.isRequest ? bad.file : "good_request.yaml";
  const std::string message = inputErrorOf([&] { (void)readTestProblem(scene, request); });
  EXPECT_THAT(message, HasSubstr(bad.file + ":" + std::to_string(bad.line) + ": "));
  EXPECT_THAT(message, HasSubstr(bad.path));
  EXPECT_THAT(message, HasSubstr(bad.problem));
}

const char* const kPrimitive = "world.collision_objects[0].primitives[0]";
const char* const kPose = "world.collision_objects[0].primitive_poses[0]";

std::vector<BadCase> badScenes() {
  const std::string primitive = kPrimitive;
  const std::string pose = kPose;
  const std::string dims = primitive + ".dimensions";
  return {
      {"bad_box_dimensions.yaml", 7, dims, "expected 3 dimensions [x, y, z] for a box, got 2"},
      {"bad_sphere_dimensions.yaml", 7, dims, "expected 1 dimension [radius] for a sphere, got 2"},
      {"bad_cylinder_dimensions.yaml", 7, dims,
       "expected 2 dimensions [height, radius] for a cylinder, got 3"},
      {"bad_cone.yaml", 6, primitive + ".type", "cone primitives are not supported"},
      {"bad_primitive_type.yaml", 6, primitive + ".type", "unknown primitive type 'capsule'"},
      {"bad_nan_position.yaml", 9, pose + ".position[1]", "must be a finite number, got .nan"},
      {"bad_inf_dimension.yaml", 7, dims + "[1]", "must be a finite number, got -.inf"},
      {"bad_negative_dimension.yaml", 7, dims + "[2]", "a dimension must be positive"},
      {"bad_huge_dimension.yaml", 7, dims + "[0]", "dimension 1e+308 m is outside [1e-06, 10000] m"},
      {"bad_far_position.yaml", 9, pose + ".position", "position (0, 1e+300, 0) m is more than 10000 m"},
      {"bad_zero_quaternion.yaml", 10, pose + ".orientation", "has zero length"},
      {"bad_orientation_count.yaml", 10, pose + ".orientation",
       "expected 4 numbers [x, y, z, w], got 3"},
      {"bad_orientation_map.yaml", 10, pose + ".orientation", "missing required key 'w'"},
      {"bad_not_a_number.yaml", 9, pose + ".position[1]", "\"zero\" is not a number"},
      {"bad_dimensions_type.yaml", 7, dims, "expected a list, got \"0.4\""},
      {"bad_missing_dimensions.yaml", 6, primitive, "missing required key 'dimensions'"},
      {"bad_pose_count.yaml", 9, "world.collision_objects[0].primitive_poses",
       "expected 2 poses (one per primitive), got 1"},
      {"bad_mesh.yaml", 6, "world.collision_objects[0].meshes",
       "mesh collision objects are not supported"},
      {"bad_operation.yaml", 5, "world.collision_objects[0].operation",
       "operation 'remove' is not supported (only ADD)"},
      {"bad_frame.yaml", 6, "world.collision_objects[0].header.frame_id",
       "frame 'panda_hand' is not supported"},
      {"bad_duplicate_id.yaml", 7, "world.collision_objects[1].id", "duplicate name 'crate'"},
      {"bad_missing_id.yaml", 4, "world.collision_objects[0]", "missing required key 'id'"},
      {"bad_acm_not_square.yaml", 6, "allowed_collision_matrix.entry_values[1]",
       "expected 2 values (the matrix must be square), got 3"},
      {"bad_acm_rows.yaml", 5, "allowed_collision_matrix.entry_values",
       "expected 3 rows (one per entry name), got 2"},
      {"bad_acm_asymmetric.yaml", 5, "allowed_collision_matrix.entry_values",
       "not symmetric: [0][1] and [1][0] (base, link1) differ"},
      {"bad_acm_value.yaml", 6, "allowed_collision_matrix.entry_values[1][0]",
       "expected true or false, got \"maybe\""},
      {"bad_syntax.yaml", 6, "", "malformed YAML"},
      {"bad_top_level.yaml", 2, "", "expected a map at the top level"},
      {"bad_base_transforms.yaml", 6, "robot_state.multi_dof_joint_state.transforms",
       "expected 2 transforms (one per joint name), got 1"},
  };
}

std::vector<BadCase> badRequests() {
  const std::string constraint = "goal_constraints[0].joint_constraints";
  return {
      {"bad_request_start_joint.yaml", 4, "start_state.joint_state.name[1]",
       "unknown joint 'elbow_joint' (robot 'tiny_model' has the joint variables: panda_joint1, "
       "panda_joint2, panda_finger_joint1)",
       true},
      {"bad_request_goal_joint.yaml", 5, constraint + "[1].joint_name",
       "unknown joint 'wrist_joint'", true},
      {"bad_request_mimic_goal.yaml", 4, constraint + "[0].joint_name",
       "joint 'panda_finger_joint2' is not a variable (a fixed or mimic joint)", true},
      {"bad_request_position_count.yaml", 5, "start_state.joint_state.position",
       "expected 2 positions (one per joint name), got 1", true},
      {"bad_request_two_goals.yaml", 5, "goal_constraints[1]",
       "several goal constraints are not supported", true},
      {"bad_request_position_goal.yaml", 5, "goal_constraints[0].position_constraints",
       "position constraints are not supported (only joint constraints)", true},
      {"bad_request_orientation_goal.yaml", 6, "goal_constraints[0].orientation_constraints",
       "orientation constraints are not supported", true},
      {"bad_request_no_goal.yaml", 2, "", "missing required key 'goal_constraints'", true},
      {"bad_request_empty_goal.yaml", 3, constraint, "there is no joint constraint", true},
      {"bad_request_nan_goal.yaml", 5, constraint + "[0].position",
       "must be a finite number, got .NaN", true},
      {"bad_request_inf_start.yaml", 5, "start_state.joint_state.position[0]",
       "must be a finite number, got +.inf", true},
      {"bad_request_syntax.yaml", 5, "", "malformed YAML", true},
      {"bad_request_planning_time.yaml", 2, "allowed_planning_time", "must not be negative", true},
  };
}

std::string caseName(const ::testing::TestParamInfo<BadCase>& info) {
  std::string name = info.param.file.substr(0, info.param.file.find('.'));
  std::replace(name.begin(), name.end(), '-', '_');
  return name;
}

INSTANTIATE_TEST_SUITE_P(MoveItBadScene, MoveItBadInputTest, ::testing::ValuesIn(badScenes()),
                         caseName);
INSTANTIATE_TEST_SUITE_P(MoveItBadRequest, MoveItBadInputTest, ::testing::ValuesIn(badRequests()),
                         caseName);

// ---------------------------------------------------------------------------------------------
// MotionBenchMaker (../shared/data/mbm/panda) with the built-in Panda

std::vector<fs::path> mbmSceneFiles(const fs::path& root) {
  std::vector<fs::path> scenes;
  for (const auto& entry : fs::recursive_directory_iterator(root)) {
    const std::string name = entry.path().filename().string();
    if (name.starts_with("scene") && entry.path().extension() == ".yaml") {
      scenes.push_back(entry.path());
    }
  }
  std::sort(scenes.begin(), scenes.end());
  return scenes;
}

TEST(MoveItMotionBenchMakerTest, LoadsEveryPandaProblem) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const fs::path root = shared / "mbm" / "panda";
  if (!fs::is_directory(root)) GTEST_SKIP() << root << " is absent: skipped";
  const RobotModelPtr panda = readUrdfFile(builtinRobotUrdf("panda"));
  std::map<std::string, int> loadedPerFamily;
  int clamped = 0;
  for (const fs::path& scene : mbmSceneFiles(root)) {
    try {
      const MoveItProblem problem = readMoveItProblem(scene, requestFileForScene(scene), panda);
      EXPECT_EQ(problem.goalJoints.size(), 7u) << scene;
      EXPECT_FALSE(problem.scene.objects().empty()) << scene;
      EXPECT_TRUE(problem.start.allFinite() && problem.goal.allFinite()) << scene;
      clamped += problem.clampedJoints.empty() ? 0 : 1;
      ++loadedPerFamily[scene.parent_path().filename().string()];
    } catch (const InputError& error) {
      ADD_FAILURE() << error.what();
    }
  }
  EXPECT_EQ(loadedPerFamily.size(), 7u);
  for (const auto& [family, loaded] : loadedPerFamily) EXPECT_EQ(loaded, 100) << family;
  EXPECT_EQ(clamped, 700) << "every MBM start state opens the fingers to 0.065";
}

TEST(MoveItMotionBenchMakerTest, ReadsOneProblemExactly) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const fs::path scene = shared / "mbm" / "panda" / "box_panda" / "scene0001.yaml";
  if (!fs::exists(scene)) GTEST_SKIP() << scene << " is absent: skipped";
  const RobotModelPtr panda = readUrdfFile(builtinRobotUrdf("panda"));
  const MoveItProblem problem = readMoveItProblem(scene, requestFileForScene(scene), panda);
  EXPECT_EQ(problem.robot, "panda");
  EXPECT_EQ(problem.group, "panda_arm");
  EXPECT_EQ(problem.plannerId, "BKPIECEGood");
  EXPECT_DOUBLE_EQ(problem.allowedPlanningTime, 60.0);
  ASSERT_EQ(problem.scene.objects().size(), 7u);
  const SceneObject& can = problem.scene.object("Can1");
  EXPECT_EQ(can.kind, "cylinder");
  EXPECT_EQ(can.pose.translation(),
            Vector3(0.5408380884576693, 0.3580155146897772, -0.3762264457751537));
  expectPose(can.pose, can.pose.translation(),
             Quaternion(0.9972531602635496, 0, 0, 0.07406844364750122));
  EXPECT_DOUBLE_EQ(std::get<Cylinder>(can.collisions.at(0).geometry).length, 0.14);
  EXPECT_DOUBLE_EQ(std::get<Cylinder>(can.collisions.at(0).geometry).radius, 0.03);
  EXPECT_EQ(std::get<Box>(problem.scene.object("side_cap").collisions.at(0).geometry).size,
            Vector3(0.7, 0.7, 0.04));
  EXPECT_DOUBLE_EQ(value(*panda, problem.start, "panda_joint4"), -2.356);
  EXPECT_DOUBLE_EQ(value(*panda, problem.start, "panda_finger_joint1"), 0.04);
  EXPECT_DOUBLE_EQ(value(*panda, problem.goal, "panda_joint1"), 0.4534448383669427);
  EXPECT_DOUBLE_EQ(value(*panda, problem.goal, "panda_joint7"), -0.1898611792470702);
  EXPECT_DOUBLE_EQ(value(*panda, problem.goal, "panda_finger_joint1"), 0.04);
  EXPECT_EQ(problem.allowedCollisions.size(), 34u);
}

}  // namespace
}  // namespace lang2manip
