// libFuzzer harness: a proxy environment variable's value to a proxy, and as a no_proxy list
// (llm/http_proxy.cpp). The input goes through fuzz_inputs.hpp, shared with tests/regression/, so
// a crash saved there replays this code.

#include "fuzz_inputs.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  (void)lang2manip::fuzz::feedProxyUrl(lang2manip::fuzz::asText(data, size));
  return 0;
}
