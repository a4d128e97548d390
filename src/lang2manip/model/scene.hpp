#pragma once
/// @file The world: robots with base poses and joint values, objects with poses and geometry,
/// and which objects are attached to which robot links. A Scene is a value: copy it to branch.

#include <optional>
#include <string>
#include <vector>

#include "lang2manip/core/types.hpp"
#include "lang2manip/model/geometry.hpp"
#include "lang2manip/model/robot_model.hpp"

namespace lang2manip {

/// What an object offers other objects.
enum class ObjectRole { kNone, kSupport, kContainer };

/// "none", "support", "container".
std::string objectRoleName(ObjectRole role);

/// Where an object's movable flag and role come from: its model (a <lang2manip_object> element,
/// or the code that built it), inference from the scene's geometry (inferObjectSemantics), or
/// the user's --movable / --fixed.
enum class SemanticsSource { kGiven, kInferred, kUser };

/// "given", "inferred", "user".
std::string semanticsSourceName(SemanticsSource source);
/// Inverse of objectRoleName(); throws InputError listing the valid names.
ObjectRole objectRoleFromName(const std::string& name);

/// World limits of a mobile base (Kautham <Limits>), per axis X, Y, Z.
struct BaseLimits {
  std::optional<std::pair<double, double>> x;
  std::optional<std::pair<double, double>> y;
  std::optional<std::pair<double, double>> z;
};

struct SceneRobot {
  std::string name;
  RobotModelPtr model;
  /// X_WB: the robot's root link in the world.
  Pose basePose = Pose::Identity();
  /// One value per model variable.
  VectorX configuration;
  BaseLimits baseLimits;
};

struct SceneObject {
  std::string name;
  /// A category such as "marker", "eraser", "pen_holder", "table" (from the model).
  std::string kind;
  /// X_WO.
  Pose pose = Pose::Identity();
  /// Collision geometry in the object frame.
  std::vector<Shape> collisions;
  /// Visual geometry in the object frame (may be empty: then the collisions are drawn).
  std::vector<Shape> visuals;
  bool movable = false;
  ObjectRole role = ObjectRole::kNone;
  SemanticsSource semantics = SemanticsSource::kGiven;
  /// For containers: the free interior in the object frame.
  std::optional<AlignedBox3> cavity;
  /// False when the problem disables collision checking for this object.
  bool collisionEnabled = true;
  BaseLimits poseLimits;
  /// The model file it was read from and the scale applied (empty when built in code).
  std::string modelSource;
  double modelScale = 1.0;

  /// Bounds of the collision geometry in the object frame.
  [[nodiscard]] AlignedBox3 localBounds() const;
  /// Extent of localBounds() along x, y, z.
  [[nodiscard]] Vector3 dimensions() const { return localBounds().sizes(); }
  /// Axis-aligned bounds in the world.
  [[nodiscard]] AlignedBox3 worldBounds() const;
};

/// An object rigidly held by a robot link: X_LO is the object's pose in the link frame.
struct Attachment {
  std::string object;
  std::string robot;
  std::string link;
  Pose linkToObject = Pose::Identity();
};

class Scene {
 public:
  /// Adds a robot; throws InputError when the name is taken or the configuration has the wrong
  /// size or non-finite values.
  void addRobot(SceneRobot robot);
  /// Adds an object; throws InputError when the name is taken or the pose is not finite.
  void addObject(SceneObject object);
  /// Removes an object (and its attachment); throws InputError when unknown.
  void removeObject(const std::string& name);

  [[nodiscard]] const std::vector<SceneRobot>& robots() const noexcept { return robots_; }
  [[nodiscard]] const std::vector<SceneObject>& objects() const noexcept { return objects_; }
  [[nodiscard]] const std::vector<Attachment>& attachments() const noexcept {
    return attachments_;
  }

  /// The robot or object by name; throws InputError listing the valid names when unknown.
  [[nodiscard]] const SceneRobot& robot(const std::string& name) const;
  [[nodiscard]] SceneRobot& robot(const std::string& name);
  [[nodiscard]] const SceneObject& object(const std::string& name) const;
  [[nodiscard]] SceneObject& object(const std::string& name);
  [[nodiscard]] const SceneObject* findObject(const std::string& name) const;
  [[nodiscard]] const SceneRobot* findRobot(const std::string& name) const;

  /// Sets a robot's configuration (checked as in addRobot()).
  void setConfiguration(const std::string& robot, const VectorX& q);

  /// Attaches `object` to `link` of `robot` keeping the given relative pose; throws InputError
  /// for unknown names or an object that is already attached.
  void attach(Attachment attachment);
  /// Detaches `object`, leaving it at `worldPose`; throws InputError if it is not attached.
  void detach(const std::string& object, const Pose& worldPose);
  [[nodiscard]] const Attachment* findAttachment(const std::string& object) const;
  /// Where `object` is in the world: its pose, or where the link holding it carries it. Throws
  /// InputError for an unknown object.
  [[nodiscard]] Pose objectWorldPose(const std::string& object) const;

  /// Penetration (m) up to which two bodies are in contact, not in collision: a robot base or
  /// an object resting exactly on a surface (models rarely meet to the micrometre). Every
  /// collision checker built for this scene uses it; 0 makes any overlap a collision.
  [[nodiscard]] double contactTolerance() const noexcept { return contactTolerance_; }
  /// Throws InputError unless `metres` is finite and in [0, kMaximumContactTolerance].
  void setContactTolerance(double metres);

  static constexpr double kDefaultContactTolerance = 0.0005;
  static constexpr double kMaximumContactTolerance = 0.01;

 private:
  std::vector<SceneRobot> robots_;
  std::vector<SceneObject> objects_;
  std::vector<Attachment> attachments_;
  double contactTolerance_ = kDefaultContactTolerance;
};

}  // namespace lang2manip
