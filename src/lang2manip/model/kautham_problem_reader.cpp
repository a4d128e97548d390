#include <algorithm>
#include <cmath>
#include <set>

#include "lang2manip/core/file_checks.hpp"
#include "lang2manip/core/log.hpp"
#include "lang2manip/core/rotation.hpp"
#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/kautham_dof_target.hpp"
#include "lang2manip/model/object_model.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

class ProblemReader {
 public:
  ProblemReader(const std::filesystem::path& file, const KauthamReadOptions& options)
      : document_(XmlDocument::loadFile(file, "problem file")), options_(options) {
    problem_.file = file;
    prefixes_ = modelPrefixes(file);
    prefixes_.insert(prefixes_.end(), options.modelDirectories.begin(),
                     options.modelDirectories.end());
  }

  /// Where models are searched, as Kautham does: the problem's directory, then the `models/`
  /// directory of it and of each directory above it, nearest first (`problems/p.xml` beside
  /// `models/`, Kautham's `demos/<set>/<scene>/p.xml` under `demos/models/`).
  static std::vector<std::filesystem::path> modelPrefixes(const std::filesystem::path& file) {
    std::error_code error;
    std::filesystem::path directory = std::filesystem::absolute(file, error).parent_path();
    if (error) directory = file.parent_path();
    std::vector<std::filesystem::path> prefixes{directory};
    for (std::filesystem::path above = directory;; above = above.parent_path()) {
      if (std::filesystem::is_directory(above / "models", error)) prefixes.push_back(above / "models");
      if (above == above.parent_path() || above.empty()) break;
    }
    return prefixes;
  }

  /// Attribute `name` of `node` as a number (`fallback` when absent). Kautham reads numbers with
  /// strtod, which stops at the first space: "0.5 0.3" or "0. 5" are read as the number before
  /// the space, with a warning; anything else that is not a number is an error.
  double number(const pugi::xml_node& node, const char* name, double fallback) const {
    const pugi::xml_attribute attribute = node.attribute(name);
    if (!attribute) return fallback;
    const std::string_view text = trimmed(attribute.value());
    const std::size_t space = text.find_first_of(" \t\r\n");
    const std::string what = std::string("<") + node.name() + "> attribute " + name;
    if (space == std::string_view::npos) return parseFiniteNumber(text, what, document_.where(node));
    const double value = parseFiniteNumber(text.substr(0, space), what, document_.where(node));
    logWarning(document_.where(node).toString() + ": " + what + " \"" + std::string(text) + "\" has a space inside: read " +
               exactNumber(value) + ", the number before it, as Kautham does");
    return value;
  }

  KauthamProblem read() {
    const pugi::xml_node root = document_.root();
    if (std::string(root.name()) != "Problem") {
      throw InputError(document_.where(root), std::string("the root element is <") + root.name() +
                                                  ">, not <Problem>: not a Kautham problem file");
    }
    problem_.name = root.attribute("name").value();
    for (const pugi::xml_node& node : root.children("Robot")) readRobot(node);
    if (problem_.robots.empty()) throw InputError(document_.where(root), "the problem has no <Robot>");
    for (const pugi::xml_node& node : root.children("Obstacle")) readObstacle(node);
    readControls(root.child("Controls"));
    readPlanner(root.child("Planner"));
    placeEntities();
    for (const pugi::xml_node& node : root.children("InitialAttachedObstacle")) readAttachment(node);
    return std::move(problem_);
  }

 private:
  std::filesystem::path resolve(const std::string& reference, const pugi::xml_node& node,
                                const std::string& what) const {
    if (reference.empty()) throw InputError(document_.where(node), what + " reference is empty");
    std::error_code error;
    std::vector<std::filesystem::path> candidates;
    for (const std::filesystem::path& prefix : prefixes_) {
      const std::filesystem::path candidate = (prefix / reference).lexically_normal();
      if (std::filesystem::is_regular_file(candidate, error)) return candidate;
      candidates.push_back(candidate);
    }
    throw InputError(document_.where(node), what + " \"" + reference +
                                                "\" resolves to no readable file (" +
                                                triedCandidates(candidates) + ")");
  }

