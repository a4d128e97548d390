// The model readers: URDF, SRDF, joint limits, Kautham problems and controls, MoveIt YAML, meshes.

#include <cmath>
#include <stdexcept>

#include "fuzz_inputs.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/model/builtin_data.hpp"
#include "lang2manip/model/joint_limits_reader.hpp"
#include "lang2manip/model/kautham_benchmark.hpp"
#include "lang2manip/model/kautham_controls.hpp"
#include "lang2manip/model/kautham_problem.hpp"
#include "lang2manip/model/mesh_loader.hpp"
#include "lang2manip/model/moveit_scene_reader.hpp"
#include "lang2manip/model/srdf_reader.hpp"
#include "lang2manip/model/urdf_reader.hpp"
#include "lang2manip/model/xacro.hpp"
#include "scratch_file.hpp"

namespace lang2manip::fuzz {
namespace {

/// Runs `parse`; an InputError is the documented rejection.
template <typename Parse>
InputOutcome outcomeOf(const Parse& parse) {
  try {
    parse();
    return InputOutcome::kAccepted;
  } catch (const InputError&) {
    return InputOutcome::kRejected;
  }
}

/// The built-in Panda (without meshes), read once.
const RobotModelPtr& builtinPanda() {
  static const RobotModelPtr panda = [] {
    UrdfReadOptions options;
    options.loadMeshes = false;
    return readUrdfFile(builtinRobotUrdf("panda"), options);
  }();
  return panda;
}

RobotModelData builtinPandaData() {
  RobotModelData data;
  data.name = builtinPanda()->name();
  data.links = builtinPanda()->links();
  data.joints = builtinPanda()->joints();
  data.source = builtinPanda()->source();
  return data;
}

InputOutcome feedMesh(std::string_view input, const std::string& extension) {
  const std::string path = writeScratchFile("mesh" + extension, input).string();
  return outcomeOf([&] { (void)loadTriangleMesh(path); });
}

}  // namespace

InputOutcome feedUrdf(std::string_view input) {
  UrdfReadOptions options;
  options.loadMeshes = false;
  return outcomeOf([&] {
    (void)readUrdfString(std::string(input), "fuzz.urdf", scratchDirectory(), options);
  });
}

InputOutcome feedXacro(std::string_view input) {
  // Files an input may include or load beside it (fuzz/corpus/xacro/ uses them).
  static const bool besideWritten = [] {
    writeScratchFile("inc.xacro",
                     "<robot xmlns:xacro=\"http://www.ros.org/wiki/xacro\"><xacro:property name=\"length\" value=\"0.5\"/>"
                     "<xacro:macro name=\"leg\" params=\"n\"><link name=\"leg${n}\"/></xacro:macro></robot>");
    writeScratchFile("data.yaml", "joint:\n  lower: !degrees -90\n  upper: 1.5\n  flags: [true, null]\n");
    return true;
  }();
  (void)besideWritten;
  const std::filesystem::path file = writeScratchFile("robot.urdf.xacro", input);
  return outcomeOf([&] { (void)expandXacroFile(file); });
}

InputOutcome feedSrdf(std::string_view input) {
  static const RobotModelData panda = builtinPandaData();
  return outcomeOf([&] { (void)readSrdfString(std::string(input), "fuzz.srdf", panda); });
}

/// Throws std::logic_error unless `model`'s limits are valid and within `original`'s ranges.
void requireValidLimits(const RobotModel& model, const RobotModel& original) {
  for (int v = 0; v < model.variableCount(); ++v) {
    for (const std::optional<double> limit : {model.accelerationLimit(v), model.jerkLimit(v)}) {
      if (limit && !(std::isfinite(*limit) && *limit > 0.0)) {
        throw std::logic_error("an accepted joint limits file set a limit that is not positive and finite");
      }
    }
    if (!(model.lowerLimits()[v] <= model.upperLimits()[v] && model.lowerLimits()[v] >= original.lowerLimits()[v] &&
          model.upperLimits()[v] <= original.upperLimits()[v])) {
      throw std::logic_error("an accepted joint limits file widened or emptied a joint's range");
    }
    if (!(std::isfinite(model.velocityLimits()[v]) && model.velocityLimits()[v] > 0.0)) {
      throw std::logic_error("an accepted joint limits file set a velocity limit that is not positive and finite");
    }
  }
}

InputOutcome feedJointLimits(std::string_view input) {
  const std::filesystem::path file = writeScratchFile("robot.joint_limits.yaml", input);
  return outcomeOf([&] {
    RobotModel panda = *builtinPanda();
    applyJointLimits(readJointLimitsFile(file), panda);
    requireValidLimits(panda, *builtinPanda());
  });
}

InputOutcome feedKauthamProblem(std::string_view input) {
  const std::filesystem::path file = writeScratchFile("problem.xml", input);
  KauthamReadOptions options;
  options.modelDirectories = {builtinDataDirectory() / "models",
                              builtinDataDirectory() / "problems" / "desk"};
  return outcomeOf([&] { (void)readKauthamProblem(file, options); });
}

InputOutcome feedKauthamBenchmark(std::string_view input) {
  return outcomeOf([&] { (void)readKauthamBenchmarkString(std::string(input), "fuzz_benchmark.xml", "/nonexistent"); });
}

InputOutcome feedKauthamControls(std::string_view input) {
  return outcomeOf([&] {
    const ControlSet controls = readControlString(std::string(input), "fuzz.cntr");
    try {
      const ControlSet again = readControlString(writeControlString(controls), "written.cntr");
      if (again.dofs.size() != controls.dofs.size() ||
          again.controls.size() != controls.controls.size()) {
        throw std::logic_error("a control set reads back with other DOFs or controls");
      }
    } catch (const InputError& error) {
      throw std::logic_error(std::string("a control set does not read back from its XML: ") +
                             error.what());
    }
  });
}

InputOutcome feedMoveItProblem(std::string_view input) {
  std::string_view scene = input;
  std::string_view request;
  const std::string separator = "\n" + std::string(kMoveItRequestSeparator) + "\n";
  if (const auto at = input.find(separator); at != std::string_view::npos) {
    scene = input.substr(0, at + 1);
    request = input.substr(at + separator.size());
  }
  const std::filesystem::path sceneFile = writeScratchFile("scene0001.yaml", scene);
  const std::filesystem::path requestFile = writeScratchFile("request0001.yaml", request);
  return outcomeOf([&] { (void)readMoveItProblem(sceneFile, requestFile, builtinPanda()); });
}

InputOutcome feedStlMesh(std::string_view input) { return feedMesh(input, ".stl"); }
InputOutcome feedObjMesh(std::string_view input) { return feedMesh(input, ".obj"); }
InputOutcome feedDaeMesh(std::string_view input) { return feedMesh(input, ".dae"); }
InputOutcome feedPlyMesh(std::string_view input) { return feedMesh(input, ".ply"); }
InputOutcome feedInventorMesh(std::string_view input) { return feedMesh(input, ".iv"); }
InputOutcome feedVrmlMesh(std::string_view input) { return feedMesh(input, ".wrl"); }

}  // namespace lang2manip::fuzz
