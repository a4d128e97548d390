// libFuzzer harness: MoveIt scene + request YAML (model/moveit_scene_reader.cpp, moveit_yaml.cpp).
// The input goes through fuzz_inputs.hpp, shared with tests/regression/, so a crash saved there
// replays this code.

#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)lang2manip::fuzz::feedMoveItProblem(lang2manip::fuzz::asText(data, size));
  return 0;
}
