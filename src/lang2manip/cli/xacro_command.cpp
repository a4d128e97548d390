#include <memory>
#include <string>
#include <vector>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/model/xacro.hpp"

namespace lang2manip {
namespace {

struct XacroCommandOptions {
  std::string file;
  std::vector<std::string> arguments;
  std::vector<std::string> packagePaths;
};

void printExpansion(const XacroCommandOptions& options, std::ostream& out) {
  XacroOptions xacro;
  for (const std::string& argument : options.arguments) xacro.arguments.insert(parseXacroArgument(argument));
  for (const std::string& path : options.packagePaths) xacro.packagePaths.emplace_back(path);
  out << expandXacroFile(options.file, xacro);
}

}  // namespace

void addXacroCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<XacroCommandOptions>();
  CLI::App* command = app.add_subcommand("xacro", "Expand a xacro robot description and print the URDF");
  command->add_option("FILE", options->file, "The .xacro (or .urdf.xacro) file")->required();
  command->add_option("ARGS", options->arguments, "Arguments NAME:=VALUE of the file's <xacro:arg>s");
  command->add_option("--package-path", options->packagePaths,
                      "Directory searched first for $(find PKG) (repeatable; then LANG2MANIP_PACKAGE_PATH, "
                      "ROS_PACKAGE_PATH and the directories above the file)");
  command->callback([options, &out] { printExpansion(*options, out); });
}

}  // namespace lang2manip
