#pragma once
/// @file Internal: what each DOF of a Kautham control set moves (a joint variable or a base
/// axis of a robot or obstacle), resolved against a loaded problem.

#include <string>
#include <vector>

#include "lang2manip/model/kautham_problem.hpp"

namespace lang2manip {

enum class DofKind { kJoint, kX, kY, kZ, kX1, kX2, kX3 };

struct DofTarget {
  /// Index into scene().robots() (robot controls) or scene().objects() (obstacle controls).
  int entity = 0;
  DofKind kind = DofKind::kJoint;
  /// Joint variable (kJoint only).
  int variable = -1;
};

/// Resolves every DOF of `controls`; throws InputError naming the control file and the DOF's line
/// for an unknown entity, an unknown DOF name (listing the valid ones), or a base DOF without
/// <Limits>.
std::vector<DofTarget> resolveDofTargets(const KauthamProblem& problem, const ControlSet& controls,
                                         bool robots);

/// Default controls: one per movable joint of each robot, plus one per base axis X/Y/Z whose
/// <Limits> have min != max (Kautham's behaviour for an empty robot control file).
ControlSet defaultRobotControls(const KauthamProblem& problem);

}  // namespace lang2manip
