#include "lang2manip/collision/fcl_collision_world.hpp"

#include <fcl/narrowphase/collision.h>

#include <algorithm>
#include <map>
#include <thread>

#include "lang2manip/collision/allowed_collision_cache.hpp"
#include "lang2manip/collision/allowed_collision_disk_cache.hpp"
#include "lang2manip/collision/fcl_collision_checker.hpp"
#include "lang2manip/collision/fcl_mesh_cache.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/kinematics/forward_kinematics.hpp"

namespace lang2manip {
namespace {

using LinkShapes = std::vector<std::vector<FclShape>>;

LinkShapes linkShapes(const RobotModel& model, FclGeometryBuilder& builder) {
  LinkShapes shapes;
  for (const Link& link : model.links()) shapes.push_back(builder.build(link.collisions));
  return shapes;
}

bool worldBoxesOverlap(const FclShape& a, const Pose& X_WA, const FclShape& b, const Pose& X_WB) {
  const Vector3 ca = X_WA * a.localCenter;
  const Vector3 cb = X_WB * b.localCenter;
  const Vector3 ha = X_WA.linear().cwiseAbs() * a.localHalfExtent;
  const Vector3 hb = X_WB.linear().cwiseAbs() * b.localHalfExtent;
  return ((ca - cb).cwiseAbs() - ha - hb).maxCoeff() <= 0.0;
}

bool shapesCollide(const FclShape& a, const Pose& X_WA, const FclShape& b, const Pose& X_WB) {
  if (!worldBoxesOverlap(a, X_WA, b, X_WB)) return false;
  fcl::CollisionRequestd request;
  fcl::CollisionResultd result;
  fcl::collide(a.geometry.get(), X_WA, b.geometry.get(), X_WB, request, result);
  return result.isCollision();
}

/// The sampled link-pair test of the ACM: every pair of distinct links with geometry.
LinkCollisionTest linkTest(const RobotModel& model, const LinkShapes& shapes) {
  return [&model, &shapes](const VectorX& q, const std::vector<char>& pairsToTest, std::vector<char>& inCollision) {
    const std::size_t links = shapes.size();
    const std::vector<Pose> X_RL = model.linkPoses(q);
    for (std::size_t a = 0; a < links; ++a) {
      for (std::size_t b = a + 1; b < links; ++b) {
        if (pairsToTest[a * links + b] == 0) continue;
        bool hit = false;
        for (const FclShape& sa : shapes[a]) {
          for (const FclShape& sb : shapes[b]) {
            hit = hit || shapesCollide(sa, X_RL[a] * sa.origin, sb, X_RL[b] * sb.origin);
          }
        }
        if (hit) inCollision[a * links + b] = inCollision[b * links + a] = 1;
      }
    }
  };
}

/// Links an object held by `link` may touch: the link, links rigidly attached to it, and the
/// finger links of each gripper mounted there (links moved by its gripper joints or their mimics).
std::vector<char> holdingLinks(const RobotModel& model, int link) {
  const std::vector<int> groups = rigidLinkGroups(model);
  std::vector<char> excluded(model.links().size(), 0);
  for (std::size_t l = 0; l < excluded.size(); ++l) {
    excluded[l] = groups[l] == groups[static_cast<std::size_t>(link)] ? 1 : 0;
  }
  for (const Manipulator& arm : model.semantics().manipulators) {
    std::vector<char> fingers(model.links().size(), 0);
    int hand = -1;
    for (std::size_t j = 0; j < model.joints().size(); ++j) {
      const Joint& joint = model.joints()[j];
      const auto& names = arm.gripperJoints;
      const bool gripper = std::find(names.begin(), names.end(), joint.name) != names.end() ||
                           (joint.mimic && std::find(names.begin(), names.end(),
                                                     joint.mimic->sourceJoint) != names.end());
      const int parent = model.parentLinkOf(static_cast<int>(j));
      const int child = model.childLinkOf(static_cast<int>(j));
      if (gripper && hand < 0) hand = parent;
      if (gripper || fingers[static_cast<std::size_t>(parent)] != 0) fingers[static_cast<std::size_t>(child)] = 1;
    }
    const bool holds = fingers[static_cast<std::size_t>(link)] != 0 ||
                       (hand >= 0 && groups[static_cast<std::size_t>(hand)] == groups[static_cast<std::size_t>(link)]);
    if (!holds) continue;
    for (std::size_t l = 0; l < excluded.size(); ++l) excluded[l] = excluded[l] || fingers[l];
  }
  return excluded;
}

/// Every collision mesh of the scene's robots and enabled objects.
std::vector<const MeshGeometry*> sceneMeshes(const Scene& scene) {
  std::vector<const MeshGeometry*> meshes;
  const auto add = [&meshes](const std::vector<Shape>& shapes) {
    for (const Shape& shape : shapes) {
      if (const auto* mesh = std::get_if<MeshGeometry>(&shape.geometry)) meshes.push_back(mesh);
    }
  };
  for (const SceneRobot& robot : scene.robots()) {
    for (const Link& link : robot.model->links()) add(link.collisions);
  }
  for (const SceneObject& object : scene.objects()) {
    if (object.collisionEnabled) add(object.collisions);
  }
  return meshes;
}

class WorldBuilder {
 public:
  WorldBuilder(const Scene& scene, const FclCheckerSettings& settings)
      : scene_(scene), settings_(settings) {
    const std::size_t given = settings.precomputedMatrices.size();
    if (given != 0 && given != scene.robots().size()) {
      throw InputError("collision checker: " + std::to_string(given) +
                       " precomputed allowed-collision matrices for " +
                       std::to_string(scene.robots().size()) + " robots");
    }
  }

