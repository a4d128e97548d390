#include "lang2manip/llm/llm_recording.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <mutex>
#include <system_error>
#include <variant>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/file_checks.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/llm/llm_json.hpp"
#include "lang2manip/llm/llm_support.hpp"

namespace lang2manip {

namespace {

using nlohmann::json;

class RecordingLlmClient final : public LlmClient {
 public:
  RecordingLlmClient(std::unique_ptr<LlmClient> inner, const std::string& file)
      : inner_(std::move(inner)), file_(file), fd_(openForAppending(file)) {
    if (!inner_) {
      ::close(fd_);
      throw LlmError(LlmErrorKind::kConfiguration, "--llm-record: no client to record");
    }
  }

  [[nodiscard]] std::string name() const override { return inner_->name(); }

  LlmReply complete(const LlmRequest& request, const StopCondition& stop) override {
    json line = {{"client", inner_->name()}, {"request", llmRequestToJson(request)}};
    LlmReply reply;
    try {
      reply = inner_->complete(request, stop);
    } catch (const LlmError& error) {
      if (error.kind() != LlmErrorKind::kCancelled) {
        line["error"] = {{"kind", llmErrorKindName(error.kind())},
                         {"message", error.what()},
                         {"httpStatus", error.httpStatus()}};
        append(line);
      }
      throw;
    }
    line["reply"] = llmReplyToJson(reply);
    append(line);
    return reply;
  }

 private:
  /// The record file opened for appending: created when missing, never through a symbolic link,
  /// never a FIFO or device (an open would block, a write go nowhere).
  static int openForAppending(const std::string& file) {
    const int fd = ::open(file.c_str(), O_WRONLY | O_APPEND | O_CREAT | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC, 0644);
    const auto refuse = [&](const std::string& why) {
      if (fd >= 0) ::close(fd);
      throw LlmError(LlmErrorKind::kConfiguration, file + ": cannot open the LLM record file for appending: " + why);
    };
    if (fd < 0) refuse(errno == ELOOP ? "it is a symbolic link" : std::generic_category().message(errno));
    struct stat status {};
    if (::fstat(fd, &status) != 0 || !S_ISREG(status.st_mode)) refuse("not a regular file");
    ::fcntl(fd, F_SETFL, O_WRONLY | O_APPEND);
    return fd;
  }

  void append(const json& line) {
    std::lock_guard lock(mutex_);
    // Replacing invalid UTF-8 (a non-JSON body quoted in an error) keeps the line writable.
    const std::string text = line.dump(-1, ' ', false, json::error_handler_t::replace) + '\n';
    std::size_t done = 0;
    while (done < text.size()) {
      const ssize_t written = ::write(fd_, text.data() + done, text.size() - done);
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) throw LlmError(LlmErrorKind::kConfiguration, file_ + ": cannot write the LLM record file");
      done += static_cast<std::size_t>(written);
    }
  }

 public:
  ~RecordingLlmClient() override {
    if (fd_ >= 0) ::close(fd_);
  }
  RecordingLlmClient(const RecordingLlmClient&) = delete;
  RecordingLlmClient& operator=(const RecordingLlmClient&) = delete;

 private:
  std::unique_ptr<LlmClient> inner_;
  std::string file_;
  std::mutex mutex_;
  int fd_ = -1;
};

/// One recorded outcome: a reply, or an error to throw again.
using RecordedOutcome = std::variant<LlmReply, LlmError>;

struct RecordedCalls {
  std::deque<RecordedOutcome> pending;
  std::optional<RecordedOutcome> last;
};

class ReplayLlmClient final : public LlmClient {
 public:
  ReplayLlmClient(const std::string& file, std::string client, const JsonLimits& limits)
      : file_(file), client_(std::move(client)), limits_(limits) {
    const std::string notAFile = notRegularFileReason(file);
    if (!notAFile.empty()) {
      throw LlmError(LlmErrorKind::kConfiguration, file + ": LLM replay file " + notAFile);
    }
    std::ifstream in(file, std::ios::binary);
    if (!in) throw LlmError(LlmErrorKind::kConfiguration, file + ": cannot open the LLM replay file");
    std::string text;
    for (int lineNumber = 1;; ++lineNumber) {
      const LineReadStatus status = readBoundedLine(in, text, limits_.maxBytes);
      if (status == LineReadStatus::kEnd) break;
      const std::string where = file + ":" + std::to_string(lineNumber) + ": ";
      if (status == LineReadStatus::kTooLong) {
        throw LlmError(LlmErrorKind::kConfiguration,
                       where + "line longer than " + std::to_string(limits_.maxBytes) +
                           " bytes, the limit for one recorded call");
      }
      if (!text.empty() && text.back() == '\r') text.pop_back();
      if (text.find_first_not_of(" \t") == std::string::npos) continue;
      try {
        readLine(text);
      } catch (const InputError& error) {
        throw LlmError(LlmErrorKind::kConfiguration, where + error.what());
      } catch (const json::exception& error) {
        throw LlmError(LlmErrorKind::kConfiguration, where + "unexpected shape (" + jsonErrorText(error) + ")");
      }
    }
    if (in.bad()) throw LlmError(LlmErrorKind::kConfiguration, file + ": read error in the LLM replay file");
  }

