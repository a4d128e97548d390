#include "language/language_test_scenes.hpp"

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/kautham_problem.hpp"

namespace lang2manip::test {
namespace {

constexpr double kTableTop = 0.75;

Shape boxShape(const Vector3& size, const Vector4& rgba) {
  Shape shape;
  shape.geometry = Box{size};
  shape.origin.translation() = Vector3(0, 0, size.z() / 2);
  shape.material = Material{"paint", rgba, ""};
  return shape;
}

SceneObject makeObject(const std::string& name, const std::string& kind, const Vector3& size,
                       const Vector4& rgba, double x, double y) {
  SceneObject object;
  object.name = name;
  object.kind = kind;
  object.movable = true;
  object.collisions.push_back(boxShape(size, rgba));
  object.visuals = object.collisions;
  object.pose.translation() = Vector3(x, y, kTableTop);
  return object;
}

SceneObject makeContainer(const std::string& name, const std::string& kind, const Vector3& size,
                          const Vector4& rgba, double x, double y) {
  SceneObject object = makeObject(name, kind, size, rgba, x, y);
  object.role = ObjectRole::kContainer;
  const double wall = 0.005;
  object.cavity = AlignedBox3(Vector3(-size.x() / 2 + wall, -size.y() / 2 + wall, wall),
                              Vector3(size.x() / 2 - wall, size.y() / 2 - wall, size.z()));
  return object;
}

}  // namespace

Scene deskScene() { return readKauthamProblem(resolveProblem("panda_desk")).scene; }

Scene workbenchScene() {
  Scene scene;
  SceneObject table;
  table.name = "table";
  table.kind = "table";
  table.role = ObjectRole::kSupport;
  Shape top = boxShape(Vector3(1.2, 0.8, 0.03), Vector4(0.72, 0.53, 0.34, 1));
  top.origin.translation() = Vector3(0, 0, kTableTop - 0.015);
  table.collisions.push_back(top);
  table.visuals = table.collisions;
  scene.addObject(table);
  scene.addObject(makeObject("red_block", "block", Vector3(0.04, 0.04, 0.04),
                             Vector4(0.85, 0.1, 0.1, 1), 0.3, 0.2));
  scene.addObject(makeObject("blue_block", "block", Vector3(0.04, 0.04, 0.04),
                             Vector4(0.1, 0.2, 0.85, 1), 0.3, 0.0));
  scene.addObject(makeObject("green_block", "block", Vector3(0.06, 0.06, 0.06),
                             Vector4(0.1, 0.7, 0.2, 1), 0.3, -0.2));
  scene.addObject(makeContainer("white_cup", "cup", Vector3(0.09, 0.09, 0.1),
                                Vector4(0.95, 0.95, 0.95, 1), 0.45, 0.25));
  scene.addObject(makeContainer("yellow_cup", "cup", Vector3(0.06, 0.06, 0.08),
                                Vector4(0.95, 0.85, 0.1, 1), 0.45, -0.25));
  scene.addObject(makeContainer("box", "box", Vector3(0.2, 0.15, 0.08),
                                Vector4(0.5, 0.5, 0.5, 1), 0.55, 0.0));
  scene.addObject(makeObject("marker_1", "marker", Vector3(0.13, 0.018, 0.018),
                             Vector4(0.8, 0.1, 0.1, 1), 0.15, 0.3));
  scene.addObject(makeObject("marker_2", "marker", Vector3(0.13, 0.018, 0.018),
                             Vector4(0.05, 0.05, 0.05, 1), 0.15, -0.3));
  return scene;
}

void restOn(Scene& scene, const std::string& object, const std::string& support) {
  const AlignedBox3 below = scene.object(support).worldBounds();
  SceneObject& item = scene.object(object);
  const Vector3 centre = below.center();
  item.pose.translation() = Vector3(centre.x(), centre.y(), below.max().z());
}

void putInside(Scene& scene, const std::string& object, const std::string& container) {
  const SceneObject& holder = scene.object(container);
  const Vector3 floor = holder.pose * Vector3(holder.cavity->center().x(),
                                              holder.cavity->center().y(), holder.cavity->min().z());
  scene.object(object).pose.translation() = floor;
}

std::vector<ObjectDescriptor> descriptorsFor(SceneId scene) {
  static const std::vector<ObjectDescriptor> desk = describeObjects(deskScene());
  static const std::vector<ObjectDescriptor> workbench = describeObjects(workbenchScene());
  return scene == SceneId::kDesk ? desk : workbench;
}

}  // namespace lang2manip::test
