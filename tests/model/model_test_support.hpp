#pragma once
/// @file Helpers shared by the model tests.

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

#include "lang2manip/core/error.hpp"

namespace lang2manip::test {

/// The message of the InputError (or NotSupportedError) `action` throws, or "(no error)".
inline std::string errorMessage(const std::function<void()>& action) {
  try {
    action();
  } catch (const InputError& error) {
    return error.what();
  } catch (const NotSupportedError& error) {
    return error.what();
  }
  return "(no error)";
}

/// Writes `text` to `path`.
inline void writeText(const std::filesystem::path& path, const std::string& text) {
  std::filesystem::create_directories(path.parent_path());
  std::ofstream(path) << text;
}

/// A two-link arm URDF body (links listed child first) used by several tests.
inline std::string twoJointUrdf(const std::string& extraJointXml = "") {
  return R"(<?xml version="1.0"?>
<robot name="arm">
  <link name="tip">
    <visual><geometry><sphere radius="0.05"/></geometry>
      <material name="red"><color rgba="1 0 0 1"/></material></visual>
    <collision><origin xyz="0 0 0.1"/><geometry><box size="0.1 0.2 0.3"/></geometry></collision>
  </link>
  <link name="upper"><collision><geometry><cylinder radius="0.04" length="0.5"/></geometry></collision></link>
  <link name="base"/>
  <joint name="shoulder" type="revolute">
    <parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.3" rpy="0 0 0"/><axis xyz="0 0 1"/>
    <limit lower="-1.5" upper="1.5" velocity="2" effort="10"/>
  </joint>
  <joint name="elbow" type="revolute">
    <parent link="upper"/><child link="tip"/>
    <origin xyz="0.5 0 0" rpy="0 0 0"/><axis xyz="0 1 0"/>
    <limit lower="-2" upper="2" velocity="3" effort="10"/>
    <safety_controller soft_lower_limit="-1.9" soft_upper_limit="1.8" k_position="10" k_velocity="1"/>
  </joint>)" + extraJointXml + "\n</robot>\n";
}

}  // namespace lang2manip::test
