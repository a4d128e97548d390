#pragma once
/// @file Internal: what each DOF of a Kautham control set moves (a joint variable or a base
/// axis of a robot or obstacle), resolved against a loaded problem.

#include <string>
#include <utility>
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

/// The range Kautham maps a joint variable's control [0, 1] onto: the joint's limits, or
/// [-2 pi, 2 pi] for a continuous joint (kautham-format.md). `variable` indexes model's variables.
std::pair<double, double> kauthamJointRange(const RobotModel& model, int variable);

/// Resolves every DOF of `controls`; throws InputError naming the control file and the DOF's line
/// for an unknown entity, an unknown DOF name (listing the valid ones), or a base DOF without
/// <Limits>.
std::vector<DofTarget> resolveDofTargets(const KauthamProblem& problem, const ControlSet& controls,
                                         bool robots);

/// Default controls (kautham-format.md, for an empty robot control file): one per movable joint
/// with a non-empty range, plus one per base axis X/Y/Z whose <Limits> have min != max; a robot
/// with a moving base keeps its Home orientation (X1..X3 offsets 0). Kautham itself also adds
/// X1..X3 controls; lang2manip does not.
ControlSet defaultRobotControls(const KauthamProblem& problem);

}  // namespace lang2manip
