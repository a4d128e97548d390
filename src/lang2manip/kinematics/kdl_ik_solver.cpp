#include "lang2manip/kinematics/kdl_ik_solver.hpp"

#include <algorithm>
#include <map>
#include <string>
#include <tuple>
#include <vector>

#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainiksolverpos_nr_jl.hpp>
#include <kdl/chainiksolvervel_pinv.hpp>

#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/ik_search.hpp"
#include "lang2manip/kinematics/kdl_chain.hpp"

namespace lang2manip {
namespace {

/// KDL's defaults: 100 Newton-Raphson iterations; twist components below this end them.
constexpr unsigned kLmaIterations = 100;
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

/// KDL's chain and solvers for one chain, built once. The solvers keep internal buffers, so an
/// instance serves one thread at a time.
struct KdlChainSolvers {
  KdlChainSolvers(const RobotModel& model, const KinematicChain& source)
      : joints(source.joints()),
        chain(makeKdlChain(model, source)),
        fk(chain),
        velocity(chain),
        ik(chain, fk, velocity, kLmaIterations, kKdlEpsilon) {}
  KdlChainSolvers(const KdlChainSolvers&) = delete;
  KdlChainSolvers& operator=(const KdlChainSolvers&) = delete;

  /// The chain this was built from, to detect a different model at a reused address.
  std::vector<ChainJoint> joints;
  KDL::Chain chain;
  KDL::ChainFkSolverPos_recursive fk;
  KDL::ChainIkSolverVel_pinv velocity;
  KDL::ChainIkSolverPos_NR_JL ik;
};

bool sameJoints(const std::vector<ChainJoint>& a, const std::vector<ChainJoint>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(), [](const ChainJoint& x, const ChainJoint& y) {
    return x.joint == y.joint && x.type == y.type && x.variable == y.variable &&
           x.axis == y.axis && x.origin.matrix() == y.origin.matrix();
  });
}

/// The calling thread's KDL solvers for `problem`'s chain: built on the thread's first call for
/// that chain, then reused (keyed by model and link names, checked against the chain's joints).
KdlChainSolvers& threadSolvers(const IkProblem& problem) {
  /// More chains than any one thread uses in practice; past it the cache starts over.
  constexpr std::size_t kMaxCachedChains = 32;
  using Key = std::tuple<const RobotModel*, std::string, std::string>;
  thread_local std::map<Key, std::unique_ptr<KdlChainSolvers>> cache;
  const Key key{&problem.model, problem.chain.baseLink(), problem.chain.tipLink()};
  auto found = cache.find(key);
  if (found != cache.end() && sameJoints(found->second->joints, problem.chain.joints())) {
    return *found->second;
  }
  if (found == cache.end() && cache.size() >= kMaxCachedChains) cache.clear();
  auto solvers = std::make_unique<KdlChainSolvers>(problem.model, problem.chain);
  return *(cache[key] = std::move(solvers));
}

}  // namespace

IkResult KdlIkSolver::doSolve(const IkProblem& problem) const {
  KdlChainSolvers& kdl = threadSolvers(problem);
  kdl.ik.setJointLimits(toJntArray(problem.lower), toJntArray(problem.upper));
  const KDL::Frame goal = toKdlFrame(kdlGoal(problem));
  IkSearch search(problem);
  if (!restarts_) search.setMaxAttempts(1);
  Random random(problem.randomSeed);
  VectorX start = problem.seed.cwiseMax(problem.lower).cwiseMin(problem.upper);
  KDL::JntArray init = toJntArray(start);
  KDL::JntArray out(kdl.chain.getNrOfJoints());
  while (!search.done()) {
    search.countAttempt();
    init.data = start;
    kdl.ik.CartToJnt(init, goal, out);
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