  Pose readHome(const pugi::xml_node& entity) const {
    const pugi::xml_node home = entity.child("Home");
    if (!home) return Pose::Identity();
    const Vector3 translation(number(home, "X", 0.0),
                              number(home, "Y", 0.0),
                              number(home, "Z", 0.0));
    const Vector3 axis(number(home, "WX", 0.0),
                       number(home, "WY", 0.0),
                       number(home, "WZ", 0.0));
    requirePositionInRange(translation, "<Home> X Y Z", document_.where(home));
    const double angle = number(home, "TH", 0.0);
    if (axis.isZero(0.0) && angle != 0.0) {
      logWarning(document_.where(home).toString() + ": <Home> has the zero rotation axis WX=WY=WZ=0 with TH=" +
                 exactNumber(angle) + ": taken as no rotation, as Kautham does");
    }
    return makePose(translation, quaternionFromKauthamAxisAngle(axis, angle));
  }


  BaseLimits readLimits(const pugi::xml_node& entity) const {
    BaseLimits limits;
    for (const pugi::xml_node& node : entity.children("Limits")) {
      const std::string axis = document_.requiredAttribute(node, "name");
      const double low = document_.requiredNumberAttribute(node, "min");
      const double high = document_.requiredNumberAttribute(node, "max");
      if (low > high) {
        throw InputError(document_.where(node), "<Limits name=\"" + axis + "\"> has min > max");
      }
      auto& slot = axis == "X" ? limits.x : axis == "Y" ? limits.y : limits.z;
      if (axis != "X" && axis != "Y" && axis != "Z") {
        throw InputError(document_.where(node), "<Limits name=\"" + axis +
                                                    "\">: the name must be X, Y or Z");
      }
      slot = std::pair{low, high};
    }
    return limits;
  }

  UrdfReadOptions urdfOptionsOf(const KauthamEntity& entity, bool ignoreMimic) const {
    UrdfReadOptions urdfOptions;
    urdfOptions.packagePaths = options_.packagePaths;
    urdfOptions.scale = entity.scale;
    urdfOptions.ignoreMimic = ignoreMimic;
    urdfOptions.xacroArguments = entity.xacroArguments;
    urdfOptions.srdf = entity.srdf;
    if (entity.isRobot) urdfOptions.approachAxes = options_.approachAxes;
    return urdfOptions;
  }

  KauthamEntity readEntity(const pugi::xml_node& node, bool isRobot, RobotModelPtr& model) {
    KauthamEntity entity;
    entity.isRobot = isRobot;
    const char* attribute = isRobot ? "robot" : "obstacle";
    entity.reference = document_.requiredAttribute(node, attribute);
    entity.scale = number(node, "scale", 1.0);
    if (entity.scale <= 0.0) throw InputError(document_.where(node), "scale must be positive");
    entity.resolvedPath = resolve(entity.reference, node, isRobot ? "robot model" : "obstacle model");
    for (const pugi::xml_node& argument : node.children("XacroArg")) {
      entity.xacroArguments[document_.requiredAttribute(argument, "name")] = document_.requiredAttribute(argument, "value");
    }
    for (const auto& [name, value] : options_.xacroArguments) entity.xacroArguments[name] = value;
    if (const pugi::xml_node srdf = node.child("Srdf"); srdf && isRobot) {
      entity.srdf = resolve(document_.requiredAttribute(srdf, "file"), srdf, "SRDF file");
    }
    model = readUrdfFile(entity.resolvedPath, urdfOptionsOf(entity, false));
    const pugi::xml_node kauthamName = node.child("KauthamName");
    entity.name = kauthamName ? document_.requiredAttribute(kauthamName, "name") : model->name();
    if (names_.count(entity.name)) {
      // Kautham keeps the first of two entities with one name and drops the other; we keep both.
      std::string unique;
      for (int n = 2; unique.empty() || names_.count(unique); ++n) unique = entity.name + "_" + std::to_string(n);
      logWarning(document_.where(node).toString() + ": a robot or obstacle is already named \"" + entity.name + "\"; this one is named \"" +
                 unique + "\" (give it a distinct <KauthamName>)");
      entity.name = unique;
    }
    names_.insert(entity.name);
    entity.home = readHome(node);
    entity.limits = readLimits(node);
    entity.inverseKinematics = node.child("InvKinematic").attribute("name").value();
    return entity;
  }

  void readRobot(const pugi::xml_node& node) {
    RobotModelPtr model;
    KauthamEntity entity = readEntity(node, true, model);
    problem_.scene.addRobot(SceneRobot{entity.name, model, entity.home, {}, entity.limits});
    problem_.robots.push_back(std::move(entity));
  }

