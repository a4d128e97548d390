#include "lang2manip/model/builtin_data.hpp"

#include <algorithm>
#include <cstdlib>

#include "lang2manip/core/error.hpp"
#include "lang2manip/core/file_checks.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

constexpr const char* kDefaultProblem = "panda_desk";

std::string joined(const std::vector<std::string>& names) {
  std::string text;
  for (const std::string& name : names) text += (text.empty() ? "" : ", ") + name;
  return text;
}

std::string problemTitle(const std::filesystem::path& file) {
  try {
    const XmlDocument document = XmlDocument::loadFile(file, "problem file");
    return document.root().attribute("name").value();
  } catch (const InputError&) {
    return "(unreadable problem file)";
  }
}

}  // namespace

std::filesystem::path builtinDataDirectory() {
  std::error_code error;
  if (const char* override = std::getenv("LANG2MANIP_DATA"); override && *override) {
    if (std::filesystem::is_directory(override, error)) return override;
    throw InputError(std::string("LANG2MANIP_DATA=") + override + " is not a directory");
  }
  for (const char* candidate : {LANG2MANIP_SOURCE_DATA_DIR, LANG2MANIP_INSTALL_DATA_DIR}) {
    if (std::filesystem::is_directory(std::filesystem::path(candidate) / "problems", error)) {
      return candidate;
    }
  }
  throw InputError(std::string("the built-in data directory was not found (looked in ") +
                   LANG2MANIP_SOURCE_DATA_DIR + " and " + LANG2MANIP_INSTALL_DATA_DIR +
                   "); set LANG2MANIP_DATA to lang2manip's data/ directory");
}

std::vector<BuiltinProblem> builtinProblems() {
  std::vector<BuiltinProblem> problems;
  const std::filesystem::path root = builtinDataDirectory() / "problems";
  for (const auto& entry : std::filesystem::recursive_directory_iterator(root)) {
    if (!entry.is_regular_file() || entry.path().extension() != ".xml") continue;
    problems.push_back({entry.path().stem().string(), problemTitle(entry.path()), entry.path()});
  }
  std::sort(problems.begin(), problems.end(), [](const auto& a, const auto& b) {
    if ((a.shortName == kDefaultProblem) != (b.shortName == kDefaultProblem)) {
      return a.shortName == kDefaultProblem;
    }
    return a.shortName < b.shortName;
  });
  return problems;
}

std::string defaultProblemName() { return kDefaultProblem; }

std::filesystem::path resolveProblem(const std::string& nameOrPath) {
  std::error_code error;
  const std::filesystem::path path(nameOrPath);
  if (std::filesystem::is_regular_file(path, error)) return path;
  std::vector<std::string> names;
  const std::vector<BuiltinProblem> problems = builtinProblems();
  for (const BuiltinProblem& problem : problems) {
    if (problem.shortName == nameOrPath) return problem.file;
    names.push_back(problem.shortName);
  }
  // A built-in robot's name, as --robot takes it, names that robot at its desk.
  for (const BuiltinProblem& problem : problems) {
    if (problem.shortName == nameOrPath + "_desk") return problem.file;
  }
  if (path.has_parent_path() || path.has_extension() || std::filesystem::exists(path, error)) {
    throw InputError(SourceLocation{nameOrPath, 0}, "problem file " + notRegularFileReason(path));
  }
  throw InputError("\"" + nameOrPath + "\" is neither a problem file, a built-in problem nor a built-in robot; " +
                   "built-in problems: " + joined(names) + "; built-in robots: " + joined(builtinRobotNames()));
}

std::vector<std::string> builtinRobotNames() {
  std::vector<std::string> names;
  const std::filesystem::path root = builtinDataDirectory() / "models" / "robots";
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(root, error)) {
    if (std::filesystem::is_regular_file(entry.path() / (entry.path().filename().string() + ".urdf"))) {
      names.push_back(entry.path().filename().string());
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::filesystem::path builtinRobotUrdf(const std::string& name) {
  const std::vector<std::string> names = builtinRobotNames();
  if (std::find(names.begin(), names.end(), name) == names.end()) {
    throw InputError("unknown built-in robot \"" + name + "\"; built-in robots: " + joined(names));
  }
  return builtinDataDirectory() / "models" / "robots" / name / (name + ".urdf");
}

}  // namespace lang2manip
