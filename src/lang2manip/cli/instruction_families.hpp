#pragma once
/// @file Instruction families of the published language-manipulation benchmarks, written from
/// their papers (Code as Policies' simulated tabletop, Liang et al. 2022; CLIPort/Ravens,
/// Shridhar et al. 2021) and instantiated over generated tabletops (tabletop_scenes.hpp): each
/// instance is an instruction, the scene it is given on, a check of the final world that does not
/// depend on how the instruction was understood, and the plan a capable planner would give (to
/// measure grounding alone).

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/random.hpp"
#include "lang2manip/model/scene.hpp"
#include "lang2manip/symbolic/action.hpp"
#include "lang2manip/symbolic/spatial_relations.hpp"

namespace lang2manip {

/// One instruction of a family on one scene.
struct FamilyInstance {
  std::string family;
  std::string instruction;
  Scene scene;
  /// Whether the final world is what the instruction asks for (given the scene before).
  std::function<GoalCheck(const Scene& final, const Scene& initial)> check;
  /// What a capable planner would answer.
  Plan plan;
};

struct InstructionFamily {
  std::string name;
  /// The benchmark it comes from: "CaP" or "Ravens".
  std::string source;
  /// An instance on a new tabletop made from `desk` (a built-in desk scene), or nullopt when the
  /// draw did not give a scene the family can be asked on, or one where it is already done (the
  /// caller draws again).
  std::function<std::optional<FamilyInstance>(const Scene& desk, Random& random)> make;
};

/// Every family, in a fixed order.
const std::vector<InstructionFamily>& instructionFamilies();

}  // namespace lang2manip
