#include "lang2manip/kinematics/dls_ik_solver.hpp"

#include <optional>

#include "lang2manip/core/random.hpp"
#include "lang2manip/kinematics/dls_descent.hpp"
#include "lang2manip/kinematics/ik_search.hpp"

namespace lang2manip {

IkResult DlsIkSolver::doSolve(const IkProblem& problem) const {
  DlsWorkspace w(problem.chain.dof());
  IkSearch search(problem);
  // Made on the first restart only: most targets are solved by the descent from the seed.
  std::optional<Random> random;
  w.q = problem.seed.cwiseMax(problem.lower).cwiseMin(problem.upper);
  while (!search.done()) {
    search.countAttempt();
    if (dlsDescend(problem, w, search)) search.addSolution(w.q, w.pose);
    if (!random) random.emplace(problem.randomSeed);
    search.randomConfiguration(*random, w.q);
  }
  return search.result();
}

std::unique_ptr<IkSolver> makeDlsIkSolver() { return std::make_unique<DlsIkSolver>(); }

}  // namespace lang2manip
