#pragma once
// The built-in robots, read once per test binary (shared by the kinematics tests).

#include <map>
#include <string>

#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/urdf_reader.hpp"

namespace lang2manip::test {

inline const RobotModel& kinematicsRobot(const std::string& name) {
  static std::map<std::string, RobotModelPtr> cache;
  auto found = cache.find(name);
  if (found == cache.end()) {
    UrdfReadOptions options;
    options.loadMeshes = false;
    found = cache.emplace(name, readUrdfFile(builtinRobotUrdf(name), options)).first;
  }
  return *found->second;
}

}  // namespace lang2manip::test
