// libFuzzer harness: an instruction understood and sequenced (language/clause_parser.cpp, sequencer.cpp).
// The input goes through fuzz_inputs.hpp, shared with tests/regression/, so a crash saved there
// replays this code.

#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)lang2manip::fuzz::feedInstruction(lang2manip::fuzz::asText(data, size));
  return 0;
}
