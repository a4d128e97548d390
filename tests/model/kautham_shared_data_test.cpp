// Every Kautham problem of the shared data loads with its meshes, and a query of each maps to
// joint values and poses computed by hand from its XML, .cntr and URDF files:
//   p = clamp(sum_j eigValue_j * k_j * (c_j - 0.5) + offset, 0, 1)  (offset 0.5 when not given)
//   q = lower + p * (upper - lower)             X_WB = Home * T(x, y, z) * R(X1, X2, X3)
// Skipped when ../shared/data is absent.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <iterator>
#include <numbers>

#include "lang2manip/model/kautham_problem.hpp"
#include "test_paths.hpp"

namespace lang2manip {
namespace {

using ::testing::IsSupersetOf;

constexpr double kSharedDataTolerance = 1e-9;

/// The problems checked by hand below (relative to the shared kautham directory).
const std::vector<std::string>& kHandChecked = test::handCheckedKauthamProblems();

/// Whether `file` holds a problem: a <Problem> element before any <Benchmark> (whose entries are
/// <Problem File=...>), outside the controls directories (which hold other XML files too).
bool isProblemFile(const std::filesystem::path& file) {
  if (file.parent_path().filename() == "controls") return false;
  const std::string text = test::readFileText(file);
  const std::size_t problem = text.find("<Problem");
  return problem != std::string::npos && problem < text.find("<Benchmark");
}

/// Every problem file under `kautham` (root <Problem>; <Benchmark> files list problems), except
/// the models directory.
std::vector<std::string> problemFiles(const std::filesystem::path& kautham) {
  std::vector<std::string> files;
  for (auto it = std::filesystem::recursive_directory_iterator(kautham);
       it != std::filesystem::recursive_directory_iterator(); ++it) {
    if (it->is_directory() && it->path() == kautham / "models") {
      it.disable_recursion_pending();
    } else if (it->is_regular_file() && it->path().extension() == ".xml" && isProblemFile(it->path())) {
      files.push_back(std::filesystem::relative(it->path(), kautham).generic_string());
    }
  }
  return files;
}

void expectMeshesLoaded(const std::vector<Shape>& shapes, const std::string& owner, int& meshCount) {
  for (const Shape& shape : shapes) {
    const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry);
    if (mesh == nullptr) continue;
    ++meshCount;
    ASSERT_NE(mesh->mesh, nullptr) << owner << ": mesh " << mesh->reference << " not loaded";
    EXPECT_FALSE(mesh->mesh->triangles.empty()) << owner << ": mesh " << mesh->reference;
  }
}

/// Reads `relative` and checks that every mesh of its robots and objects was loaded.
KauthamProblem loadProblem(const std::filesystem::path& shared, const std::string& relative) {
  KauthamProblem problem = readKauthamProblem(shared / "kautham" / relative);
  int meshCount = 0;
  for (const SceneRobot& robot : problem.scene.robots()) {
    for (const Link& link : robot.model->links()) {
      expectMeshesLoaded(link.visuals, robot.name + "/" + link.name, meshCount);
      expectMeshesLoaded(link.collisions, robot.name + "/" + link.name, meshCount);
    }
  }
  for (const SceneObject& object : problem.scene.objects()) {
    expectMeshesLoaded(object.visuals, object.name, meshCount);
    expectMeshesLoaded(object.collisions, object.name, meshCount);
  }
  EXPECT_GT(meshCount, 0) << relative;
  return problem;
}

RobotStates statesFor(const KauthamProblem& problem, const std::vector<double>& controls) {
  return robotStatesFromControls(problem, controls, "query");
}

/// Expects joint `joint` of robot 0 in `q` to be `expected`.
void expectJoint(const KauthamProblem& problem, const VectorX& q, const std::string& joint, double expected) {
  const RobotModel& model = *problem.scene.robots()[0].model;
  EXPECT_NEAR(q[model.variableIndex(joint)], expected, kSharedDataTolerance) << joint;
}

void expectTranslation(const Pose& pose, const Vector3& expected) {
  EXPECT_TRUE(pose.translation().isApprox(expected, kSharedDataTolerance))
      << pose.translation().transpose() << " vs " << expected.transpose();
}

/// Expects the rotation of `pose` to be a yaw of `angle`.
void expectYaw(const Pose& pose, double angle) {
  EXPECT_TRUE(
      pose.linear().isApprox(Eigen::AngleAxisd(angle, Vector3::UnitZ()).toRotationMatrix(), kSharedDataTolerance))
      << pose.linear();
}

TEST(KauthamSharedData, EveryProblemLoadsWithItsMeshesAndHasAHandCheckBelow) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const std::vector<std::string> files = problemFiles(shared / "kautham");
  // The hand-computed tests below cover kHandChecked; every other problem must at least load.
  EXPECT_THAT(files, IsSupersetOf(kHandChecked));
  for (const std::string& file : files) {
    SCOPED_TRACE(file);
    // Every mesh must load (loadProblem checks it); the ODE demos are built of primitives only.
    const KauthamProblem problem = file.rfind("OMPL_ode_demos/", 0) != 0
                                       ? loadProblem(shared, file)
                                       : readKauthamProblem(shared / "kautham" / file);
    EXPECT_FALSE(problem.queries.empty());
    EXPECT_FALSE(problem.planner.name.empty());
  }
}

