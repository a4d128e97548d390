// The KDL/OMPL link-order trap (docs deps.md, trap 1): Debian's libompl and liborocos-kdl both
// export Eigen instantiations (JacobiSVD, products with diagonal matrices, ...) compiled against
// different Eigen versions, and the dynamic linker binds both libraries to the copies of the one
// loaded first. OMPL's prolate hyperspheroid (the informed samplers of BIT*, ABIT*, AIT* and
// informed RRT*) crashes on KDL's copies; KDL's forward kinematics and NR_JL IK, which is all
// lang2manip uses of KDL, run on OMPL's (KDL's LMA solver does not: it is not used).
//
// This binary inherits its link order from lang2manip::kinematics alone and holds no Eigen code
// of ours (an instantiation exported by the executable would serve both libraries and hide the
// order): if the module ever puts KDL first, the hyperspheroid test dies.

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <kdl/chain.hpp>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>
#include <ompl/util/Console.h>
#include <ompl/util/ProlateHyperspheroid.h>

namespace {

TEST(KdlLinkOrder, OmplInformedSamplingRunsInABinaryThatLinksKdl) {
  ompl::msg::setLogLevel(ompl::msg::LOG_WARN);
  for (unsigned dimension : {2U, 7U}) {
    std::vector<double> focus1(dimension, 0.0), focus2(dimension, 0.0);
    for (unsigned i = 0; i < dimension; ++i) focus2[i] = 0.1 * (i + 1);
    ompl::ProlateHyperspheroid phs(dimension, focus1.data(), focus2.data());
    phs.setTransverseDiameter(5.0);
    EXPECT_GT(phs.getPhsMeasure(), 0.0);
    std::vector<double> ball(dimension, 0.1), out(dimension);
    phs.transform(ball.data(), out.data());
    EXPECT_TRUE(phs.isInPhs(out.data()));
  }
}

/// A 6-joint arm with alternating axes (0.3 m links).
KDL::Chain sixJointArm() {
  KDL::Chain chain;
  for (int i = 0; i < 6; ++i) {
    const KDL::Joint joint(i % 2 == 0 ? KDL::Joint::RotZ : KDL::Joint::RotY);
    chain.addSegment(KDL::Segment(joint, KDL::Frame(KDL::Vector(0.0, 0.0, 0.3))));
  }
  return chain;
}

TEST(KdlLinkOrder, KdlNewtonRaphsonIkRunsInABinaryThatLinksOmplFirst) {
  const KDL::Chain chain = sixJointArm();
  KDL::JntArray lower(6), upper(6);
  for (unsigned i = 0; i < 6; ++i) {
    lower(i) = -3.0;
    upper(i) = 3.0;
  }
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::ChainIkSolverVel_pinv velocity(chain);
  KDL::ChainIkSolverPos_NR_JL ik(chain, lower, upper, fk, velocity, 200, 1e-6);
  int solved = 0;
  for (int sample = 0; sample < 20; ++sample) {
    KDL::JntArray target(6), seed(6), out(6);
    for (unsigned i = 0; i < 6; ++i) {
      target(i) = 0.1 * (sample % 7) + 0.2 * i - 0.5;
      seed(i) = std::clamp(target(i) + 0.1, lower(i), upper(i));
    }
    KDL::Frame goal;
    ASSERT_GE(fk.JntToCart(target, goal), 0);
    if (ik.CartToJnt(seed, goal, out) >= 0) ++solved;
  }
  EXPECT_GE(solved, 18);
}

}  // namespace