  FclWorldTables build() {
    prebuildMeshBvhs(sceneMeshes(scene_), std::thread::hardware_concurrency());
    tables_.robotGeometries.resize(scene_.robots().size());
    for (std::size_t r = 0; r < scene_.robots().size(); ++r) addRobot(static_cast<int>(r));
    for (const SceneObject& object : scene_.objects()) addObject(object);
    for (std::size_t r = 0; r < scene_.robots().size(); ++r) addPairs(static_cast<int>(r));
    addRobotRobotPairs();
    tables_.skippedShapes = builder_.skipped();
    return std::move(tables_);
  }

 private:
  void addRobot(int r) {
    const SceneRobot& robot = scene_.robots()[static_cast<std::size_t>(r)];
    const RobotModel* model = robot.model.get();
    if (!shapes_.count(model)) {
      shapes_[model] = linkShapes(*model, builder_);
      acms_[model] = settings_.precomputedMatrices.empty() ? sharedMatrix(robot.model) : nullptr;
    }
    tables_.allowedCollisions.push_back(acms_[model] ? acms_[model] : precomputed(r, *model));
    holding_.emplace_back();
    quietLinks_.push_back(linksWithDefaultCollisionsOff(*model));
    const LinkShapes& shapes = shapes_[model];
    for (std::size_t l = 0; l < shapes.size(); ++l) {
      if (shapes[l].empty()) continue;
      addBody(FclBody{robot.name + "/" + model->links()[l].name, r, static_cast<int>(l), false},
              shapes[l], Pose::Identity(), r);
    }
  }

  void addObject(const SceneObject& object) {
    if (!object.collisionEnabled) return;
    const std::vector<FclShape> shapes = builder_.build(object.collisions);
    const Attachment* attachment = scene_.findAttachment(object.name);
    if (!attachment) {
      addBody(FclBody{object.name, -1, -1, false}, shapes, object.pose, -1);
      return;
    }
    const int r = robotIndex(attachment->robot);
    const RobotModel& model = *scene_.robots()[static_cast<std::size_t>(r)].model;
    const int link = model.linkIndex(attachment->link);
    const int body = addBody(FclBody{object.name, r, link, true}, shapes, attachment->linkToObject, r);
    holding_[static_cast<std::size_t>(r)].emplace(body, holdingLinks(model, link));
  }

  /// The model's matrix from the process-wide cache; on its first use in this process, from the
  /// disk cache or computed here.
  std::shared_ptr<const AllowedCollisionMatrix> sharedMatrix(const RobotModelPtr& model) const {
    const LinkShapes& shapes = shapes_.at(model.get());
    const AllowedCollisionSettings& settings = settings_.allowedCollisions;
    return cachedAllowedCollisionMatrix(model, settings, [&] {
      return storedOrComputedAllowedCollisions(
          *model, settings, [&] { return computeAllowedCollisionMatrix(*model, linkTest(*model, shapes), settings); },
          [&](const AllowedCollisionMatrix& stored) {
            return allowsNoMoreThan(stored, computeAllowedCollisionMatrix(*model, linkTest(*model, shapes), confirmationSettings(settings)));
          });
    });
  }

  std::shared_ptr<const AllowedCollisionMatrix> precomputed(int r, const RobotModel& model) const {
    auto matrix = settings_.precomputedMatrices[static_cast<std::size_t>(r)];
    if (!matrix || matrix->linkCount() != static_cast<int>(model.links().size())) {
      throw InputError("collision checker: the precomputed allowed-collision matrix of robot " +
                       std::to_string(r) + " does not fit robot '" + model.name() + "' (" +
                       std::to_string(model.links().size()) + " links)");
    }
    return matrix;
  }