// ur5.urdf / ur5_modern.urdf: every joint in [-6.2831853, 6.2831853]; all offsets 0.5.
constexpr double kUr5Lower = -6.2831853;
constexpr double kUr5Span = 2 * 6.2831853;

TEST(KauthamSharedData, Ur5TableMapsItsQuery) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem = loadProblem(shared, "OMPL_geo_demos/UR5/ur5_table.xml");
  const KauthamQuery& query = problem.queries.at(0);
  const RobotStates init = statesFor(problem, query.init);  // 0.438 0.500 0.625 0.500 0.500 0.500
  expectJoint(problem, init.configurations[0], "ShoulderPanJoint", kUr5Lower + 0.438 * kUr5Span);
  expectJoint(problem, init.configurations[0], "ShoulderLiftJoint", 0.0);
  expectJoint(problem, init.configurations[0], "ElbowJoint", kUr5Lower + 0.625 * kUr5Span);
  expectJoint(problem, init.configurations[0], "Wrist3Joint", 0.0);
  const RobotStates goal = statesFor(problem, query.goal);  // 0.685 0.500 0.625 0.500 0.500 0.500
  expectJoint(problem, goal.configurations[0], "ShoulderPanJoint", kUr5Lower + 0.685 * kUr5Span);
  expectJoint(problem, goal.configurations[0], "ElbowJoint", kUr5Lower + 0.625 * kUr5Span);
  // Home TH="1.0" with an all-zero axis: the identity.
  expectTranslation(init.basePoses[0], Vector3(0, 0, 0.01));
  EXPECT_TRUE(init.basePoses[0].linear().isIdentity(kSharedDataTolerance));
  EXPECT_EQ(problem.planner.name, "omplRRT");
}

TEST(KauthamSharedData, Ur5ConstrainedBoxMapsItsQuery) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem = loadProblem(shared, "OMPL_constr_demos/UR5/ur5_table_constr_box.xml");
  const KauthamQuery& query = problem.queries.at(0);
  const VectorX init = statesFor(problem, query.init).configurations[0];  // 0.2 0.5 0.625 0.375 0.45 0.5
  expectJoint(problem, init, "shoulder_pan_joint", kUr5Lower + 0.2 * kUr5Span);
  expectJoint(problem, init, "shoulder_lift_joint", 0.0);
  expectJoint(problem, init, "elbow_joint", kUr5Lower + 0.625 * kUr5Span);
  expectJoint(problem, init, "wrist_1_joint", kUr5Lower + 0.375 * kUr5Span);
  expectJoint(problem, init, "wrist_2_joint", kUr5Lower + 0.45 * kUr5Span);
  const VectorX goal = statesFor(problem, query.goal).configurations[0];  // 0.29 0.5 0.625 0.375 0.54 0.5
  expectJoint(problem, goal, "shoulder_pan_joint", kUr5Lower + 0.29 * kUr5Span);
  expectJoint(problem, goal, "wrist_2_joint", kUr5Lower + 0.54 * kUr5Span);
  EXPECT_EQ(problem.planner.name, "omplconstr");
}

