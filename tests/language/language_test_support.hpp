#pragma once
/// @file Helpers shared by the language tests: a one-line summary of a TaskSpecification.

#include <string>

#include "lang2manip/language/instruction.hpp"

namespace lang2manip::test {

/// "marker in holder; eraser in holder | grasp marker=side | planner (home)=PRM | planner *=PRM".
inline std::string summarize(const TaskSpecification& specification) {
  std::string text;
  for (const Goal& goal : specification.goals) {
    if (!text.empty()) text += "; ";
    text += describeGoal(goal);
  }
  for (const auto& [object, grasp] : specification.grasps) {
    text += " | grasp " + object + "=" + graspDirectionName(grasp);
  }
  for (const auto& [object, planner] : specification.planners) {
    text += " | planner " + (object.empty() ? std::string("(home)") : object) + "=" + planner;
  }
  if (!specification.defaultPlanner.empty()) text += " | planner *=" + specification.defaultPlanner;
  return text;
}

}  // namespace lang2manip::test
