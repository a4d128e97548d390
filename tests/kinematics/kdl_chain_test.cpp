// makeKdlChain: the KDL chain built from a robot model agrees with our own kinematics.

#include <gtest/gtest.h>

#include <kdl/chainfksolverpos_recursive.hpp>

#include "kinematics/kinematics_test_robots.hpp"
#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/kdl_chain.hpp"
#include "lang2manip/kinematics/kinematic_chain.hpp"

namespace lang2manip {
namespace {

TEST(KdlChain, MatchesOwnForwardKinematics) {
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
