// Linked into every harness: libFuzzer calls LLVMFuzzerInitialize once before the first input.
// Warnings the parsers log (e.g. a mesh's missing texture) would flood the fuzzer's output.

#include <string_view>

#include "lang2manip/core/log.hpp"

extern "C" int LLVMFuzzerInitialize(int* /*argc*/, char*** /*argv*/) {
  lang2manip::setLogSink([](lang2manip::LogLevel /*level*/, std::string_view /*message*/) {});
  return 0;
}
