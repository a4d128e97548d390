#include "lang2manip/model/scene.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include "lang2manip/core/error.hpp"

namespace lang2manip {

std::string objectRoleName(ObjectRole role) {
  switch (role) {
    case ObjectRole::kNone: return "none";
    case ObjectRole::kSupport: return "support";
    case ObjectRole::kContainer: return "container";
  }
  return "none";
}

std::string semanticsSourceName(SemanticsSource source) {
  switch (source) {
    case SemanticsSource::kGiven: return "given";
    case SemanticsSource::kInferred: return "inferred";
    case SemanticsSource::kUser: return "user";
  }
  return "given";
}

ObjectRole objectRoleFromName(const std::string& name) {
  for (const ObjectRole role : {ObjectRole::kNone, ObjectRole::kSupport, ObjectRole::kContainer}) {
    if (objectRoleName(role) == name) return role;
  }
  throw InputError("unknown object role \"" + name + "\"; valid roles: none, support, container");
}

AlignedBox3 SceneObject::localBounds() const {
  AlignedBox3 bounds;
  for (const Shape& shape : collisions) bounds.extend(shapeBounds(shape));
  if (bounds.isEmpty()) {
    for (const Shape& shape : visuals) bounds.extend(shapeBounds(shape));
  }
  if (bounds.isEmpty()) bounds.extend(Vector3::Zero());
  return bounds;
}

AlignedBox3 SceneObject::worldBounds() const {
  const AlignedBox3 local = localBounds();
  AlignedBox3 world;
  for (int corner = 0; corner < 8; ++corner) {
    world.extend(pose * local.corner(static_cast<AlignedBox3::CornerType>(corner)));
  }
  return world;
}

namespace {

template <typename Item>
std::string listNames(const std::vector<Item>& items) {
  std::string names;
  for (const Item& item : items) names += (names.empty() ? "" : ", ") + item.name;
  return names.empty() ? "(none)" : names;
}

template <typename Item>
auto findByName(std::vector<Item>& items, const std::string& name) {
  return std::find_if(items.begin(), items.end(), [&](const Item& item) { return item.name == name; });
}

void checkPose(const Pose& pose, const std::string& what) {
  if (!pose.matrix().allFinite()) throw InputError(what + " has a non-finite pose");
  requirePositionInRange(pose.translation(), what + " position", SourceLocation{});
}

void checkShapes(const SceneObject& object) {
  const SourceLocation where{object.modelSource, 0};
  for (std::size_t i = 0; i < object.collisions.size(); ++i) {
    requireShapeInRange(object.collisions[i], "object \"" + object.name + "\" collision " + std::to_string(i + 1), where);
  }
  for (std::size_t i = 0; i < object.visuals.size(); ++i) {
    requireShapeInRange(object.visuals[i], "object \"" + object.name + "\" visual " + std::to_string(i + 1), where);
  }
}

}  // namespace

void Scene::addRobot(SceneRobot robot) {
  if (!robot.model) throw InputError("robot \"" + robot.name + "\" has no model");
  if (findRobot(robot.name) || findObject(robot.name)) {
    throw InputError("the scene already has an entity named \"" + robot.name + "\"");
  }
  if (robot.configuration.size() == 0) robot.configuration = robot.model->middleConfiguration();
  robot.model->checkConfiguration(robot.configuration, "configuration of \"" + robot.name + "\"");
  checkPose(robot.basePose, "robot \"" + robot.name + "\"");
  robots_.push_back(std::move(robot));
}

void Scene::addObject(SceneObject object) {
  if (object.name.empty()) throw InputError("an object needs a name");
  if (findRobot(object.name) || findObject(object.name)) {
    throw InputError("the scene already has an entity named \"" + object.name + "\"");
  }
  checkPose(object.pose, "object \"" + object.name + "\"");
  checkShapes(object);
  objects_.push_back(std::move(object));
}

void Scene::removeObject(const std::string& name) {
  const auto found = findByName(objects_, name);
  if (found == objects_.end()) static_cast<void>(object(name));  // throws, listing the names
  objects_.erase(found);
  std::erase_if(attachments_, [&](const Attachment& a) { return a.object == name; });
}

const SceneRobot* Scene::findRobot(const std::string& name) const {
  const auto found = std::find_if(robots_.begin(), robots_.end(),
                                  [&](const SceneRobot& robot) { return robot.name == name; });
  return found == robots_.end() ? nullptr : &*found;
}

const SceneObject* Scene::findObject(const std::string& name) const {
  const auto found = std::find_if(objects_.begin(), objects_.end(),
                                  [&](const SceneObject& object) { return object.name == name; });
  return found == objects_.end() ? nullptr : &*found;
}

const SceneRobot& Scene::robot(const std::string& name) const {
  if (const SceneRobot* found = findRobot(name)) return *found;
  throw InputError("the scene has no robot \"" + name + "\"; its robots are: " + listNames(robots_));
}

SceneRobot& Scene::robot(const std::string& name) {
  return const_cast<SceneRobot&>(std::as_const(*this).robot(name));
}

const SceneObject& Scene::object(const std::string& name) const {
  if (const SceneObject* found = findObject(name)) return *found;
  throw InputError("the scene has no object \"" + name + "\"; its objects are: " +
                   listNames(objects_));
}

SceneObject& Scene::object(const std::string& name) {
  return const_cast<SceneObject&>(std::as_const(*this).object(name));
}

void Scene::setConfiguration(const std::string& robotName, const VectorX& q) {
  SceneRobot& target = robot(robotName);
  target.model->checkConfiguration(q, "configuration of \"" + robotName + "\"");
  target.configuration = q;
}

void Scene::attach(Attachment attachment) {
  static_cast<void>(object(attachment.object));
  const SceneRobot& holder = robot(attachment.robot);
  static_cast<void>(holder.model->linkIndex(attachment.link));
  checkPose(attachment.linkToObject, "attachment of \"" + attachment.object + "\"");
  if (findAttachment(attachment.object)) {
    throw InputError("object \"" + attachment.object + "\" is already attached");
  }
  attachments_.push_back(std::move(attachment));
}

void Scene::detach(const std::string& objectName, const Pose& worldPose) {
  const auto found = std::find_if(attachments_.begin(), attachments_.end(),
                                  [&](const Attachment& a) { return a.object == objectName; });
  if (found == attachments_.end()) {
    throw InputError("object \"" + objectName + "\" is not attached to any robot");
  }
  checkPose(worldPose, "object \"" + objectName + "\"");
  object(objectName).pose = worldPose;
  attachments_.erase(found);
}

const Attachment* Scene::findAttachment(const std::string& objectName) const {
  const auto found = std::find_if(attachments_.begin(), attachments_.end(),
                                  [&](const Attachment& a) { return a.object == objectName; });
  return found == attachments_.end() ? nullptr : &*found;
}

Pose Scene::objectWorldPose(const std::string& objectName) const {
  const SceneObject& found = object(objectName);
  const Attachment* held = findAttachment(objectName);
  if (held == nullptr) return found.pose;
  const SceneRobot& holder = robot(held->robot);
  const int link = holder.model->linkIndex(held->link);
  return holder.basePose * holder.model->linkPoses(holder.configuration)[static_cast<std::size_t>(link)] * held->linkToObject;
}

void Scene::setContactTolerance(double metres) {
  if (!std::isfinite(metres) || metres < 0.0 || metres > kMaximumContactTolerance) {
    std::ostringstream message;
    message << "contact tolerance " << metres << " m is not in [0, " << kMaximumContactTolerance << "] m";
    throw InputError(message.str());
  }
  contactTolerance_ = metres;
}

}  // namespace lang2manip