  void readObstacle(const pugi::xml_node& node) {
    RobotModelPtr model;
    KauthamEntity entity = readEntity(node, false, model);
    SceneObject object = objectFromModel(*model, entity.name, entity.resolvedPath, entity.scale);
    object.pose = entity.home;
    object.poseLimits = entity.limits;
    const pugi::xml_node collision = node.child("Collision");
    if (collision && collision.attribute("enabled")) {
      object.collisionEnabled = parseFlag(collision.attribute("enabled").value(),
                                          "<Collision> attribute enabled", document_.where(collision));
    }
    problem_.scene.addObject(std::move(object));
    problem_.obstacles.push_back(std::move(entity));
  }

  void readControls(const pugi::xml_node& node) {
    const std::string robotFile = node.attribute("robot").value();
    if (robotFile.empty()) {
      problem_.robotControls = defaultRobotControls(problem_);
    } else {
      problem_.robotControls = readControlFile(resolve(robotFile, node, "robot control file"));
      for (const KauthamEntity& robot : problem_.robots) decoupleControlledMimics(robot);
      resolveDofTargets(problem_, problem_.robotControls, true);
    }
    const std::string obstacleFile = node.attribute("obstacle").value();
    if (!obstacleFile.empty()) {
      problem_.obstacleControls = readControlFile(resolve(obstacleFile, node, "obstacle control file"));
      resolveDofTargets(problem_, problem_.obstacleControls, false);
    }
  }

  // Kautham has no mimic joints: a control file may drive a joint the URDF marks as a mimic with
  // its own coefficients. Such a robot is read again with every movable joint independent, so the
  // query maps exactly as Kautham maps it; robots whose mimic joints no control touches keep them.
  void decoupleControlledMimics(const KauthamEntity& entity) {
    SceneRobot& robot = problem_.scene.robot(entity.name);
    bool drivesMimic = false;
    for (const ControlledDof& dof : problem_.robotControls.dofs) {
      if (dof.entity != entity.name) continue;
      for (const Joint& joint : robot.model->joints()) {
        drivesMimic = drivesMimic || (joint.mimic && joint.childLink == dof.dof);
      }
    }
    if (!drivesMimic) return;
    robot.model = readUrdfFile(entity.resolvedPath, urdfOptionsOf(entity, true));
    robot.configuration = robot.model->middleConfiguration();
  }

  void readPlanner(const pugi::xml_node& planner) {
    const pugi::xml_node parameters = planner.child("Parameters");
    problem_.planner.name = std::string(trimmed(parameters.child_value("Name")));
    for (const pugi::xml_node& parameter : parameters.children("Parameter")) {
      problem_.planner.parameters.emplace_back(document_.requiredAttribute(parameter, "name"),
                                               std::string(trimmed(parameter.child_value())));
    }
    for (const pugi::xml_node& query : planner.child("Queries").children("Query")) readQuery(query);
  }

  std::vector<double> controlValues(const pugi::xml_node& node, std::size_t expected,
                                    const std::string& what) const {
    std::vector<double> values = parseNumberList(node.child_value(), what, document_.where(node));
    if (values.size() != expected) {
      throw InputError(document_.where(node), what + " has " + std::to_string(values.size()) +
                                                  " values; the control set has " +
                                                  std::to_string(expected) + " controls");
    }
    checkUnitRange(values, node, what);
    return values;
  }

  void checkUnitRange(const std::vector<double>& values, const pugi::xml_node& node,
                      const std::string& what) const {
    for (const double value : values) {
      if (value < 0.0 || value > 1.0) {
        throw InputError(document_.where(node), what + ": control value " + std::to_string(value) +
                                                    " is outside [0, 1]");
      }
    }
  }

  void readQuery(const pugi::xml_node& node) {
    if (node.child("RobotControl")) {
      readNamedQuery(node);
      return;
    }
    const std::size_t robotCount = problem_.robotControls.controls.size();
    const std::size_t obstacleCount = problem_.obstacleControls.controls.size();
    std::vector<double> obstacles(obstacleCount, 0.5);
    if (const pugi::xml_node initObs = node.child("InitObs")) {
      obstacles = controlValues(initObs, obstacleCount, "<InitObs>");
    }
    std::vector<pugi::xml_node> inits;
    std::vector<pugi::xml_node> goals;
    for (const pugi::xml_node& init : node.children("Init")) inits.push_back(init);
    for (const pugi::xml_node& goal : node.children("Goal")) goals.push_back(goal);
    if (inits.empty() || inits.size() != goals.size()) {
      throw InputError(document_.where(node), "<Query> needs as many <Goal> as <Init> (got " +
                                                  std::to_string(inits.size()) + " and " +
                                                  std::to_string(goals.size()) + ")");
    }
    for (std::size_t i = 0; i < inits.size(); ++i) {
      problem_.queries.push_back({controlValues(inits[i], robotCount, "<Init>"),
                                  controlValues(goals[i], robotCount, "<Goal>"), obstacles});
    }
  }