TEST(KauthamSharedData, Ur5ConstrainedOrientationReordersNamedControls) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem =
      loadProblem(shared, "OMPL_constr_demos/UR5/ur5_table_constr_orientation.xml");
  // <RobotControl> order in the file: shoulder, fore_arm, upper_arm, wrist1..3; the .cntr order
  // is shoulder, upper_arm, fore_arm, wrist1..3.
  const KauthamQuery& query = problem.queries.at(0);
  EXPECT_EQ(query.init, (std::vector<double>{0.25, 0.5, 0.625, 0.5, 0.5, 0.375}));
  EXPECT_EQ(query.goal, (std::vector<double>{0.375, 0.5, 0.625, 0.375, 0.62, 0.5}));
  const VectorX init = statesFor(problem, query.init).configurations[0];
  expectJoint(problem, init, "shoulder_pan_joint", kUr5Lower + 0.25 * kUr5Span);
  expectJoint(problem, init, "elbow_joint", kUr5Lower + 0.625 * kUr5Span);
  expectJoint(problem, init, "wrist_3_joint", kUr5Lower + 0.375 * kUr5Span);
  const VectorX goal = statesFor(problem, query.goal).configurations[0];
  expectJoint(problem, goal, "wrist_1_joint", kUr5Lower + 0.375 * kUr5Span);
  expectJoint(problem, goal, "wrist_2_joint", kUr5Lower + 0.62 * kUr5Span);
  // red_wall: Home TH=1.57 about y at (0.2, 0.4, 0).
  const Pose& wall = problem.scene.object("red_wall").pose;
  expectTranslation(wall, Vector3(0.2, 0.4, 0));
  EXPECT_TRUE(
      (wall.linear() * Vector3::UnitZ()).isApprox(Vector3(std::sin(1.57), 0, std::cos(1.57)), kSharedDataTolerance));
}

TEST(KauthamSharedData, CubeMazeMovesTheFreeFlyingCubeInTheHomeFrame) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem =
      loadProblem(shared, "OMPL_geo_demos/Cube_Maze_R2/OMPL_RRTconnect_bigcube-maze2D_R2.xml");
  // Limits X, Y in [0, 1], Z in [0.056, 0.056]; Home (0.01, 0.01, 0.056), no rotation.
  // (X1..X3 are not in bigcube_R2.cntr; only the translation is checked here.)
  const KauthamQuery& query = problem.queries.at(0);
  EXPECT_EQ(problem.scene.robots()[0].model->variableCount(), 0);
  // Init 0.05 0.7: (0.01 + 0.05, 0.01 + 0.7, 0.056 + 0.056).
  expectTranslation(statesFor(problem, query.init).basePoses[0], Vector3(0.06, 0.71, 0.112));
  // Goal 0.3 0.5: (0.01 + 0.3, 0.01 + 0.5, 0.112).
  expectTranslation(statesFor(problem, query.goal).basePoses[0], Vector3(0.31, 0.51, 0.112));
  expectTranslation(problem.scene.robots()[0].basePose, Vector3(0.06, 0.71, 0.112));
}

// tx90.urdf / tx90_robotniq.urdf arm limits.
struct Tx90Joint {
  const char* name;
  double lower;
  double upper;
};
constexpr Tx90Joint kTx90[] = {
    {"joint_1", -3.141592653589793, 3.141592653589793}, {"joint_2", -2.2689280275926285, 2.5743606466916362},
    {"joint_3", -2.530727415391778, 2.530727415391778}, {"joint_4", -4.71238898038469, 4.71238898038469},
    {"joint_5", -2.007128639793479, 2.443460952792061}, {"joint_6", -4.71238898038469, 4.71238898038469}};