  int robotIndex(const std::string& name) const {
    for (std::size_t r = 0; r < scene_.robots().size(); ++r) {
      if (scene_.robots()[r].name == name) return static_cast<int>(r);
    }
    throw InputError("collision checker: attachment to unknown robot '" + name + "'");
  }

  int addBody(FclBody body, const std::vector<FclShape>& shapes, const Pose& X_FB, int robot) {
    const int index = static_cast<int>(tables_.bodies.size());
    tables_.bodies.push_back(std::move(body));
    for (const FclShape& shape : shapes) {
      FclShape placed = shape;
      placed.origin = X_FB * shape.origin;
      if (robot >= 0) tables_.robotGeometries[static_cast<std::size_t>(robot)].push_back(static_cast<int>(tables_.geometries.size()));
      tables_.geometries.push_back(FclGeometryEntry{std::move(placed), index});
    }
    return index;
  }

  bool bodiesMayTouch(int r, int a, int b) const {
    const FclBody& first = tables_.bodies[static_cast<std::size_t>(a)];
    const FclBody& second = tables_.bodies[static_cast<std::size_t>(b)];
    if (a == b || (first.attached && second.attached)) return true;
    if (!first.attached && !second.attached) {
      return tables_.allowedCollisions[static_cast<std::size_t>(r)]->isAllowed(first.link, second.link);
    }
    const int object = first.attached ? a : b;
    const int link = first.attached ? second.link : first.link;
    return holding_[static_cast<std::size_t>(r)].at(object)[static_cast<std::size_t>(link)] != 0 ||
           quietLinks_[static_cast<std::size_t>(r)][static_cast<std::size_t>(link)] != 0;
  }

  /// True for the geometry of a robot link whose collisions are off by default (SRDF).
  bool quiet(int geometry) const {
    const FclBody& body = tables_.bodies[static_cast<std::size_t>(bodyOf(geometry))];
    return !body.attached && body.robot >= 0 &&
           quietLinks_[static_cast<std::size_t>(body.robot)][static_cast<std::size_t>(body.link)] != 0;
  }

  int bodyOf(int geometry) const { return tables_.geometries[static_cast<std::size_t>(geometry)].body; }
  int robotOf(int geometry) const { return tables_.bodies[static_cast<std::size_t>(bodyOf(geometry))].robot; }

  void addPairs(int r) {
    const std::vector<int>& own = tables_.robotGeometries[static_cast<std::size_t>(r)];
    std::vector<FclGeometryPair>& pairs = tables_.robotPairs.emplace_back();
    for (std::size_t i = 0; i < own.size(); ++i) {
      for (std::size_t j = i + 1; j < own.size(); ++j) {
        if (!bodiesMayTouch(r, bodyOf(own[i]), bodyOf(own[j]))) pairs.push_back({own[i], own[j], true});
      }
    }
    tables_.worldPairs.insert(tables_.worldPairs.end(), pairs.begin(), pairs.end());
    for (const int g : own) {
      if (quiet(g)) continue;
      for (std::size_t h = 0; h < tables_.geometries.size(); ++h) {
        const int other = robotOf(static_cast<int>(h));
        if (other == r || quiet(static_cast<int>(h))) continue;
        pairs.push_back({g, static_cast<int>(h), other < 0});
        if (other < 0) tables_.worldPairs.push_back({g, static_cast<int>(h), true});
      }
    }
  }

  void addRobotRobotPairs() {
    const std::size_t robots = tables_.robotGeometries.size();
    for (std::size_t r = 0; r < robots; ++r) {
      for (std::size_t s = r + 1; s < robots; ++s) {
        for (const int g : tables_.robotGeometries[r]) {
          for (const int h : tables_.robotGeometries[s]) {
            if (!quiet(g) && !quiet(h)) tables_.worldPairs.push_back({g, h});
          }
        }
      }
    }
  }

  const Scene& scene_;
  const FclCheckerSettings& settings_;
  FclGeometryBuilder builder_;
  FclWorldTables tables_;
  std::map<const RobotModel*, LinkShapes> shapes_;
  std::map<const RobotModel*, std::shared_ptr<const AllowedCollisionMatrix>> acms_;
  /// Per robot: attached body -> links it may touch.
  std::vector<std::map<int, std::vector<char>>> holding_;
  /// Per robot: its links whose collisions are off by default (linksWithDefaultCollisionsOff).
  std::vector<std::vector<char>> quietLinks_;
};

}  // namespace

FclWorldTables buildFclWorld(const Scene& scene, const FclCheckerSettings& settings) {
  return WorldBuilder(scene, settings).build();
}

}  // namespace lang2manip
