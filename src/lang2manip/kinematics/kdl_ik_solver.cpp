#include "lang2manip/kinematics/kdl_ik_solver.hpp"

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>

#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/ik_search.hpp"
#include "lang2manip/kinematics/kdl_chain.hpp"

namespace lang2manip {
namespace {

/// KDL's defaults: 100 Newton-Raphson iterations; twist components below this end them.
constexpr unsigned kMaxIterations = 100;
constexpr double kKdlEpsilon = 1e-6;

KDL::JntArray toJntArray(const VectorX& values) {
  KDL::JntArray array(static_cast<unsigned>(values.size()));
  array.data = values;
  return array;
}

/// The pose KDL is asked for: the target itself, or for an approach-axis target the seed's
/// orientation turned the shortest way onto the approach axis.
Pose kdlGoal(const IkProblem& problem) {
  const IkTarget& target = problem.target;
  Pose goal = Pose::Identity();
  goal.translation() = target.position;
  if (target.kind == IkTarget::Kind::kPose) {
    goal.linear() = target.orientation.toRotationMatrix();
    return goal;
  }
  const Matrix3 seedRotation = problem.chain.pose(problem.seed).linear();
  const Vector3 axis = seedRotation * target.toolAxis;
  goal.linear() = Quaternion::FromTwoVectors(axis, target.approachAxis).toRotationMatrix() *
                  seedRotation;
  return goal;
}

}  // namespace

IkResult KdlIkSolver::doSolve(const IkProblem& problem) const {
  const KDL::Chain chain = makeKdlChain(problem.model, problem.chain);
  KDL::ChainFkSolverPos_recursive fk(chain);
  KDL::ChainIkSolverVel_pinv velocity(chain);
  KDL::ChainIkSolverPos_NR_JL solver(chain, toJntArray(problem.lower), toJntArray(problem.upper),
                                     fk, velocity, kMaxIterations, kKdlEpsilon);
  const KDL::Frame goal = toKdlFrame(kdlGoal(problem));
  IkSearch search(problem);
  if (!restarts_) search.setMaxAttempts(1);
  Random random(problem.randomSeed);
  VectorX start = problem.seed.cwiseMax(problem.lower).cwiseMin(problem.upper);
  KDL::JntArray init = toJntArray(start);
  KDL::JntArray out(chain.getNrOfJoints());
  while (!search.done()) {
    search.countAttempt();
    init.data = start;
    solver.CartToJnt(init, goal, out);
    search.addSolution(out.data, problem.chain.pose(out.data));
    search.randomConfiguration(random, start);
  }
  return search.result();
}

std::unique_ptr<IkSolver> makeKdlIkSolver() { return std::make_unique<KdlIkSolver>(false); }

std::unique_ptr<IkSolver> makeKdlRestartsIkSolver() {
  return std::make_unique<KdlIkSolver>(true);
}

}  // namespace lang2manip
