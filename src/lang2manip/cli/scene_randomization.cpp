#include "lang2manip/cli/scene_randomization.hpp"

namespace lang2manip {

std::optional<Scene> randomizedScene(const Scene& scene, double spread, double turn, Random& random) {
  for (int attempt = 0; attempt < 100; ++attempt) {
    Scene trial = scene;
    for (const SceneObject& object : scene.objects()) {
      if (!object.movable) continue;
      Pose& pose = trial.object(object.name).pose;
      pose.translation() += Vector3(random.uniform(-spread, spread), random.uniform(-spread, spread), 0.0);
      pose.linear() = Eigen::AngleAxisd(random.uniform(-turn, turn), Vector3::UnitZ()).toRotationMatrix() * pose.linear();
    }
    bool overlapping = false;
    for (const SceneObject& a : trial.objects()) {
      for (const SceneObject& b : trial.objects()) {
        const AlignedBox3 common = a.worldBounds().intersection(b.worldBounds());
        if (&a < &b && (a.movable || b.movable) && !common.isEmpty() && common.volume() > 1e-9) overlapping = true;
      }
    }
    if (!overlapping) return trial;
  }
  return std::nullopt;
}

}  // namespace lang2manip