/// Arm joints for control values `c` (offsets 0.5, coefficient 1).
void expectTx90Arm(const KauthamProblem& problem, const VectorX& q, const std::vector<double>& c) {
  for (std::size_t i = 0; i < 6; ++i) {
    expectJoint(problem, q, kTx90[i].name, kTx90[i].lower + c[i] * (kTx90[i].upper - kTx90[i].lower));
  }
}

TEST(KauthamSharedData, Tx90TwoCanMapsItsQuery) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem =
      loadProblem(shared, "OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_TwoCan.xml");
  const KauthamQuery& query = problem.queries.at(0);
  expectTx90Arm(problem, statesFor(problem, query.init).configurations[0],
                {0.373, 0.359, 0.969, 0.332, 0.6, 0.837});
  expectTx90Arm(problem, statesFor(problem, query.goal).configurations[0],
                {0.29, 0.575, 0.842, 0.492, 0.304, 0.665});
  // Home: TH = 3.1415926536 about z at (-0.2005, 0.2301, 0).
  const Pose& base = problem.scene.robots()[0].basePose;
  expectTranslation(base, Vector3(-0.2005, 0.2301, 0));
  expectYaw(base, 3.1415926536);
  EXPECT_EQ(problem.robots[0].inverseKinematics, "TX90");
  // "Speed Factor" (misspelled, without the underscore) is kept as written.
  ASSERT_EQ(problem.planner.parameters.size(), 3U);
  EXPECT_EQ(problem.planner.parameters[1], (std::pair<std::string, std::string>{"Speed Factor", "1"}));
}

TEST(KauthamSharedData, Tx90GripperCouplesSixFingerJointsWithOffsets) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem =
      loadProblem(shared, "OMPL_geo_demos/TX90_IOC/OMPL_RRTConnect_TX90_gripper_TwoCan.xml");
  const KauthamQuery& query = problem.queries.at(0);
  const VectorX init = statesFor(problem, query.init).configurations[0];
  const VectorX goal = statesFor(problem, query.goal).configurations[0];
  expectTx90Arm(problem, init, {0.373, 0.359, 0.969, 0.332, 0.6, 0.837});
  expectTx90Arm(problem, goal, {0.29, 0.575, 0.842, 0.492, 0.304, 0.665});
  // gripper c = 0 (init), 0.199 (goal); drivers in [0, 0.872664444444], others in +-2.96705911111.
  const double driverSpan = 0.872664444444;
  const double fingerLower = -2.96705911111;
  const double fingerSpan = 2 * 2.96705911111;
  for (const std::string side : {"right", "left"}) {
    // driver: offset 0.505, k 0.853: p = 0.505 + 0.853*(0 - 0.5) = 0.0785; goal 0.505 + 0.853*(-0.301) =
    // 0.248247
    expectJoint(problem, init, "gripper_" + side + "_driver_joint", 0.0785 * driverSpan);
    expectJoint(problem, goal, "gripper_" + side + "_driver_joint", 0.248247 * driverSpan);
    // follower: offset 0.418, k -0.099: p = 0.418 + 0.0495 = 0.4675; goal 0.418 + 0.029799 = 0.447799
    expectJoint(problem, init, "gripper_" + side + "_follower_joint", fingerLower + 0.4675 * fingerSpan);
    expectJoint(problem, goal, "gripper_" + side + "_follower_joint", fingerLower + 0.447799 * fingerSpan);
    // spring link: offset 0.558, k 0.124: p = 0.558 - 0.062 = 0.496; goal 0.558 - 0.037324 = 0.520676
    expectJoint(problem, init, "gripper_" + side + "_spring_link_joint", fingerLower + 0.496 * fingerSpan);
    expectJoint(problem, goal, "gripper_" + side + "_spring_link_joint", fingerLower + 0.520676 * fingerSpan);
  }
}

