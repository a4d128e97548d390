// The KDL/OMPL link-order trap (docs deps.md, trap 1): Debian's libompl exports Eigen JacobiSVD
// symbols compiled against an older Eigen. When libompl is loaded before liborocos-kdl, the
// dynamic linker binds KDL's calls to OMPL's copies and ChainIkSolverPos_LMA aborts ("didn't
// compute U"). This binary links both (KDL first, see tests/CMakeLists.txt) and uses OMPL for
// real, so the library is loaded, then runs LMA IK on the Panda: if the order is ever swapped,
// this test dies.

#include <gtest/gtest.h>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_lma.hpp>
#include <ompl/base/spaces/RealVectorStateSpace.h>
#include <ompl/util/Console.h>

#include "kinematics/kinematics_test_robots.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/kdl_chain.hpp"

namespace lang2manip {
namespace {

TEST(KdlLinkOrder, LmaIkRunsInABinaryThatLinksOmpl) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  const ompl::base::RealVectorStateSpace space(7);  // makes sure libompl is really loaded
  EXPECT_EQ(space.getDimension(), 7U);

  const RobotModel& model = test::kinematicsRobot("panda");
  const Manipulator& arm = model.semantics().manipulators.front();
  const KDL::Chain chain = makeKdlChain(model, arm.baseLink, arm.toolFrame);
  ASSERT_EQ(chain.getNrOfJoints(), 7U);
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::ChainIkSolverPos_LMA lma(chain);

  Random random(9);
  int solved = 0;
  for (int sample = 0; sample < 20; ++sample) {
    const VectorX q = random.uniformVector(model.lowerLimits(), model.upperLimits());
    KDL::JntArray target(7);
    for (int i = 0; i < 7; ++i) target(static_cast<unsigned>(i)) = q[model.variableIndex(arm.armJoints[static_cast<std::size_t>(i)])];
    KDL::Frame goal;
    ASSERT_GE(fk.JntToCart(target, goal), 0);
    KDL::JntArray seed(7);
    KDL::JntArray out(7);
    if (lma.CartToJnt(seed, goal, out) >= 0) ++solved;
  }
  EXPECT_GE(solved, 10);
}

TEST(KdlLinkOrder, OwnChainMatchesOwnForwardKinematics) {
  for (const char* robot : {"panda", "ur5", "iiwa14", "tx90"}) {
    const RobotModel& model = test::kinematicsRobot(robot);
    const Manipulator& arm = model.semantics().manipulators.front();
    const KinematicChain own(model, arm.baseLink, arm.toolFrame);
    const KDL::Chain chain = makeKdlChain(model, own);
    KDL::ChainFkSolverPos_recursive fk(chain);
    Random random(13);
    const VectorX q = random.uniformVector(model.lowerLimits(), model.upperLimits());
    VectorX qc(own.dof());
    own.gather(q, qc);
    KDL::JntArray values(static_cast<unsigned>(qc.size()));
    values.data = qc;
    KDL::Frame frame;
    ASSERT_GE(fk.JntToCart(values, frame), 0);
    EXPECT_TRUE(fromKdlFrame(frame).isApprox(own.pose(qc), 1e-9)) << robot;
  }
}

}  // namespace
}  // namespace lang2manip
