#pragma once
/// @file Record / replay of LLM calls (--llm-record FILE, --llm-replay FILE), so that an LLM
/// experiment can be re-run exactly without network. The file is JSON Lines, one call per line:
///   {"client":"openai:gpt-4o","request":{...},"reply":{...}}
///   {"client":"openai:gpt-4o","request":{...},"error":{"kind":"timeout","message":...,"httpStatus":0}}
/// with the request and reply as in llm_json.hpp. No credentials are ever written.

#include <memory>
#include <string>

#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {

/// How long and deep one line of a record file may be when it is replayed: a line holds a request
/// (with earlier answers, each at most HttpOptions::maxResponseBytes) and its reply.
inline constexpr JsonLimits kRecordLineLimits{kDefaultJsonMaxDepth, std::size_t{64} << 20};

/// Wraps `inner` and appends every call to `file` (created when absent): its reply, or the
/// LlmError it ended in (except cancellation, which says nothing about the model). Each line is
/// flushed when written; calls from several threads are serialized. name() is inner's name.
/// Throws LlmError(kConfiguration) when the file cannot be opened for appending.
std::unique_ptr<LlmClient> makeRecordingLlmClient(std::unique_ptr<LlmClient> inner,
                                                  const std::string& file);

/// Answers from a file written by a recording client, without network. A request matches a
/// recorded call when their canonical JSON forms are equal and, when `client` is not empty, the
/// recorded client is `client` (e.g. "openai:gpt-4o"). Identical requests receive the recorded
/// answers in recording order; once those are used up, the last one again. A recorded error is
/// thrown again as the same LlmError kind. A request with no recorded call throws
/// LlmError(kReplayMiss). Replies have replayed = true. name() is "replay:FILE".
/// Throws LlmError(kConfiguration) "FILE: ..." for a file that cannot be read and
/// "FILE:LINE: ..." for a malformed line: not JSON, not the shape above, nested deeper than
/// limits.maxDepth, or longer than limits.maxBytes (such a line is never read whole).
/// Thread-safe.
std::unique_ptr<LlmClient> makeReplayLlmClient(const std::string& file, const std::string& client = "",
                                               const JsonLimits& limits = kRecordLineLimits);

}  // namespace lang2manip
