#pragma once
/// @file Helpers for the Kautham reader tests: tiny URDFs with primitive geometry and a fixture
/// that lays out a Kautham problem directory in a temporary directory:
///   <tmp>/models/robots/..., <tmp>/models/obstacles/...       (models)
///   <tmp>/demos/scene/problem.xml, <tmp>/demos/scene/controls/ (problem and control files)
/// so that "robots/x.urdf" resolves through <problem dir>/../../models/.

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "lang2manip/model/kautham_problem.hpp"
#include "model_test_support.hpp"
#include "test_paths.hpp"

namespace lang2manip::test {

/// An arm (robot name `name`) with joints whose CHILD links are the Kautham DOF names:
///   shoulder: revolute about z, [-1, 1],   base  -> upper (origin z = 0.1)
///   elbow:    revolute about y, [-2, 3],   upper -> fore  (origin x = 0.5)
///   spin:     continuous about x,           fore  -> wheel
///   slide:    prismatic along x, [0, 0.4],  fore  -> slider
inline std::string armUrdf(const std::string& name = "arm") {
  return R"(<?xml version="1.0"?>
<robot name=")" +
         name + R"(">
  <link name="base"><collision><geometry><box size="0.2 0.2 0.1"/></geometry></collision></link>
  <link name="upper"><collision><geometry><cylinder radius="0.04" length="0.5"/></geometry></collision></link>
  <link name="fore"/>
  <link name="wheel"/>
  <link name="slider"/>
  <joint name="shoulder" type="revolute"><parent link="base"/><child link="upper"/>
    <origin xyz="0 0 0.1"/><axis xyz="0 0 1"/><limit lower="-1" upper="1" velocity="1" effort="1"/></joint>
  <joint name="elbow" type="revolute"><parent link="upper"/><child link="fore"/>
    <origin xyz="0.5 0 0"/><axis xyz="0 1 0"/><limit lower="-2" upper="3" velocity="1" effort="1"/></joint>
  <joint name="spin" type="continuous"><parent link="fore"/><child link="wheel"/><axis xyz="1 0 0"/>
    <limit velocity="1" effort="1"/></joint>
  <joint name="slide" type="prismatic"><parent link="fore"/><child link="slider"/><axis xyz="1 0 0"/>
    <limit lower="0" upper="0.4" velocity="1" effort="1"/></joint>
</robot>
)";
}

/// A two-finger hand: left_joint [-0.5, 0.5] (child "left") and right_joint [-0.4, 0.6]
/// (child "right") that the URDF declares a mimic of left_joint with multiplier -1.
inline std::string mimicHandUrdf() {
  return R"(<?xml version="1.0"?>
<robot name="hand">
  <link name="palm"/><link name="left"/><link name="right"/>
  <joint name="left_joint" type="revolute"><parent link="palm"/><child link="left"/>
    <axis xyz="0 0 1"/><limit lower="-0.5" upper="0.5" velocity="1" effort="1"/></joint>
  <joint name="right_joint" type="revolute"><parent link="palm"/><child link="right"/>
    <axis xyz="0 0 1"/><limit lower="-0.4" upper="0.6" velocity="1" effort="1"/>
    <mimic joint="left_joint" multiplier="-1"/></joint>
</robot>
)";
}

/// A one-link obstacle made of one box of size `size` ("x y z"), plus `extra` inside <robot>.
inline std::string boxUrdf(const std::string& name, const std::string& size, const std::string& extra = "") {
  return "<?xml version=\"1.0\"?>\n<robot name=\"" + name + "\">\n" + extra +
         "  <link name=\"body\"><collision><geometry><box size=\"" + size +
         "\"/></geometry></collision></link>\n</robot>\n";
}

/// `body` inside <Problem name="test">...</Problem>.
inline std::string problemXml(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<Problem name=\"test\">\n" + body + "</Problem>\n";
}

/// `body` inside <ControlSet>...</ControlSet>.
inline std::string controlSet(const std::string& body) {
  return "<?xml version=\"1.0\"?>\n<ControlSet>\n" + body + "</ControlSet>\n";
}

/// A control named `name` moving one DOF with coefficient 1.
inline std::string simpleControl(const std::string& name, const std::string& dof) {
  return "  <Control name=\"" + name + "\" eigValue=\"1.0\"><DOF name=\"" + dof +
         "\" value=\"1.0\"/></Control>\n";
}

/// A <Planner> block with `queries` (each a <Query> element) inside <Queries>.
inline std::string plannerWithQueries(const std::string& queries) {
  return "  <Planner><Parameters><Name>omplRRT</Name></Parameters>\n    <Queries>\n" + queries +
         "    </Queries>\n  </Planner>\n";
}

/// An old-form query: one <Init> and one <Goal>.
inline std::string oldQuery(const std::string& init, const std::string& goal) {
  return "      <Query><Init>" + init + "</Init><Goal>" + goal + "</Goal></Query>\n";
}

/// 1-based line of the first occurrence of `needle` in `text` (0 when absent).
inline int lineOf(const std::string& text, const std::string& needle) {
  const std::size_t at = text.find(needle);
  if (at == std::string::npos) return 0;
  int line = 1;
  for (std::size_t i = 0; i < at; ++i) line += text[i] == '\n' ? 1 : 0;
  return line;
}

/// "<file>:<line>" as InputError messages start.
inline std::string fileLine(const std::filesystem::path& file, int line) {
  return file.string() + ":" + std::to_string(line);
}

/// See the file comment.
class KauthamDirectoryTest : public ::testing::Test {
 protected:
  [[nodiscard]] std::filesystem::path root() const { return directory_.path(); }
  [[nodiscard]] std::filesystem::path sceneDirectory() const { return root() / "demos" / "scene"; }
  [[nodiscard]] std::filesystem::path problemFile() const { return sceneDirectory() / "problem.xml"; }
  [[nodiscard]] std::filesystem::path controlFile(const std::string& name) const {
    return sceneDirectory() / "controls" / name;
  }

  /// Writes `urdf` as <tmp>/models/<relative>.
  void writeModel(const std::string& relative, const std::string& urdf) const {
    writeText(root() / "models" / relative, urdf);
  }
  /// Writes a control file as <scene>/controls/<name>.
  void writeControls(const std::string& name, const std::string& xml) const {
    writeText(controlFile(name), xml);
  }
  /// Writes problemXml(body) as the problem file and returns its text.
  std::string writeProblem(const std::string& body) const {
    const std::string text = problemXml(body);
    writeText(problemFile(), text);
    return text;
  }
  [[nodiscard]] KauthamProblem read(const KauthamReadOptions& options = {}) const {
    return readKauthamProblem(problemFile(), options);
  }
  /// The InputError message reading the problem throws ("(no error)" when it does not).
  [[nodiscard]] std::string readError() const {
    return errorMessage([this] { (void)read(); });
  }

 private:
  TempDirectory directory_;
};

}  // namespace lang2manip::test
