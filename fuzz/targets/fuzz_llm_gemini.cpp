// libFuzzer harness: Gemini generateContent response body to a reply (llm/gemini_protocol.cpp).
// The input goes through fuzz_inputs.hpp, shared with tests/regression/, so a crash saved there
// replays this code.

#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)lang2manip::fuzz::feedGeminiReply(lang2manip::fuzz::asText(data, size));
  return 0;
}
