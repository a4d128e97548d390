// Kautham's planning-session verbs over HTTP: one PlanningSession per client id.

#include <algorithm>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "lang2manip/cli/collision_queries.hpp"
#include "lang2manip/cli/problem_loading.hpp"
#include "lang2manip/cli/solve_scene.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/gltf_writer.hpp"
#include "lang2manip/planning/motion_plan_json.hpp"
#include "lang2manip/server/server_routes.hpp"
#include "lang2manip/server/session_registry.hpp"

namespace lang2manip {
namespace {

using nlohmann::json;

json vectorJson(const std::optional<VectorX>& point) {
  if (!point) return nullptr;
  return std::vector<double>(point->data(), point->data() + point->size());
}

json plannerJson(const PlannerSettings& settings) {
  json parameters = json::object();
  for (const auto& [name, value] : settings.omplParameters()) parameters[name] = value;
  json ignored = json::array();
  for (const IgnoredParameter& parameter : settings.ignoredParameters()) {
    ignored.push_back({{"name", parameter.name}, {"value", parameter.value}, {"reason", parameter.reason}});
  }
  return {{"name", settings.planner()}, {"max_planning_time", settings.maxPlanningTime()},
          {"parameters", parameters}, {"accepted_parameters", settings.parameterNames()}, {"ignored_parameters", ignored}};
}

json sessionJson(const std::string& client, const ClientSession& session) {
  json state{{"client", client}, {"open", session.planning.isOpen()}};
  if (!session.planning.isOpen()) return state;
  const KauthamProblem& problem = session.planning.problem();
  state["problem"] = session.problemName;
  state["planner"] = plannerJson(session.planning.plannerSettings());
  state["dof_names"] = session.planning.pathDofNames();
  json robots = json::array();
  for (const SceneRobot& robot : problem.scene.robots()) robots.push_back(robot.name);
  json obstacles = json::array();
  for (const SceneObject& object : problem.scene.objects()) obstacles.push_back(object.name);
  state["robots"] = robots;
  state["obstacles"] = obstacles;
  state["query"] = {{"init", vectorJson(session.planning.init())}, {"goal", vectorJson(session.planning.goal())}};
  state["has_path"] = session.planning.hasPath();
  return state;
}

/// A route on one client's session: {client} is the first path parameter.
ApiRoute verb(SessionRegistry& sessions, const std::string& method, const std::string& name, bool creates,
              std::function<json(ClientSession&, const ApiRequest&)> work, std::vector<std::string> bodyFields = {}) {
  return {method, "/api/sessions/{client}/" + name,
          [&sessions, creates, work = std::move(work)](const ApiRequest& request) {
            json answer;
            const std::string& client = request.pathParameters.at(0);
            sessions.use(client, creates, [&](ClientSession& session) { answer = work(session, request); });
            return ApiResponse::json(answer);
          },
          std::move(bodyFields)};
}

/// A verb that changes the session and answers with its state.
ApiRoute change(SessionRegistry& sessions, const std::string& name, std::vector<std::string> fields,
                std::function<void(ClientSession&, const json&)> work) {
  return verb(
      sessions, "POST", name, false,
      [name, work = std::move(work)](ClientSession& session, const ApiRequest& request) {
        work(session, request.body);
        return json{{"ok", true}, {"verb", name}};
      },
      std::move(fields));
}

std::string queryValue(const ApiRequest& request, const std::string& name) {
  const auto found = request.query.find(name);
  if (found == request.query.end() || found->second.empty()) {
    throw ApiError(400, "bad_request", "query parameter \"" + name + "\" is missing");
  }
  return found->second;
}

json solveJson(const PlanningSession& planning, const MotionPlan& plan) {
  return {{"solved", plan.solved()},
          {"status", motionPlanStatusName(plan.status)},
          {"message", plan.message},
          {"computation_time", planning.getLastPlanComputationTime()},
          {"vertices", planning.getNumVertices()},
          {"edges", planning.getNumEdges()},
          {"statistics", motionPlanStatisticsToJson(plan.statistics)}};
}

std::vector<ApiRoute> problemVerbs(SessionRegistry& sessions, const ServerOptions& options) {
  std::vector<ApiRoute> routes;
  routes.push_back(verb(sessions, "POST", "openProblem", true, [&options](ClientSession& session, const ApiRequest& request) {
    const std::string problem = body::string(request.body, "problem", options.defaultProblem);
    const std::string robot = servedRobot(options, body::string(request.body, "robot", ""));
    LoadedProblem loaded = loadProblem(servedProblem(options, problem), robot);
    session.planning.openProblem(std::move(loaded.problem));
    session.problemName = loaded.name;
    return json{{"ok", true}, {"verb", "openProblem"}, {"problem", loaded.name}, {"format", loaded.format},
                {"queries", session.planning.problem().queries.size()}};
  }, {"problem", "robot"}));
  routes.push_back(change(sessions, "closeProblem", {}, [](ClientSession& session, const json&) {
    session.planning.closeProblem();
    session.problemName.clear();
  }));
  routes.push_back({"GET", "/api/sessions/{client}", [&sessions](const ApiRequest& request) {
                      json state;
                      const std::string& client = request.pathParameters.at(0);
                      sessions.use(client, false, [&](ClientSession& session) { state = sessionJson(client, session); });
                      return ApiResponse::json(state);
                    }});
  routes.push_back({"DELETE", "/api/sessions/{client}", [&sessions](const ApiRequest& request) {
                      const std::string& client = request.pathParameters.at(0);
                      if (!sessions.remove(client)) throw ApiError(404, "not_found", "client \"" + client + "\" has no session");
                      return ApiResponse::json({{"ok", true}, {"closed", client}});
                    }});
  return routes;
}

std::vector<ApiRoute> plannerVerbs(SessionRegistry& sessions, const ServerOptions& options) {
  std::vector<ApiRoute> routes;
  routes.push_back(change(sessions, "setPlanner", {"name", "parameters"}, [](ClientSession& session, const json& request) {
    session.planning.setPlanner(body::string(request, "name"));
    const auto parameters = request.find("parameters");
    if (parameters == request.end() || parameters->is_null()) return;
    if (!parameters->is_object()) throw ApiError(400, "bad_request", "body field \"parameters\": expected an object of NAME: VALUE");
    for (const auto& [name, value] : parameters->items()) {
      if (!value.is_string() && !value.is_number()) {
        throw ApiError(400, "bad_request", "body field \"parameters." + name + "\": expected a string or a number");
      }
      session.planning.setPlannerParameter(name, value.is_string() ? value.get<std::string>() : value.dump());
    }
  }));
  routes.push_back(change(sessions, "setPlannerParameter", {"name", "value"}, [](ClientSession& session, const json& request) {
    const auto value = request.find("value");
    if (value == request.end() || (!value->is_string() && !value->is_number())) {
      throw ApiError(400, "bad_request", "body field \"value\": expected a string or a number");
    }
    session.planning.setPlannerParameter(body::string(request, "name"), value->is_string() ? value->get<std::string>() : value->dump());
  }));
  routes.push_back(change(sessions, "setQuery", {"init", "goal"}, [](ClientSession& session, const json& request) {
    session.planning.setQuery(body::numbers(request, "init"), body::numbers(request, "goal"));
  }));
  routes.push_back(change(sessions, "setInit", {"init"}, [](ClientSession& session, const json& request) {
    session.planning.setInit(body::numbers(request, "init"));
  }));
  routes.push_back(change(sessions, "setGoal", {"goal"}, [](ClientSession& session, const json& request) {
    session.planning.setGoal(body::numbers(request, "goal"));
  }));
  const double maxSeconds = std::min(3600.0, options.maxRequestSeconds);
  routes.push_back(verb(sessions, "POST", "solve", false, [maxSeconds](ClientSession& session, const ApiRequest& request) {
    const double timeLimit = body::number(request.body, "time_limit", 0.0);
    if (timeLimit < 0.0 || timeLimit > maxSeconds) {
      throw ApiError(400, "bad_request", "body field \"time_limit\": expected 0 to " + numberText(maxSeconds) +
                                             " seconds (the server's longest request)");
    }
    // For this solve only: the session's planner keeps its own _Max Planning Time. It stops when
    // the client leaves (request.stop).
    return solveJson(session.planning, timeLimit > 0.0 ? session.planning.solveWithin(timeLimit, request.stop)
                                                       : session.planning.solve(request.stop));
  }, {"time_limit"}));
  routes.push_back(verb(sessions, "GET", "getPath", false, [](ClientSession& session, const ApiRequest&) {
    const MotionPlan& plan = session.planning.getPath();
    return json{{"dof_names", session.planning.pathDofNames()}, {"path", pathToJson(plan.path)},
                {"trajectory", trajectoryToJson(plan.trajectory)}, {"trajectory_joint_robots", trajectoryJointRobots(plan.trajectory)}, {"duration", plan.trajectory.duration()}};
  }));
  return routes;
}

std::vector<ApiRoute> worldVerbs(SessionRegistry& sessions, const ServerOptions& options) {
  std::vector<ApiRoute> routes;
  routes.push_back(verb(sessions, "POST", "checkCollision", false, [](ClientSession& session, const ApiRequest& request) {
    const CollisionReport report = session.planning.checkCollision(body::numbers(request.body, "controls"));
    json answer = collisionReportJson(report);
    answer["summary"] = collisionSummary(report);
    return answer;
  }, {"controls"}));
  routes.push_back(change(sessions, "setRobotsConfig", {"controls"}, [](ClientSession& session, const json& request) {
    session.planning.setRobotsConfig(body::numbers(request, "controls"));
  }));
  routes.push_back(change(sessions, "setObstaclesConfig", {"controls"}, [](ClientSession& session, const json& request) {
    session.planning.setObstaclesConfig(body::numbers(request, "controls"));
  }));
  routes.push_back(change(sessions, "setObstaclePos", {"obstacle", "pose"}, [](ClientSession& session, const json& request) {
    session.planning.setObstaclePos(body::string(request, "obstacle"), body::pose(request, "pose"));
  }));
  routes.push_back(verb(sessions, "GET", "getObstaclePos", false, [](ClientSession& session, const ApiRequest& request) {
    return poseToJson(session.planning.getObstaclePos(queryValue(request, "obstacle")));
  }));
  routes.push_back(change(sessions, "setRobotPos", {"robot", "pose"}, [](ClientSession& session, const json& request) {
    session.planning.setRobotPos(body::string(request, "robot"), body::pose(request, "pose"));
  }));
  routes.push_back(verb(sessions, "GET", "getRobotPos", false, [](ClientSession& session, const ApiRequest& request) {
    return poseToJson(session.planning.getRobotPos(queryValue(request, "robot")));
  }));
  routes.push_back(change(sessions, "addObstacle", {"urdf", "name", "pose", "scale"}, [&options](ClientSession& session, const json& request) {
    const double scale = body::number(request, "scale", 1.0);
    if (!(scale > 0.0)) throw ApiError(400, "bad_request", "body field \"scale\": expected a positive number");
    session.planning.addObstacle(servedFile(options, body::string(request, "urdf")), body::string(request, "name"),
                                 body::pose(request, "pose"), scale);
  }));
  routes.push_back(change(sessions, "removeObstacle", {"name"}, [](ClientSession& session, const json& request) {
    session.planning.removeObstacle(body::string(request, "name"));
  }));
  routes.push_back(change(sessions, "attachObstacle2RobotLink", {"robot", "link", "obstacle"}, [](ClientSession& session, const json& request) {
    session.planning.attachObstacle2RobotLink(body::string(request, "robot"), body::string(request, "link"), body::string(request, "obstacle"));
  }));
  routes.push_back(change(sessions, "detachObstacle", {"obstacle"}, [](ClientSession& session, const json& request) {
    session.planning.detachObstacle(body::string(request, "obstacle"));
  }));
  return routes;
}

/// The session's scene as GLB (binary, so not through verb()), with both geometries (the viewer
/// toggles between them); after a solve that found a path, that path animated and drawn (as
/// `solve --html` draws a query).
ApiRoute sceneRoute(SessionRegistry& sessions) {
  return {"GET", "/api/sessions/{client}/scene.glb", [&sessions](const ApiRequest& request) {
            ApiResponse response{200, "model/gltf-binary", ""};
            sessions.use(request.pathParameters.at(0), false, [&](ClientSession& session) {
              const KauthamProblem& problem = session.planning.problem();
              if (session.planning.hasPath()) {
                const MotionPlan& plan = session.planning.getPath();
                response.body = solveSceneGlb(problem, {SolvedQuery{0, "solved", plan.trajectory, plan.tree}});
                return;
              }
              GltfOptions gltf;
              gltf.geometry = GltfGeometry::kBoth;
              response.body = sceneToGlb(problem.scene, gltf);
            });
            return response;
          }};
}

/// The server's default problem as glTF binary: what the viewer served at / shows when it is
/// given nothing else (written once, on first request).
ApiRoute defaultSceneRoute(const ServerOptions& options) {
  struct Cache {
    std::once_flag once;
    std::string glb;
  };
  auto cache = std::make_shared<Cache>();
  return {"GET", "/api/scene.glb", [cache, &options](const ApiRequest&) {
            std::call_once(cache->once, [&] {
              const LoadedProblem loaded = loadProblem(servedProblem(options, options.defaultProblem), "");
              GltfOptions gltf;
              gltf.geometry = GltfGeometry::kBoth;
              cache->glb = sceneToGlb(loaded.problem.scene, gltf);
            });
            return ApiResponse{200, "model/gltf-binary", cache->glb};
          }};
}

}  // namespace

std::vector<ApiRoute> sessionRoutes(SessionRegistry& sessions, const ServerOptions& options) {
  std::vector<ApiRoute> routes = problemVerbs(sessions, options);
  routes.push_back(sceneRoute(sessions));
  routes.push_back(defaultSceneRoute(options));
  for (ApiRoute& route : plannerVerbs(sessions, options)) routes.push_back(std::move(route));
  for (ApiRoute& route : worldVerbs(sessions, options)) routes.push_back(std::move(route));
  return routes;
}

}  // namespace lang2manip
