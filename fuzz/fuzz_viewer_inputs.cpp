// Feed functions of the viewer and API inputs (fuzz_inputs.hpp): HTTP request bodies and paths
// as the server reads them, and run documents as `render` reads them.

#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "fuzz_inputs.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/model/viewer_document.hpp"
#include "lang2manip/server/api_types.hpp"
#include "lang2manip/server/static_files.hpp"
#include "scratch_file.hpp"

namespace lang2manip::fuzz {
namespace {

/// Every reader of body fields, as the routes call them, on one body.
void readEveryField(const nlohmann::json& body) {
  const auto attempt = [](const auto& read) {
    try {
      read();
    } catch (const ApiError& error) {
      if (error.status() != 400) throw std::logic_error("a body field error that is not 400");
    }
  };
  attempt([&] { (void)body::string(body, "problem"); });
  attempt([&] { (void)body::string(body, "task", "default"); });
  attempt([&] { (void)body::number(body, "time_limit", 1.0); });
  attempt([&] { (void)body::integer(body, "rounds", 3, 1, 10); });
  attempt([&] { (void)body::numbers(body, "controls"); });
  attempt([&] { (void)body::boolean(body, "record_tree", false); });
  attempt([&] { (void)body::pose(body, "pose"); });
  attempt([&] { body::onlyFields(body, {"problem", "task", "pose"}); });
}

}  // namespace

InputOutcome feedApiRequest(std::string_view input) {
  // First line: the URL path and a client id separated by a space; the rest: the body.
  const std::size_t newline = input.find('\n');
  const std::string head(input.substr(0, newline));
  const std::string_view text = newline == std::string_view::npos ? std::string_view() : input.substr(newline + 1);
  const std::size_t space = head.find(' ');
  const std::string path = head.substr(0, space);
  bool accepted = true;
  static const std::filesystem::path viewer = [] {
    const std::filesystem::path directory = scratchDirectory() / "viewer";
    std::filesystem::create_directories(directory);
    std::ofstream(directory / "index.html") << "<html></html>";
    return directory;
  }();
  try {
    (void)readStaticFile(viewer, path);
  } catch (const ApiError& error) {
    if (error.status() != 403 && error.status() != 404) throw std::logic_error("a viewer path error that is not 403 or 404");
    accepted = false;
  }
  try {
    checkClientId(space == std::string::npos ? "" : head.substr(space + 1));
  } catch (const ApiError&) {
    accepted = false;
  }
  JsonLimits limits;
  limits.maxDepth = 32;
  limits.maxBytes = std::size_t{1} << 20;
  try {
    const nlohmann::json body = parseJsonWithinLimits(text, limits, "request body");
    if (body.is_object()) readEveryField(body);
  } catch (const InputError&) {
    accepted = false;
  }
  return accepted ? InputOutcome::kAccepted : InputOutcome::kRejected;
}

InputOutcome feedViewerDocument(std::string_view input) {
  // First line: a GLB header candidate (as bytes); the rest: viewer.json.
  const std::size_t newline = input.find('\n');
  const std::string glb(input.substr(0, newline));
  bool accepted = true;
  try {
    checkGlb(glb, "scene.glb");
  } catch (const InputError&) {
    accepted = false;
  }
  try {
    const std::string_view text = newline == std::string_view::npos ? std::string_view() : input.substr(newline + 1);
    (void)viewerMoments(parseJsonWithinLimits(text, {}, "viewer.json"), "viewer.json");
  } catch (const InputError&) {
    accepted = false;
  }
  return accepted ? InputOutcome::kAccepted : InputOutcome::kRejected;
}

}  // namespace lang2manip::fuzz
