#pragma once
/// @file What each fuzz target does with one input, shared by the libFuzzer harnesses
/// (fuzz/targets/) and the regression test (tests/regression/regression_test.cpp), so that a
/// saved crash input is replayed through exactly the code that found it.
///
/// A feed function returns whether the parser accepted the input or rejected it with its
/// documented error (lang2manip's InputError; LlmError of the documented kind for the LLM
/// parsers). Anything else escapes: another exception type, an LlmError of another kind, or a
/// broken round trip (std::logic_error) is a finding, and so is every crash the sanitizers see.

#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

namespace lang2manip::fuzz {

enum class InputOutcome { kAccepted, kRejected };

/// The parser behind one fuzz target.
struct FuzzTarget {
  /// Name of the harness (fuzz_<name>) and of its corpus and regression directories.
  std::string name;
  InputOutcome (*feed)(std::string_view input);
};

/// Every target, in a fixed order.
const std::vector<FuzzTarget>& fuzzTargets();

/// The target called `name`; throws std::invalid_argument when there is none.
const FuzzTarget& fuzzTarget(std::string_view name);

/// LLM answer text -> Plan (extractJsonDocument + parsePlan), with and without object and
/// planner names to check against; an accepted plan must parse again from its own JSON.
InputOutcome feedPlanText(std::string_view input);

/// An HTTP 2xx response body -> LlmReply, as HttpLlmClient parses it, for each protocol.
InputOutcome feedOpenAiReply(std::string_view input);
InputOutcome feedAnthropicReply(std::string_view input);
InputOutcome feedGeminiReply(std::string_view input);
InputOutcome feedOllamaReply(std::string_view input);

/// A proxy variable's value -> HttpProxy (parseProxyUrl), and the same text as a no_proxy list
/// checked against a few hosts (noProxyMatches); an accepted proxy's origin must parse to itself.
InputOutcome feedProxyUrl(std::string_view input);

/// An --llm-replay file (JSON Lines) -> the replay client.
InputOutcome feedLlmReplay(std::string_view input);

/// An instruction understood over the built-in Panda desk's objects and sequenced into a plan
/// (a refusal is a PlanningError).
InputOutcome feedInstruction(std::string_view input);
/// An instruction corpus (data/corpus/instructions.tsv format).
InputOutcome feedInstructionCorpus(std::string_view input);

/// URDF text (meshes not loaded, so inputs need no sibling files).
InputOutcome feedUrdf(std::string_view input);
/// A xacro file (with inc.xacro and data.yaml beside it to include and load), expanded.
InputOutcome feedXacro(std::string_view input);
/// SRDF text for the built-in Panda.
InputOutcome feedSrdf(std::string_view input);

/// A MoveIt joint_limits.yaml, applied to a copy of the built-in Panda; the limits that result
/// must be valid (positive accelerations and jerks, each range within the URDF's).
InputOutcome feedJointLimits(std::string_view input);

/// A Kautham problem XML; model and control references resolve in the built-in data
/// (data/models and data/problems/desk).
InputOutcome feedKauthamProblem(std::string_view input);
/// A Kautham .cntr file; an accepted control set must read again from its own XML.
InputOutcome feedKauthamControls(std::string_view input);
/// A Kautham <Benchmark> file (its problem files are not read).
InputOutcome feedKauthamBenchmark(std::string_view input);

/// A MoveIt planning scene YAML and its motion plan request for the built-in Panda, in one
/// input: the scene, then a line holding exactly kMoveItRequestSeparator, then the request
/// (no separator: the whole input is the scene, with an empty request).
inline constexpr std::string_view kMoveItRequestSeparator = "#--- request ---";
InputOutcome feedMoveItProblem(std::string_view input);

/// Mesh files through loadTriangleMesh(), one target per format.
InputOutcome feedStlMesh(std::string_view input);
InputOutcome feedObjMesh(std::string_view input);
InputOutcome feedDaeMesh(std::string_view input);
InputOutcome feedPlyMesh(std::string_view input);
InputOutcome feedInventorMesh(std::string_view input);
InputOutcome feedVrmlMesh(std::string_view input);

/// An HTTP request as the server reads it: the first line a URL path and a client id, the rest a
/// JSON body read by every body-field reader (fuzz_viewer_inputs.cpp).
InputOutcome feedApiRequest(std::string_view input);
/// A run directory's viewer inputs: the first line a GLB header, the rest viewer.json.
InputOutcome feedViewerDocument(std::string_view input);

/// The bytes libFuzzer passes, as text.
inline std::string_view asText(const std::uint8_t* data, std::size_t size) {
  return {reinterpret_cast<const char*>(data), size};
}

}  // namespace lang2manip::fuzz
