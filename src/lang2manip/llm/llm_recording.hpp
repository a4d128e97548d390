#pragma once
/// @file Record / replay of LLM calls (--llm-record FILE, --llm-replay FILE), so that an LLM
/// experiment can be re-run exactly without network. The file is JSON Lines, one call per line:
///   {"client":"openai:gpt-4o","request":{...},"reply":{...}}
///   {"client":"openai:gpt-4o","request":{...},"error":{"kind":"timeout","message":...,"httpStatus":0}}
/// with the request and reply as in llm_json.hpp. No credentials are ever written.

#include <memory>
#include <string>

#include "lang2manip/llm/llm_client.hpp"

namespace lang2manip {

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
/// "FILE:LINE: ..." for a malformed line. Thread-safe.
std::unique_ptr<LlmClient> makeReplayLlmClient(const std::string& file,
                                               const std::string& client = "");

}  // namespace lang2manip
