#pragma once
/// @file Kautham control sets (.cntr): normalized controls in [0,1] that drive robot joints and
/// base DOFs through coupling coefficients, eigValues and offsets.

#include <filesystem>
#include <string>
#include <vector>

#include "lang2manip/core/error.hpp"

namespace lang2manip {

/// A DOF addressed as "<entity>/<dof>": dof is X, Y, Z, X1, X2, X3 (base) or the CHILD LINK
/// name of a joint.
struct ControlledDof {
  std::string entity;
  std::string dof;
  /// Offset in normalized units (0.5 when the file gives none).
  double offset = 0.5;
  /// Line of the control file where the DOF first appears (for messages; 0 when unknown).
  int line = 0;

  [[nodiscard]] std::string fullName() const { return entity + "/" + dof; }
};

/// One control: p_d += eigValue * coefficient_d * (c - 0.5) for each DOF d it couples.
struct Control {
  std::string name;
  double eigValue = 1.0;
  /// (index into ControlSet::dofs, coefficient).
  std::vector<std::pair<int, double>> coefficients;
  /// Line of the control file where the control is defined (0 when unknown).
  int line = 0;
};

struct ControlSet {
  std::vector<ControlledDof> dofs;
  std::vector<Control> controls;
  /// The .cntr file read (empty for default controls).
  std::string source;

  /// Normalized DOF values p_d for control values `c` (one per control), clamped to [0,1].
  /// Throws InputError when `c` has the wrong size or a value outside [0,1] or not finite.
  [[nodiscard]] std::vector<double> dofValues(const std::vector<double>& c,
                                              const std::string& what) const;

  /// Index of DOF "entity/dof", or -1.
  [[nodiscard]] int findDof(const std::string& entity, const std::string& dof) const;

  /// Names of the controls in order.
  [[nodiscard]] std::vector<std::string> controlNames() const;
};

/// Reads a .cntr file. Throws InputError naming the file and line for a file that is not .cntr,
/// malformed XML, a DOF name without "/", non-finite values, or a control without DOFs.
ControlSet readControlFile(const std::filesystem::path& path);

/// Reads .cntr text; `sourceName` names it in messages.
ControlSet readControlString(const std::string& xml, const std::string& sourceName);

/// Writes a control set as .cntr XML text.
std::string writeControlString(const ControlSet& controls);

}  // namespace lang2manip
