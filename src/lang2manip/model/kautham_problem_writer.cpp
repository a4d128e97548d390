#include <algorithm>
#include <cstdio>
#include <fstream>

#include "lang2manip/core/rotation.hpp"
#include "lang2manip/model/kautham_dof_target.hpp"
#include "lang2manip/model/object_model.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {


void writeFile(const std::filesystem::path& path, const std::string& text) {
  std::ofstream stream(path, std::ios::binary | std::ios::trunc);
  stream << text;
  stream.close();
  if (!stream) throw InputError(SourceLocation{path.string(), 0}, "cannot write the file");
}

std::string homeXml(const Pose& pose) {
  Vector3 axis;
  double angle = 0.0;
  axisAngleFromQuaternion(Quaternion(pose.linear()), axis, angle);
  const Vector3& t = pose.translation();
  return "    <Home X=\"" + exactNumber(t.x()) + "\" Y=\"" + exactNumber(t.y()) + "\" Z=\"" + exactNumber(t.z()) +
         "\" WX=\"" + exactNumber(axis.x()) + "\" WY=\"" + exactNumber(axis.y()) + "\" WZ=\"" +
         exactNumber(axis.z()) + "\" TH=\"" + exactNumber(angle) + "\"/>\n";
}

std::string limitsXml(const BaseLimits& limits) {
  std::string xml;
  for (const auto& [name, range] : {std::pair{"X", limits.x}, std::pair{"Y", limits.y},
                                    std::pair{"Z", limits.z}}) {
    if (range) {
      xml += std::string("    <Limits name=\"") + name + "\" min=\"" + exactNumber(range->first) +
             "\" max=\"" + exactNumber(range->second) + "\"/>\n";
    }
  }
  return xml;
}

const KauthamEntity* entityNamed(const std::vector<KauthamEntity>& entities, const std::string& name) {
  for (const KauthamEntity& entity : entities) {
    if (entity.name == name) return &entity;
  }
  return nullptr;
}

std::string relativeReference(const std::filesystem::path& file, const std::filesystem::path& directory) {
  return std::filesystem::relative(std::filesystem::absolute(file), std::filesystem::absolute(directory))
      .generic_string();
}

std::string robotXml(const SceneRobot& robot, const KauthamEntity* entity,
                     const std::filesystem::path& directory) {
  const std::filesystem::path urdf =
      entity ? entity->resolvedPath : std::filesystem::path(robot.model->source());
  if (urdf.empty()) {
    throw NotSupportedError("robot \"" + robot.name +
                            "\" was built in code, not read from a URDF: it cannot be written as a "
                            "Kautham problem");
  }
  const double scale = entity ? entity->scale : 1.0;
  const bool hasBaseLimits = robot.baseLimits.x || robot.baseLimits.y || robot.baseLimits.z;
  const Pose home = entity && hasBaseLimits ? entity->home : robot.basePose;
  std::string arguments;
  if (entity) {
    for (const auto& [name, value] : entity->xacroArguments) {
      arguments += "    <XacroArg name=\"" + xmlEscaped(name) + "\" value=\"" + xmlEscaped(value) + "\"/>\n";
    }
  }
  return "  <Robot robot=\"" + xmlEscaped(relativeReference(urdf, directory)) + "\" scale=\"" +
         exactNumber(scale) + "\">\n" + homeXml(home) + "    <KauthamName name=\"" +
         xmlEscaped(robot.name) + "\"/>\n" + arguments + limitsXml(robot.baseLimits) + "  </Robot>\n";
}

Pose worldPoseOf(const Scene& scene, const SceneObject& object) {
  const Attachment* attachment = scene.findAttachment(object.name);
  if (!attachment) return object.pose;
  const SceneRobot& robot = scene.robot(attachment->robot);
  const int link = robot.model->linkIndex(attachment->link);
  return robot.basePose * robot.model->linkPoses(robot.configuration)[static_cast<std::size_t>(link)] *
         attachment->linkToObject;
}

std::string obstacleXml(const Scene& scene, const SceneObject& object,
                        const std::filesystem::path& directory) {
  const std::string reference = "models/" + object.name + ".urdf";
  writeFile(directory / reference, objectUrdfString(object));
  std::string xml = "  <Obstacle obstacle=\"" + xmlEscaped(reference) + "\" scale=\"1\">\n" +
                    homeXml(worldPoseOf(scene, object)) + "    <KauthamName name=\"" +
                    xmlEscaped(object.name) + "\"/>\n" + limitsXml(object.poseLimits);
  if (!object.collisionEnabled) xml += "    <Collision enabled=\"false\"/>\n";
  return xml + "  </Obstacle>\n";
}

// Normalized values of `problem`'s scene configurations under default controls `controls`;
// `clamp` keeps them in [0,1] (a file Kautham reads), otherwise a value outside the limits maps
// outside [0,1] (so a query outside the limits is refused, not moved inside them).
std::vector<double> normalizedControls(const KauthamProblem& problem, const ControlSet& controls,
                                       const std::vector<VectorX>& configurations, bool clamp = true) {
  const auto limited = [clamp](double value) { return clamp ? std::clamp(value, 0.0, 1.0) : value; };
  const std::vector<DofTarget> targets = resolveDofTargets(problem, controls, true);
  std::vector<double> values;
  for (std::size_t d = 0; d < targets.size(); ++d) {
    const SceneRobot& robot = problem.scene.robots()[static_cast<std::size_t>(targets[d].entity)];
    if (targets[d].kind != DofKind::kJoint) {
      const Vector3 offset = (problem.robots[static_cast<std::size_t>(targets[d].entity)].home.inverse() *
                              robot.basePose).translation();
      const auto axis = static_cast<Eigen::Index>(targets[d].kind) - 1;
      const auto& range = axis == 0 ? robot.baseLimits.x : axis == 1 ? robot.baseLimits.y : robot.baseLimits.z;
      values.push_back(limited((offset[axis] - range->first) / (range->second - range->first)));
      continue;
    }
    const RobotModel& model = *robot.model;
    const auto [lower, upper] = kauthamJointRange(model, targets[d].variable);
    const double q = configurations[static_cast<std::size_t>(targets[d].entity)][targets[d].variable];
    values.push_back(upper > lower ? limited((q - lower) / (upper - lower)) : 0.5);
  }
  return values;
}

