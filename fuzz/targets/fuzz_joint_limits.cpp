// libFuzzer harness: a MoveIt joint_limits.yaml applied to the built-in Panda
// (model/joint_limits_reader.cpp).
// The input goes through fuzz_inputs.hpp, shared with tests/regression/, so a crash saved there
// replays this code.

#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)lang2manip::fuzz::feedJointLimits(lang2manip::fuzz::asText(data, size));
  return 0;
}
