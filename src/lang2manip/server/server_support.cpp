// What every route shares: files named by requests kept under the data root, errors mapped to
// HTTP statuses, and the server's options checked.

#include <algorithm>
#include <filesystem>
#include <new>

#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/llm/llm_client.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/server/server_routes.hpp"
#include "lang2manip/symbolic/task_planner.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

fs::path dataRoot(const ServerOptions& options) {
  std::error_code error;
  const fs::path root = fs::canonical(options.dataRoot.empty() ? fs::current_path() : options.dataRoot, error);
  if (error) throw ApiError(500, "internal_error", "the server's data directory is gone: " + error.message());
  return root;
}

}  // namespace

fs::path servedFile(const ServerOptions& options, const std::string& path) {
  if (path.empty()) throw ApiError(400, "bad_request", "a file name must not be empty");
  if (path.find('\0') != std::string::npos) throw ApiError(400, "bad_request", "a file name must not have a NUL byte");
  const fs::path root = dataRoot(options);
  std::error_code error;
  const fs::path file = fs::weakly_canonical(fs::path(path).is_absolute() ? fs::path(path) : root / path, error);
  const std::string prefix = root == root.root_path() ? root.string() : root.string() + "/";
  if (error || file.string().rfind(prefix, 0) != 0) {
    throw ApiError(403, "forbidden", "file " + path.substr(0, 200) + ": outside the server's data directory");
  }
  if (!fs::is_regular_file(file, error)) throw ApiError(404, "not_found", "file " + path.substr(0, 200) + ": no such file in the data directory");
  return file;
}

namespace {

bool isBuiltinProblem(const std::string& name) {
  const auto& problems = builtinProblems();
  return std::any_of(problems.begin(), problems.end(), [&](const BuiltinProblem& problem) { return problem.shortName == name; });
}

}  // namespace

std::string servedProblem(const ServerOptions& options, const std::string& nameOrPath) {
  // The operator's own problem (serve PROBLEM) is allowed wherever it lies.
  if (nameOrPath.empty() || nameOrPath == options.defaultProblem || isBuiltinProblem(nameOrPath)) return nameOrPath;
  return servedFile(options, nameOrPath).string();
}

std::string checkedDefaultProblem(const std::string& problem) {
  if (problem.empty() || isBuiltinProblem(problem)) return problem;
  try {
    (void)loadProblem(problem, "");
  } catch (const InputError& error) {
    throw InputError("serve: PROBLEM " + problem + ": " + error.what());
  }
  return fs::absolute(problem).lexically_normal().string();
}

std::string servedRobot(const ServerOptions& options, const std::string& nameOrPath) {
  if (nameOrPath.empty()) return nameOrPath;
  const std::vector<std::string> names = builtinRobotNames();
  if (std::find(names.begin(), names.end(), nameOrPath) != names.end()) return nameOrPath;
  return servedFile(options, nameOrPath).string();
}

std::string withoutDataRoot(const std::string& message, const ServerOptions& options) {
  std::error_code error;
  const fs::path root = fs::canonical(options.dataRoot.empty() ? fs::current_path() : options.dataRoot, error);
  if (error || root == root.root_path()) return message;
  std::string text = message;
  const std::string prefix = root.string() + "/";
  for (std::size_t at = text.find(prefix); at != std::string::npos; at = text.find(prefix, at)) text.erase(at, prefix.size());
  return text;
}

ApiResponse guarded(const std::function<ApiResponse()>& operation) {
  try {
    return operation();
  } catch (const ApiError&) {
    throw;
  } catch (const InputError& error) {
    throw ApiError(400, "bad_request", error.what());
  } catch (const NotSupportedError& error) {
    throw ApiError(501, "not_supported", error.what());
  } catch (const LlmError& error) {
    throw ApiError(502, "llm_error", error.what());
  } catch (const PlanningError& error) {
    throw ApiError(422, "planning_failed", error.what());
  } catch (const std::bad_alloc&) {
    throw ApiError(503, "out_of_memory", "the server ran out of memory for this request");
  } catch (const std::exception& error) {
    throw ApiError(500, "internal_error", error.what());
  }
}

void checkServerOptions(const ServerOptions& options) {
  if (options.port < 0 || options.port > 65535) throw InputError("serve: --port " + std::to_string(options.port) + ": expected 0 to 65535");
  if (options.host.empty()) throw InputError("serve: --host must not be empty");
  if (options.token.find_first_of(" \t\r\n;,\"") != std::string::npos) {
    throw InputError("serve: the token must not contain spaces, quotes, commas or semicolons");
  }
  if (options.maxBodyBytes < 1024 || options.maxJsonDepth < 4) throw InputError("serve: body limits below 1 KiB or 4 JSON levels");
  if (options.maxSessions < 1 || options.maxQueuedRuns < 1 || options.maxKeptRuns < 1 || options.maxEventStreams < 1 ||
      options.maxConnections < 2 || options.maxConnections > 4096) {
    throw InputError("serve: session, run and stream limits must be positive, and connections 2 to 4096");
  }
  if (options.maxHeadBytes < 1024 || !(options.headSeconds > 0.0 && options.headSeconds <= 3600.0) ||
      !(options.requestReadSeconds >= options.headSeconds && options.requestReadSeconds <= 3600.0)) {
    throw InputError("serve: request heads of at least 1 KiB, and head and request deadlines of (0, 3600] s "
                     "(the request's no shorter than the head's)");
  }
  if (!(options.maxRequestSeconds > 0.0 && options.maxRequestSeconds <= 86400.0)) {
    throw InputError("serve: --max-request-seconds " + numberText(options.maxRequestSeconds) + ": expected more than 0 and at most 86400");
  }
  std::error_code error;
  if (!options.dataRoot.empty() && !fs::is_directory(options.dataRoot, error)) {
    throw InputError("serve: --data-root " + options.dataRoot.string() + ": not a directory");
  }
  if (!options.viewerDirectory.empty() && !fs::is_regular_file(options.viewerDirectory / "index.html", error)) {
    throw InputError("serve: --viewer " + options.viewerDirectory.string() + ": no index.html in it (build the viewer first)");
  }
}

}  // namespace lang2manip
