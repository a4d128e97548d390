#pragma once
/// @file The route tables of the API server (internal to the server module).

#include <filesystem>
#include <string>
#include <vector>

#include "lang2manip/server/api_server.hpp"
#include "lang2manip/server/api_types.hpp"

namespace lang2manip {

class SessionRegistry;
class RunRegistry;

/// A problem named by a request: a built-in name, or a file under options.dataRoot (throws
/// ApiError 403 for a path outside it, 404 for a file that does not exist).
std::string servedProblem(const ServerOptions& options, const std::string& nameOrPath);
/// The problem `serve PROBLEM` names, loaded once to check it (throws InputError naming it when it
/// cannot be loaded), as an absolute path (a built-in name or "" as it is).
std::string checkedDefaultProblem(const std::string& problem);
/// A robot named by a request (built-in robot name or a .urdf/.xacro under the data root).
std::string servedRobot(const ServerOptions& options, const std::string& nameOrPath);
/// A file under the data root (403 outside it, 404 missing).
std::filesystem::path servedFile(const ServerOptions& options, const std::string& path);

/// Kautham's session verbs: /api/sessions/{client}/openProblem, setPlanner, setQuery, solve,
/// getPath, checkCollision, ... and the session's scene as GLB.
std::vector<ApiRoute> sessionRoutes(SessionRegistry& sessions, const ServerOptions& options);

/// /api/observe, /api/plan and /api/runs (start, list, status, documents, cancel). The event
/// stream of a run is served by the server itself (it streams).
std::vector<ApiRoute> taskRoutes(RunRegistry& runs, const ServerOptions& options);

/// `message` with the data root's absolute path taken out of every file path in it (a client
/// sees paths as it named them, relative to the data root).
std::string withoutDataRoot(const std::string& message, const ServerOptions& options);

/// Runs an API operation, turning lang2manip's errors into ApiError: InputError 400,
/// NotSupportedError 501.
ApiResponse guarded(const std::function<ApiResponse()>& operation);

}  // namespace lang2manip
