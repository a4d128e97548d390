#include "lang2manip/model/kautham_benchmark.hpp"

#include <array>

#include "lang2manip/core/text_parsing.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

constexpr std::array<const char*, 6> kParameters{"maxTime", "maxMem", "runCount", "filename", "displayProgress", "timeBetweenUpdates"};

std::string knownParameters() {
  std::string names;
  for (const char* name : kParameters) names += (names.empty() ? "" : ", ") + std::string(name);
  return names;
}

void readParameter(const XmlDocument& document, const pugi::xml_node& node, KauthamBenchmark& benchmark) {
  const std::string name = document.requiredAttribute(node, "Name");
  const std::string value = document.requiredAttribute(node, "Value");
  const SourceLocation where = document.where(node);
  const std::string what = "<Parameter Name=\"" + name + "\"> Value";
  if (name == "maxTime" || name == "maxMem") {
    const double number = parseFiniteNumber(value, what, where);
    if (number <= 0.0) throw InputError(where, what + " must be positive, got " + value);
    (name == "maxTime" ? benchmark.maxTime : benchmark.maxMemoryMb) = number;
  } else if (name == "runCount") {
    const double number = parseFiniteNumber(value, what, where);
    if (number < 1.0 || number > 1e6 || number != static_cast<double>(static_cast<int>(number))) {
      throw InputError(where, what + " must be a whole number from 1 to 1000000, got " + value);
    }
    benchmark.runCount = static_cast<int>(number);
  } else if (name == "filename") {
    benchmark.logFile = value;
  } else if (name == "displayProgress" || name == "timeBetweenUpdates") {
    benchmark.ignoredParameters.push_back(name);
  } else {
    throw InputError(where, "unknown benchmark parameter \"" + name + "\" (parameters: " + knownParameters() + ")");
  }
}

KauthamBenchmark readDocument(const XmlDocument& document, const std::filesystem::path& directory) {
  const pugi::xml_node root = document.root();
  if (std::string(root.name()) != "Benchmark") {
    throw InputError(document.where(root), std::string("the root element is <") + root.name() + ">, not <Benchmark>: not a Kautham benchmark file");
  }
  KauthamBenchmark benchmark;
  benchmark.name = root.attribute("Name").value();
  for (const pugi::xml_node& node : root.children()) {
    const std::string element = node.name();
    if (element == "Problem") {
      const std::string file = document.requiredAttribute(node, "File");
      benchmark.problems.push_back({(directory / file).lexically_normal(), node.attribute("PlannerAlias").value(), document.where(node)});
    } else if (element == "Parameter") {
      readParameter(document, node, benchmark);
    } else if (node.type() == pugi::node_element) {
      throw InputError(document.where(node), "unknown element <" + element + "> in a benchmark (elements: Problem, Parameter)");
    }
  }
  if (benchmark.problems.empty()) throw InputError(document.where(root), "the benchmark names no <Problem>");
  return benchmark;
}

}  // namespace

KauthamBenchmark readKauthamBenchmarkFile(const std::filesystem::path& path) {
  return readDocument(XmlDocument::loadFile(path, "benchmark file"), path.parent_path());
}

KauthamBenchmark readKauthamBenchmarkString(const std::string& xml, const std::string& sourceName,
                                            const std::filesystem::path& directory) {
  return readDocument(XmlDocument::loadString(xml, sourceName, "benchmark"), directory);
}

}  // namespace lang2manip