  void readNamedQuery(const pugi::xml_node& node) {
    const std::vector<std::string> robotNames = problem_.robotControls.controlNames();
    const std::vector<std::string> obstacleNames = problem_.obstacleControls.controlNames();
    KauthamQuery query{std::vector<double>(robotNames.size(), -1.0),
                       std::vector<double>(robotNames.size(), -1.0),
                       std::vector<double>(obstacleNames.size(), 0.5)};
    for (const pugi::xml_node& control : node.children("RobotControl")) {
      const std::size_t index = controlIndex(robotNames, control, "robot");
      query.init[index] = document_.requiredNumberAttribute(control, "init");
      query.goal[index] = document_.requiredNumberAttribute(control, "goal");
      checkUnitRange({query.init[index], query.goal[index]}, control, "<RobotControl>");
    }
    for (const pugi::xml_node& control : node.children("ObstacleControl")) {
      const std::size_t index = controlIndex(obstacleNames, control, "obstacle");
      query.obstacles[index] = document_.requiredNumberAttribute(control, "default");
      checkUnitRange({query.obstacles[index]}, control, "<ObstacleControl>");
    }
    for (std::size_t i = 0; i < robotNames.size(); ++i) {
      if (query.init[i] < 0.0) {
        throw InputError(document_.where(node), "<Query> gives no <RobotControl> for control \"" +
                                                    robotNames[i] + "\"");
      }
    }
    problem_.queries.push_back(std::move(query));
  }

  std::size_t controlIndex(const std::vector<std::string>& names, const pugi::xml_node& node,
                           const std::string& kind) const {
    const std::string name = document_.requiredAttribute(node, "name");
    const auto found = std::find(names.begin(), names.end(), name);
    if (found == names.end()) {
      std::string valid;
      for (const std::string& n : names) valid += (valid.empty() ? "" : ", ") + n;
      throw InputError(document_.where(node), "unknown " + kind + " control \"" + name +
                                                  "\"; the controls are: " +
                                                  (valid.empty() ? "(none)" : valid));
    }
    return static_cast<std::size_t>(found - names.begin());
  }

  void placeEntities() {
    std::vector<double> robotValues(problem_.robotControls.controls.size(), 0.5);
    std::vector<double> obstacleValues(problem_.obstacleControls.controls.size(), 0.5);
    if (!problem_.queries.empty()) {
      robotValues = problem_.queries.front().init;
      obstacleValues = problem_.queries.front().obstacles;
    }
    const RobotStates states = robotStatesFromControls(problem_, robotValues, "initial state");
    for (std::size_t r = 0; r < problem_.robots.size(); ++r) {
      SceneRobot& robot = problem_.scene.robot(problem_.robots[r].name);
      robot.configuration = states.configurations[r];
      robot.basePose = states.basePoses[r];
    }
    const std::vector<Pose> poses = obstaclePosesFromControls(problem_, obstacleValues, "initial state");
    for (std::size_t o = 0; o < problem_.obstacles.size(); ++o) {
      problem_.scene.object(problem_.obstacles[o].name).pose = poses[o];
    }
  }

  void readAttachment(const pugi::xml_node& node) {
    Attachment attachment{document_.requiredAttribute(node, "obstacle"),
                          document_.requiredAttribute(node, "robot"),
                          document_.requiredAttribute(node, "link"), Pose::Identity()};
    try {
      const SceneRobot& robot = problem_.scene.robot(attachment.robot);
      const int link = robot.model->linkIndex(attachment.link);
      const Pose X_WL = robot.basePose * robot.model->linkPoses(robot.configuration)[static_cast<std::size_t>(link)];
      attachment.linkToObject = X_WL.inverse() * problem_.scene.object(attachment.object).pose;
      problem_.scene.attach(attachment);
    } catch (const InputError& error) {
      throw InputError(document_.where(node), std::string("<InitialAttachedObstacle>: ") + error.what());
    }
    problem_.initialAttachments.push_back(attachment);
  }

  XmlDocument document_;
  const KauthamReadOptions& options_;
  std::vector<std::filesystem::path> prefixes_;
  std::set<std::string> names_;
  KauthamProblem problem_;
};

}  // namespace

KauthamProblem readKauthamProblem(const std::filesystem::path& file,
                                  const KauthamReadOptions& options) {
  return ProblemReader(file, options).read();
}

}  // namespace lang2manip
