#include "lang2manip/cli/run_page.hpp"

#include <cstdlib>
#include <fstream>
#include <sstream>

#include "lang2manip/core/error.hpp"
#include "lang2manip/model/xml_document.hpp"

namespace lang2manip {
namespace {

namespace fs = std::filesystem;

bool hasViewer(const fs::path& directory) {
  std::error_code error;
  return fs::is_regular_file(directory / "viewer.js", error);
}

/// JSON text safe inside <script>: every '<' escaped, so no "</script>" or "<!--" can appear.
std::string scriptSafeJson(const nlohmann::json& value) {
  const std::string text = value.dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
  std::string safe;
  safe.reserve(text.size());
  for (const char c : text) {
    if (c == '<') {
      safe += "\\u003c";
    } else {
      safe += c;
    }
  }
  return safe;
}

}  // namespace

fs::path builtViewerDirectory() {
  if (const char* variable = std::getenv("LANG2MANIP_VIEWER_DIR"); variable != nullptr && *variable != '\0') {
    return hasViewer(variable) ? fs::path(variable) : fs::path();
  }
  std::error_code error;
  const fs::path program = fs::read_symlink("/proc/self/exe", error);
  if (error) return {};
  const fs::path directory = program.parent_path();
  for (const fs::path& candidate : {directory / "../../../viewer/dist", directory / "../share/lang2manip/viewer"}) {
    if (hasViewer(candidate)) return fs::canonical(candidate, error);
  }
  return {};
}

std::string viewerScript() {
  const fs::path directory = builtViewerDirectory();
  if (directory.empty()) {
    throw InputError("the web viewer is not built: build with the viewer (npm; CMake option LANG2MANIP_BUILD_VIEWER=ON, "
                     "the default) or set LANG2MANIP_VIEWER_DIR to a directory holding viewer.js");
  }
  std::ifstream in(directory / "viewer.js", std::ios::binary);
  std::ostringstream script;
  script << in.rdbuf();
  if (!in && !in.eof()) throw InputError((directory / "viewer.js").string() + ": cannot be read");
  return script.str();
}

std::string base64(const std::string& bytes) {
  static constexpr char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string text;
  text.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const std::size_t left = bytes.size() - i;
    std::uint32_t word = static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i])) << 16;
    if (left > 1) word |= static_cast<std::uint32_t>(static_cast<unsigned char>(bytes[i + 1])) << 8;
    if (left > 2) word |= static_cast<unsigned char>(bytes[i + 2]);
    text += kAlphabet[(word >> 18) & 63];
    text += kAlphabet[(word >> 12) & 63];
    text += left > 1 ? kAlphabet[(word >> 6) & 63] : '=';
    text += left > 2 ? kAlphabet[word & 63] : '=';
  }
  return text;
}

std::string runPageHtml(const nlohmann::json& runDocument, const std::string& glb, const std::string& script) {
  for (const char* forbidden : {"</script", "</SCRIPT", "<!--"}) {
    if (script.find(forbidden) != std::string::npos) throw InputError(std::string("the viewer script contains \"") + forbidden + "\": it cannot be inlined");
  }
  const std::string title = "lang2manip: " + runDocument.value("task", std::string("run"));
  std::string page = "<!doctype html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
                     "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>" + xmlEscaped(title) +
                     "</title>\n<link rel=\"icon\" href=\"data:,\">\n</head>\n<body>\n";
  page += "<script type=\"application/json\" id=\"lang2manip-run\">" + scriptSafeJson(runDocument) + "</script>\n";
  page += "<script type=\"text/plain\" id=\"lang2manip-glb\">" + base64(glb) + "</script>\n";
  page += "<script>" + script + "</script>\n</body>\n</html>\n";
  return page;
}

}  // namespace lang2manip
