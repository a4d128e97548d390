// /api/observe, /api/plan and /api/runs: the task pipeline over HTTP.

#include <string>
#include <vector>

#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/task_planner_choice.hpp"
#include "lang2manip/cli/task_run.hpp"
#include "lang2manip/server/run_registry.hpp"
#include "lang2manip/server/server_routes.hpp"
#include "lang2manip/symbolic/observation.hpp"
#include "lang2manip/symbolic/plan_json.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

constexpr std::size_t kMaxTaskBytes = 4096;

std::string taskOf(const json& request, const std::string& fallback) {
  std::string task = body::string(request, "task", fallback);
  if (task.find_first_not_of(" \t\r\n") == std::string::npos) throw ApiError(400, "bad_request", "body field \"task\": must not be empty");
  if (task.size() > kMaxTaskBytes) throw ApiError(400, "bad_request", "body field \"task\": longer than " + std::to_string(kMaxTaskBytes) + " bytes");
  return task;
}

/// The task planner a request names: "offline" or PROVIDER:MODEL with the server's API keys (no
/// base URL, recording or replay from the network).
TaskPlannerChoice plannerOf(const json& request) {
  TaskPlannerChoice choice;
  choice.llm = body::string(request, "llm", kOfflinePlannerSpec);
  return choice;
}

LoadedProblem problemOf(const json& request, const ServerOptions& options) {
  const std::string robot = servedRobot(options, body::string(request, "robot", ""));
  return loadProblem(servedProblem(options, body::string(request, "problem", options.defaultProblem)), robot);
}

ApiResponse observe(const ApiRequest& request, const ServerOptions& options) {
  const LoadedProblem loaded = problemOf(request.body, options);
  const json observation = observeEnvironment(loaded.problem.scene);
  return ApiResponse::json({{"problem", loaded.name}, {"observation", observation}, {"text", observationText(observation)}});
}

json roundsJson(const RepairResult& result) {
  json rounds = json::array();
  for (const RepairRound& round : result.rounds) {
    json value{{"round", round.round}, {"outcome", roundOutcomeName(round.outcome)}};
    if (!round.attempt.failure.empty()) value["failure"] = round.attempt.failure;
    rounds.push_back(std::move(value));
  }
  return rounds;
}

ApiResponse plan(const ApiRequest& request, const ServerOptions& options) {
  const std::string task = taskOf(request.body, "");
  const int rounds = static_cast<int>(body::integer(request.body, "rounds", RepairOptions{}.maxRounds, 1, 10));
  const LoadedProblem loaded = problemOf(request.body, options);
  const SelectedTaskPlanner selected = makeTaskPlanner(plannerOf(request.body));
  PlanningRequest planning;
  planning.task = task;
  planning.scene = &loaded.problem.scene;
  RepairOptions repair;
  repair.maxRounds = rounds;
  const RepairResult result = planWithRepair(selected.planner(), planning, nullptr, repair, request.stop);
  json answer{{"success", result.succeeded()}, {"planner", selected.label()}, {"rounds", roundsJson(result)}};
  if (result.plan) answer["plan"] = toJson(*result.plan);
  if (!result.succeeded()) answer["failure"] = result.failure;
  return ApiResponse::json(answer);
}

