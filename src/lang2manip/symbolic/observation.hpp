#pragma once
/// @file The environment-state observation of the paper (its "textualization"): robots, objects
/// and spatial relations, as JSON for programs and as the text given to task planners. The text
/// is rendered from the JSON, so both always say the same.

#include <nlohmann/json.hpp>
#include <string>

#include "lang2manip/symbolic/spatial_relations.hpp"
#include "lang2manip/symbolic/symbolic_state.hpp"

namespace lang2manip {

class Scene;

struct ObservationOptions {
  /// The robot whose base frame relations are expressed in (the first robot when empty).
  std::string robot;
  /// The arm that will act: regions are of the part of a top it reaches (every arm when empty).
  std::string arm;
  SpatialOptions spatial;
  SymbolicStateTolerances tolerances;
};

/// The observation of `scene` as JSON (lengths in metres, angles in radians, rounded to 0.1 mm):
/// - "robots": name, model, dofs, joints (name, type, value, lower, upper), links (name, parent,
///   joint), base_pose (position, orientation_wxyz, yaw), end_effectors (tool frame, its pose
///   in the world and in the base frame, gripper joints/values/state, held object),
///   configuration (named configuration or null) and named_configurations;
/// - "objects": name, kind, position, orientation_wxyz, yaw, dimensions, movable, role,
///   in/on/held/clear, position_in_base, side of the robot, distance from the robot base, colour
///   and category (object_appearance.hpp, null when none), the region of its support's top it
///   stands in ("region"), and for supports their "top": height, area and reachable part;
/// - "relations": {subject, relation, object} facts: in, on, holding, left_of, right_of,
///   in_front_of, behind (robot base frame, between objects that are not supports) and near.
/// Throws InputError for an unknown robot name.
nlohmann::json observeEnvironment(const Scene& scene, const ObservationOptions& options = {});

/// The text given to task planners for an observation made by observeEnvironment().
std::string observationText(const nlohmann::json& observation);

}  // namespace lang2manip