TEST(KauthamSharedData, Ur3eGripperCouplesMirroredFingers) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem = loadProblem(shared, "OMPL_geo_demos/UR3e/ur3e_fib_upc.xml");
  const KauthamQuery& query = problem.queries.at(0);
  // Arm: +-6.28 except the elbow (+-3.14); empty <Offset>: every offset is 0.5.
  const VectorX init = statesFor(problem, query.init).configurations[0];  // 0.5 0.375 0.5 0.375 0.5 0.5 0.2
  expectJoint(problem, init, "shoulder_pan_joint", 0.0);
  expectJoint(problem, init, "shoulder_lift_joint", -6.28 + 0.375 * 12.56);
  expectJoint(problem, init, "elbow_joint", 0.0);
  expectJoint(problem, init, "wrist_1_joint", -6.28 + 0.375 * 12.56);
  // gripper c = 0.2: l_out, l_tip (k = -1, in [-0.523599, 0.610865]): p = 0.5 - (0.2 - 0.5) = 0.8
  //                  r_out, r_tip (k = +1, in [-0.610865, 0.523599]): p = 0.5 + (0.2 - 0.5) = 0.2
  const double span = 0.610865 + 0.523599;
  expectJoint(problem, init, "l_out", -0.523599 + 0.8 * span);
  expectJoint(problem, init, "l_tip", -0.523599 + 0.8 * span);
  expectJoint(problem, init, "r_out", -0.610865 + 0.2 * span);
  expectJoint(problem, init, "r_tip", -0.610865 + 0.2 * span);
  const VectorX goal =
      statesFor(problem, query.goal).configurations[0];  // 0.548 0.342 0.326 0.375 0.625 0.55 0.89
  expectJoint(problem, goal, "shoulder_pan_joint", -6.28 + 0.548 * 12.56);
  expectJoint(problem, goal, "shoulder_lift_joint", -6.28 + 0.342 * 12.56);
  expectJoint(problem, goal, "elbow_joint", -3.14 + 0.326 * 6.28);
  expectJoint(problem, goal, "wrist_2_joint", -6.28 + 0.625 * 12.56);
  expectJoint(problem, goal, "wrist_3_joint", -6.28 + 0.55 * 12.56);
  // gripper c = 0.89: left p = 0.5 - 0.39 = 0.11, right p = 0.5 + 0.39 = 0.89.
  expectJoint(problem, goal, "l_out", -0.523599 + 0.11 * span);
  expectJoint(problem, goal, "r_tip", -0.610865 + 0.89 * span);
  // Home: TH = 1.570796 about (0, 0, -1) at (0.3, -0.2, 0.74).
  const Pose& base = problem.scene.robots()[0].basePose;
  expectTranslation(base, Vector3(0.3, -0.2, 0.74));
  expectYaw(base, -1.570796);
  // wood_piece: TH = 1.570796 with an all-zero axis: no rotation.
  const Pose& wood = problem.scene.object("wood_piece").pose;
  expectTranslation(wood, Vector3(0.43, -0.62, 0.76));
  EXPECT_TRUE(wood.linear().isIdentity(kSharedDataTolerance));
}

TEST(KauthamSharedData, TableRoomsUsesNamedControlsOffsetsAndObstacleControls) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem =
      loadProblem(shared, "OMPL_geo_demos/Table_Rooms_R2/OMPL_RRTconnect_table_rooms_R2_ab.xml");
  const KauthamQuery& query = problem.queries.at(0);
  EXPECT_EQ(query.init, (std::vector<double>{0.6, 0.1}));
  EXPECT_EQ(query.goal, (std::vector<double>{0.85, 0.85}));
  EXPECT_EQ(query.obstacles, (std::vector<double>{0.5, 0.7, 0.8, 0.8}));
  // table: X in [-125, 125], Y in [-115, 115], Z in [50, 50]; Home (0, 0, 50);
  // offsets X1 = X2 = 0, X3 = 0.25: a yaw of 2 pi * 0.25.
  // Init: x = -125 + 0.6*250 = 25, y = -115 + 0.1*230 = -92 -> (25, -92, 50 + 50).
  const Pose init = statesFor(problem, query.init).basePoses[0];
  expectTranslation(init, Vector3(25, -92, 100));
  expectYaw(init, std::numbers::pi / 2);
  // Goal: x = -125 + 0.85*250 = 87.5, y = -115 + 0.85*230 = 80.5.
  expectTranslation(statesFor(problem, query.goal).basePoses[0], Vector3(87.5, 80.5, 100));
  // Obstacles (same limits, X3 offset 0.5: a yaw of pi):
  //   bigbox:   Home z 40; x = -125 + 0.5*250 = 0,  y = -115 + 0.7*230 = 46 -> (0, 46, 90)
  //   smallbox: Home z 35; x = -125 + 0.8*250 = 75, y = -115 + 0.8*230 = 69 -> (75, 69, 85)
  const Pose& bigbox = problem.scene.object("bigbox").pose;
  expectTranslation(bigbox, Vector3(0, 46, 90));
  expectYaw(bigbox, std::numbers::pi);
  const Pose& smallbox = problem.scene.object("smallbox").pose;
  expectTranslation(smallbox, Vector3(75, 69, 85));
  expectYaw(smallbox, std::numbers::pi);
  expectTranslation(problem.scene.object("rooms2").pose, Vector3(0, 0, 25));
}