/// A run request checked as `run` checks it, and the name of its problem.
std::pair<RunRequest, std::string> runRequestOf(const json& request, const ServerOptions& options) {
  RunRequest run;
  run.problem = servedProblem(options, body::string(request, "problem", options.defaultProblem));
  run.robot = servedRobot(options, body::string(request, "robot", run.robot));
  run.task = taskOf(request, kPaperTask);
  run.planner = plannerOf(request);
  (void)makeTaskPlanner(run.planner);  // an unknown provider or a missing key fails now, not in the queue
  run.motionPlanner = body::string(request, "planner", "");
  run.ik = body::string(request, "ik", "");
  run.arm = body::string(request, "arm", "");
  run.rounds = static_cast<int>(body::integer(request, "rounds", run.rounds, 1, 10));
  run.seed = body::integer(request, "seed", run.seed, 0, 2147483647);
  run.timeLimit = body::number(request, "time_limit", run.timeLimit);
  run.ikTimeout = body::number(request, "ik_timeout", run.ikTimeout);
  run.recordTree = body::boolean(request, "record_tree", false);
  if (!(run.timeLimit > 0.0 && run.timeLimit <= 600.0)) throw ApiError(400, "bad_request", "body field \"time_limit\": expected more than 0 and at most 600 seconds");
  if (!(run.ikTimeout > 0.0 && run.ikTimeout <= 60.0)) throw ApiError(400, "bad_request", "body field \"ik_timeout\": expected more than 0 and at most 60 seconds");
  try {
    run.timing = trajectoryTimingNamed(body::string(request, "timing", trajectoryTimingName(run.timing)));
  } catch (const InputError& error) {
    throw ApiError(400, "bad_request", std::string("body field \"timing\": ") + error.what());
  }
  for (const auto& [field, value] : {std::pair{"velocity_scaling", &run.velocityScaling}, std::pair{"acceleration_scaling", &run.accelerationScaling}}) {
    if (!request.contains(field) || request[field].is_null()) continue;  // the robot's or the default scaling
    const double given = body::number(request, field, 0.0);
    if (const std::string problem = scalingProblem(given); !problem.empty()) {
      throw ApiError(400, "bad_request", std::string("body field \"") + field + "\": " + problem);
    }
    *value = given;
  }
  run.fullSpeed = body::boolean(request, "full_speed", false);
  try {
    std::string problem = checkRunNames(run);  // as `run` does, but before the run waits in the queue
    return {std::move(run), std::move(problem)};
  } catch (const RunNameError& error) {
    throw ApiError(400, "bad_request", "body field \"" + error.field() + "\": " + error.what());
  }
}

}  // namespace

std::vector<ApiRoute> taskRoutes(RunRegistry& runs, const ServerOptions& options) {
  std::vector<ApiRoute> routes;
  routes.push_back({"POST", "/api/observe", [&options](const ApiRequest& request) { return observe(request, options); }, {"problem", "robot"}});
  routes.push_back({"POST", "/api/plan", [&options](const ApiRequest& request) { return plan(request, options); },
                    {"problem", "robot", "task", "llm", "rounds"}});
  routes.push_back({"POST", "/api/runs", [&runs, &options](const ApiRequest& request) {
                      auto [run, problem] = runRequestOf(request.body, options);
                      const std::string id = runs.start(std::move(run), std::move(problem));
                      return ApiResponse::json({{"id", id}, {"state", "queued"}, {"status", "/api/runs/" + id},
                                                {"events", "/api/runs/" + id + "/events"}},
                                               202);
                    },
                    {"problem", "robot", "task", "llm", "planner", "ik", "arm", "rounds", "seed", "time_limit", "ik_timeout", "record_tree", "full_speed",
                     "timing", "velocity_scaling", "acceleration_scaling"}});
  routes.push_back({"GET", "/api/runs", [&runs](const ApiRequest&) { return ApiResponse::json(runs.list()); }});
  routes.push_back({"GET", "/api/runs/{run}", [&runs](const ApiRequest& request) {
                      return ApiResponse::json(runs.status(request.pathParameters.at(0)));
                    }});
  routes.push_back({"POST", "/api/runs/{run}/cancel", [&runs](const ApiRequest& request) {
                      return ApiResponse::json(runs.cancel(request.pathParameters.at(0)), 202);
                    }});
  routes.push_back({"GET", "/api/runs/{run}/files/{document}", [&runs](const ApiRequest& request) {
                      const auto [type, text] = runs.document(request.pathParameters.at(0), request.pathParameters.at(1));
                      return ApiResponse{200, type, text};
                    }});
  return routes;
}

}  // namespace lang2manip