  [[nodiscard]] std::string name() const override { return "replay:" + file_; }

  LlmReply complete(const LlmRequest& request, const StopCondition& stop) override {
    if (stop.shouldStop()) {
      throw LlmError(LlmErrorKind::kCancelled, name() + ": cancelled before the call");
    }
    const std::string key = llmRequestToJson(request).dump();
    std::unique_lock lock(mutex_);
    const auto found = calls_.find(key);
    if (found == calls_.end()) throw miss(request, key);
    RecordedCalls& calls = found->second;
    if (!calls.pending.empty()) {
      calls.last = std::move(calls.pending.front());
      calls.pending.pop_front();
    }
    const RecordedOutcome outcome = *calls.last;
    lock.unlock();
    if (const auto* error = std::get_if<LlmError>(&outcome)) throw *error;
    LlmReply reply = std::get<LlmReply>(outcome);
    reply.replayed = true;
    return reply;
  }

 private:
  void readLine(const std::string& text) {
    const json line = parseJsonWithinLimits(text, limits_, "record");
    if (!line.is_object()) {
      throw InputError("record: expected a JSON object {\"client\", \"request\", \"reply\" or \"error\"}, got " +
                       std::string(line.type_name()) + " " + boundedJsonDump(line));
    }
    if (!line.contains("client") || !line["client"].is_string()) {
      throw InputError("client: missing or not a string");
    }
    const std::string client = line["client"].get<std::string>();
    if (!line.contains("request")) throw InputError("request: missing");
    const std::string key = llmRequestToJson(llmRequestFromJson(line["request"])).dump();
    RecordedOutcome outcome = readOutcome(line);
    ++recordedCount_;
    if (!client_.empty() && client != client_) {
      otherClients_[key] = client;
      return;
    }
    calls_[key].pending.push_back(std::move(outcome));
  }

  static RecordedOutcome readOutcome(const json& line) {
    if (line.contains("reply")) return llmReplyFromJson(line["reply"]);
    if (!line.contains("error")) throw InputError("neither reply nor error");
    const json& error = line["error"];
    if (!error.is_object() || !error.contains("kind") || !error["kind"].is_string()) {
      throw InputError("error.kind: missing or not a string");
    }
    const std::string kindName = error["kind"].get<std::string>();
    const auto kind = llmErrorKindFromName(kindName);
    if (!kind) throw InputError("error.kind: \"" + kindName + "\" is not an LLM error kind");
    if (!error.contains("message") || !error["message"].is_string()) {
      throw InputError("error.message: missing or not a string");
    }
    const int status = error.contains("httpStatus") && error["httpStatus"].is_number_integer()
                           ? error["httpStatus"].get<int>()
                           : 0;
    return LlmError(*kind, error["message"].get<std::string>(), status);
  }

  LlmError miss(const LlmRequest& request, const std::string& key) const {
    std::string message = name() + ": no recorded answer for this request (" +
                          std::to_string(recordedCount_) + " calls recorded";
    if (const auto other = otherClients_.find(key); other != otherClients_.end()) {
      message += "; this request was recorded for " + other->second + ", not " + client_;
    }
    const std::string& last = request.messages.empty() ? std::string() : request.messages.back().content;
    message += "); the last message starts \"" + abbreviated(last, 80) +
               "\". Record it first with --llm-record.";
    return LlmError(LlmErrorKind::kReplayMiss, message);
  }

  std::string file_;
  std::string client_;
  JsonLimits limits_;
  std::mutex mutex_;
  std::map<std::string, RecordedCalls> calls_;
  std::map<std::string, std::string> otherClients_;
  int recordedCount_ = 0;
};

}  // namespace

std::unique_ptr<LlmClient> makeRecordingLlmClient(std::unique_ptr<LlmClient> inner,
                                                  const std::string& file) {
  return std::make_unique<RecordingLlmClient>(std::move(inner), file);
}

std::unique_ptr<LlmClient> makeReplayLlmClient(const std::string& file, const std::string& client,
                                               const JsonLimits& limits) {
  return std::make_unique<ReplayLlmClient>(file, client, limits);
}

}  // namespace lang2manip
