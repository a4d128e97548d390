#pragma once
/// @file Kautham problem files: reading a problem directory into a Scene plus the controls,
/// planner block and queries, mapping queries to joint values, and writing a Scene back.

#include <filesystem>
#include <map>
#include <string>
#include <vector>

#include "lang2manip/model/kautham_controls.hpp"
#include "lang2manip/model/scene.hpp"

namespace lang2manip {

/// The <Planner><Parameters> block, kept verbatim for the motion layer.
struct PlannerSpec {
  std::string name;
  /// (name, value) in file order.
  std::vector<std::pair<std::string, std::string>> parameters;
};

/// One <Query>: control values in the order of the control sets.
struct KauthamQuery {
  std::vector<double> init;
  std::vector<double> goal;
  /// Obstacle control values (empty when the problem has no obstacle controls).
  std::vector<double> obstacles;
};

/// How a robot or obstacle entry was written, to write it back the same way.
struct KauthamEntity {
  std::string name;
  /// The model reference as written (e.g. "robots/UR5/ur5.urdf") and the file it resolved to.
  std::string reference;
  std::filesystem::path resolvedPath;
  double scale = 1.0;
  /// The Home pose (X_WB for robots, X_WO for obstacles before obstacle controls).
  Pose home = Pose::Identity();
  BaseLimits limits;
  bool isRobot = false;
  /// <InvKinematic name> of a robot (empty when none).
  std::string inverseKinematics;
  /// <XacroArg name="..." value="..."/> children of a robot whose model is a .xacro file (our
  /// extension; Kautham ignores unknown elements).
  std::map<std::string, std::string> xacroArguments;
  /// <Srdf file="..."/> child of a robot (our extension): its semantics, over a sibling SRDF
  /// and inference; resolved like the model. Empty when none.
  std::filesystem::path srdf;
};

/// A loaded problem. `scene` holds the robots at the first query's init (middle of the ranges
/// when there is no query) and the obstacles at their initial poses.
struct KauthamProblem {
  std::string name;
  std::filesystem::path file;
  Scene scene;
  std::vector<KauthamEntity> robots;
  std::vector<KauthamEntity> obstacles;
  ControlSet robotControls;
  ControlSet obstacleControls;
  PlannerSpec planner;
  std::vector<KauthamQuery> queries;
  /// <InitialAttachedObstacle>s, applied to `scene` after the robots are placed.
  std::vector<Attachment> initialAttachments;
};

/// Options for reading a problem.
struct KauthamReadOptions {
  /// Extra directory prefixes tried after the problem's directory and the models/ directories of
  /// it and every directory above it (nearest first), as Kautham searches.
  std::vector<std::filesystem::path> modelDirectories;
  /// package:// search paths for the URDFs.
  std::vector<std::filesystem::path> packagePaths;
  /// <xacro:arg> values for every .xacro robot, over the problem's own <XacroArg>s.
  std::map<std::string, std::string> xacroArguments;
  /// Approach axes for every robot's manipulators (UrdfReadOptions::approachAxes).
  std::map<std::string, Vector3> approachAxes;
};

/// Reads a Kautham problem XML. Throws InputError naming the file, the line where known and what
/// is wrong (missing file, malformed XML, model reference that resolves nowhere, unknown DOF or
/// control names, wrong number of query values, non-finite numbers, a control file not .cntr).
/// A <Home> whose rotation axis is zero (WX=WY=WZ=0) means no rotation whatever its TH, as in
/// Kautham; a non-zero TH then logs a warning naming the file and line.
KauthamProblem readKauthamProblem(const std::filesystem::path& file,
                                  const KauthamReadOptions& options = {});

/// Robot configurations and base poses for control values `controls` (robot control set).
struct RobotStates {
  std::vector<VectorX> configurations;  ///< one per scene robot
  std::vector<Pose> basePoses;          ///< one per scene robot
};

/// Maps robot control values to joint values with Kautham's formula (see kautham-format.md).
/// Throws InputError for the wrong number of values or values outside [0,1].
RobotStates robotStatesFromControls(const KauthamProblem& problem,
                                    const std::vector<double>& controls, const std::string& what);

/// The robots' states at `positions`: one value per DOF of the robot control set, in its order, in
/// the DOF's own unit (a joint's value; a base axis in metres within its <Limits>, a base rotation
/// as Kautham's unit value), as trajectories of the problem's control space hold them. Joints no
/// DOF names sit mid-range, as robotStatesFromControls() puts them. Throws InputError for the
/// wrong number of values or a value that is not finite.
RobotStates robotStatesFromDofPositions(const KauthamProblem& problem, const std::vector<double>& positions,
                                        const std::string& what);

/// Object poses (one per scene object) for obstacle control values.
std::vector<Pose> obstaclePosesFromControls(const KauthamProblem& problem,
                                            const std::vector<double>& controls,
                                            const std::string& what);

/// Writes `problem` as `<directory>/<stem>.xml` with its control files under
/// `<directory>/controls/`; models built in code are written as URDFs under
/// `<directory>/models/`. The scene's current robot configurations become the query's init.
/// Returns the problem file's path. Throws InputError when the directory cannot be written.
std::filesystem::path writeKauthamProblem(const KauthamProblem& problem,
                                          const std::filesystem::path& directory,
                                          const std::string& stem);

/// A KauthamProblem for a Scene that did not come from a Kautham file (default controls, no
/// planner, no query: add them with kauthamQueryFromStates).
KauthamProblem kauthamProblemFromScene(const Scene& scene, const std::string& name);

/// The query, in `problem`'s robot controls, from configuration `init` to `goal` (one per scene
/// robot). Controls must be the default ones (one per joint variable, kauthamProblemFromScene).
/// A configuration outside the joint limits maps to control values outside [0,1], which the
/// planning session refuses. Throws InputError for the wrong number of robots or values.
KauthamQuery kauthamQueryFromStates(const KauthamProblem& problem, const std::vector<VectorX>& init,
                                    const std::vector<VectorX>& goal);

}  // namespace lang2manip