std::string valuesText(const std::vector<double>& values) {
  std::string text;
  for (const double value : values) text += (text.empty() ? "" : " ") + exactNumber(value);
  return text;
}

std::string queriesXml(const KauthamProblem& problem, const KauthamProblem& target) {
  std::vector<VectorX> current;
  for (const SceneRobot& robot : problem.scene.robots()) current.push_back(robot.configuration);
  std::vector<std::pair<std::vector<VectorX>, std::vector<VectorX>>> queries;
  for (std::size_t i = 0; i < problem.queries.size(); ++i) {
    const KauthamQuery& query = problem.queries[i];
    const RobotStates goal = robotStatesFromControls(problem, query.goal, "query goal");
    const RobotStates init = robotStatesFromControls(problem, query.init, "query init");
    queries.emplace_back(i == 0 ? current : init.configurations, goal.configurations);
  }
  if (queries.empty()) queries.emplace_back(current, current);
  std::string xml = "    <Queries>\n";
  for (const auto& [init, goal] : queries) {
    xml += "      <Query>\n        <Init>" + valuesText(normalizedControls(target, target.robotControls, init)) +
           "</Init>\n        <Goal>" + valuesText(normalizedControls(target, target.robotControls, goal)) +
           "</Goal>\n      </Query>\n";
  }
  return xml + "    </Queries>\n";
}

std::string plannerXml(const KauthamProblem& problem, const KauthamProblem& target) {
  std::string xml = "  <Planner>\n    <Parameters>\n";
  if (!problem.planner.name.empty()) xml += "      <Name>" + xmlEscaped(problem.planner.name) + "</Name>\n";
  for (const auto& [name, value] : problem.planner.parameters) {
    xml += "      <Parameter name=\"" + xmlEscaped(name) + "\">" + xmlEscaped(value) + "</Parameter>\n";
  }
  return xml + "    </Parameters>\n" + queriesXml(problem, target) + "  </Planner>\n";
}

}  // namespace

KauthamQuery kauthamQueryFromStates(const KauthamProblem& problem, const std::vector<VectorX>& init,
                                    const std::vector<VectorX>& goal) {
  for (const auto* states : {&init, &goal}) {
    if (states->size() != problem.scene.robots().size()) {
      throw InputError("a query needs one configuration per robot (" +
                       std::to_string(problem.scene.robots().size()) + "), got " +
                       std::to_string(states->size()));
    }
    for (std::size_t r = 0; r < states->size(); ++r) {
      const SceneRobot& robot = problem.scene.robots()[r];
      robot.model->checkConfiguration((*states)[r], "query configuration of \"" + robot.name + "\"");
    }
  }
  KauthamQuery query;
  query.init = normalizedControls(problem, problem.robotControls, init, false);
  query.goal = normalizedControls(problem, problem.robotControls, goal, false);
  return query;
}

KauthamProblem kauthamProblemFromScene(const Scene& scene, const std::string& name) {
  KauthamProblem problem;
  problem.name = name;
  problem.scene = scene;
  for (const SceneRobot& robot : scene.robots()) {
    KauthamEntity entity;
    entity.name = robot.name;
    entity.isRobot = true;
    entity.resolvedPath = robot.model->source();
    entity.home = robot.basePose;
    entity.limits = robot.baseLimits;
    problem.robots.push_back(entity);
  }
  problem.robotControls = defaultRobotControls(problem);
  return problem;
}

std::filesystem::path writeKauthamProblem(const KauthamProblem& problem,
                                          const std::filesystem::path& directory,
                                          const std::string& stem) {
  std::error_code error;
  std::filesystem::create_directories(directory / "controls", error);
  std::filesystem::create_directories(directory / "models", error);
  if (error) {
    throw InputError(SourceLocation{directory.string(), 0}, "cannot create the directory: " + error.message());
  }
  KauthamProblem target = problem;
  target.robotControls = defaultRobotControls(problem);
  std::string xml = "<?xml version=\"1.0\"?>\n<!-- Written by lang2manip. -->\n<Problem name=\"" +
                    xmlEscaped(problem.name) + "\">\n";
  for (const SceneRobot& robot : problem.scene.robots()) {
    xml += robotXml(robot, entityNamed(problem.robots, robot.name), directory);
  }
  for (const SceneObject& object : problem.scene.objects()) xml += obstacleXml(problem.scene, object, directory);
  const std::string controls = "controls/" + stem + ".cntr";
  writeFile(directory / controls, writeControlString(target.robotControls));
  xml += "  <Controls robot=\"" + xmlEscaped(controls) + "\"/>\n";
  for (const Attachment& attachment : problem.scene.attachments()) {
    xml += "  <InitialAttachedObstacle robot=\"" + xmlEscaped(attachment.robot) + "\" link=\"" +
           xmlEscaped(attachment.link) + "\" obstacle=\"" + xmlEscaped(attachment.object) + "\"/>\n";
  }
  xml += plannerXml(problem, target) + "</Problem>\n";
  const std::filesystem::path file = directory / (stem + ".xml");
  writeFile(file, xml);
  return file;
}

}  // namespace lang2manip
