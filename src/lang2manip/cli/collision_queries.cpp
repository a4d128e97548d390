#include "lang2manip/cli/collision_queries.hpp"

#include <cmath>
#include <cstdio>

namespace lang2manip {
namespace {

std::string metres(double value) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.4f m", value);
  return buffer;
}

CollisionReport checkStates(const RobotStates& states, const CollisionChecker& checker,
                            CollisionContext& context) {
  const WorldState state{states.configurations, states.basePoses};
  return checker.checkWorld(state, CollisionRequest{true}, context);
}

}  // namespace

std::vector<QueryCollisions> checkQueries(const LoadedProblem& loaded, const CollisionChecker& checker) {
  const auto context = checker.makeContext();
  std::vector<QueryCollisions> results;
  for (const auto& [start, goal] : loaded.queries) {
    results.push_back({checkStates(start, checker, *context), checkStates(goal, checker, *context)});
  }
  return results;
}

std::vector<std::string> limitViolations(const Scene& scene, const RobotStates& states) {
  std::vector<std::string> violations;
  for (std::size_t r = 0; r < scene.robots().size(); ++r) {
    const SceneRobot& robot = scene.robots()[r];
    for (const std::string& violation : robot.model->limitViolations(states.configurations[r])) {
      violations.push_back(scene.robots().size() > 1 ? robot.name + ": " + violation : violation);
    }
  }
  return violations;
}

nlohmann::json collisionReportJson(const CollisionReport& report) {
  nlohmann::json contacts = nlohmann::json::array();
  for (const CollisionContact& contact : report.contacts) {
    contacts.push_back({{"first", contact.first}, {"second", contact.second},
                        {"penetration_depth", contact.penetrationDepth}});
  }
  nlohmann::json json{{"valid", report.valid}, {"contacts", contacts}};
  if (std::isfinite(report.minimumDistance) && !report.closestFirst.empty()) {
    json["minimum_distance"] = report.minimumDistance;
    json["closest"] = {report.closestFirst, report.closestSecond};
  }
  return json;
}

std::string collisionSummary(const CollisionReport& report) {
  if (report.valid) {
    if (report.closestFirst.empty()) return "collision-free";
    return "collision-free, clearance " + metres(report.minimumDistance) + " (" +
           report.closestFirst + " - " + report.closestSecond + ")";
  }
  std::string text = "in collision:";
  for (std::size_t i = 0; i < report.contacts.size(); ++i) {
    const CollisionContact& contact = report.contacts[i];
    text += (i == 0 ? " " : ", ") + contact.first + " - " + contact.second + " (penetration " +
            metres(contact.penetrationDepth) + ")";
  }
  return text;
}

}  // namespace lang2manip