/// Expects plainbox_1..10 at `xyz[i]` (the controlled values) offset by Home z = 0.1.
void expectPlainBoxes(const KauthamProblem& problem, const std::vector<Vector3>& xyz) {
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const std::string name = "plainbox_" + std::to_string(i + 1);
    SCOPED_TRACE(name);
    expectTranslation(problem.scene.object(name).pose, xyz[i] + Vector3(0, 0, 0.1));
  }
}

TEST(KauthamSharedData, BoxesWorldR2PlacesTheCubeAndTenControlledBoxes) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem =
      loadProblem(shared, "OMPL_geo_demos/boxes_world_R2/OMPL_RRTconnect_boxes_world_R2.xml");
  const KauthamQuery& query = problem.queries.at(0);
  // bigcube: X, Y in [0, 1], Z in [0.056, 0.056], Home (0, 0, 0.056).
  expectTranslation(statesFor(problem, query.init).basePoses[0], Vector3(0.6, 0.1, 0.112));
  expectTranslation(statesFor(problem, query.goal).basePoses[0], Vector3(0.85, 0.85, 0.112));
  // InitObs pairs (x, y) for plainbox_1..10; Z in [0.056, 0.056].
  expectPlainBoxes(problem, {{0.2, 0.2, 0.056},
                             {0.2, 0.4, 0.056},
                             {0.2, 0.6, 0.056},
                             {0.2, 0.8, 0.056},
                             {0.8, 0.2, 0.056},
                             {0.8, 0.4, 0.056},
                             {0.8, 0.6, 0.056},
                             {0.8, 0.8, 0.056},
                             {0.4, 0.4, 0.056},
                             {0.6, 0.6, 0.056}});
}

TEST(KauthamSharedData, BoxesWorldR3PlacesTheCubeAndTenControlledBoxes) {
  LANG2MANIP_REQUIRE_SHARED_DATA(shared);
  const KauthamProblem problem =
      loadProblem(shared, "OMPL_geo_demos/boxes_world_R3/OMPL_RRTconnect_boxes_world_R3.xml");
  const KauthamQuery& query = problem.queries.at(0);
  // bigcube: X, Y, Z in [0, 1], Home (0, 0, 0.056).
  expectTranslation(statesFor(problem, query.init).basePoses[0], Vector3(0.1, 0.1, 0.156));
  expectTranslation(statesFor(problem, query.goal).basePoses[0], Vector3(0.85, 0.85, 0.906));
  // InitObs triples for plainbox_1..10 (X, Y, Z in [0, 1]).
  expectPlainBoxes(problem, {{0.2, 0.2, 0.2},
                             {0.2, 0.2, 0.4},
                             {0.2, 0.4, 0.6},
                             {0.2, 0.4, 0.8},
                             {0.8, 0.8, 0.2},
                             {0.8, 0.6, 0.4},
                             {0.8, 0.4, 0.6},
                             {0.8, 0.8, 0.8},
                             {0.4, 0.4, 0.4},
                             {0.6, 0.6, 0.6}});
}

}  // namespace
}  // namespace lang2manip
