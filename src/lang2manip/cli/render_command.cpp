// `lang2manip render RUN_DIR`: PNG snapshots of a run's key moments and a contact sheet of them,
// drawn by the viewer in headless Chromium.

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/progress_display.hpp"
#include "lang2manip/cli/run_page.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/model/viewer_document.hpp"

extern char** environ;

namespace lang2manip {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct RenderOptions {
  std::string runDirectory;
  std::string size = "960x720";
  std::string camera;
  std::string out;
  std::string chromium;
  bool force = false;
  int columns = 3;
  double timeoutSeconds = 120.0;
};

std::string readWhole(const fs::path& file, const std::string& what) {
  std::error_code error;
  if (!fs::is_regular_file(file, error)) throw InputError(file.string() + ": missing (" + what + "; write it with `lang2manip run`)");
  std::ifstream in(file, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  if (!in && !in.eof()) throw InputError(file.string() + ": cannot be read");
  return text.str();
}

std::pair<int, int> sizeOf(const std::string& text) {
  int width = 0;
  int height = 0;
  char x = 0;
  std::istringstream in(text);
  if (!(in >> width >> x >> height) || x != 'x' || !in.eof() || width < 64 || height < 64 || width > 7680 || height > 4320) {
    throw InputError("render: --size " + text + ": expected WIDTHxHEIGHT from 64x64 to 7680x4320");
  }
  return {width, height};
}

std::string findChromium(const std::string& given) {
  if (!given.empty()) {
    if (::access(given.c_str(), X_OK) != 0) throw InputError("render: --chromium " + given + ": not an executable");
    return given;
  }
  const char* path = std::getenv("PATH");
  std::istringstream directories(path != nullptr ? path : "/usr/bin");
  for (std::string directory; std::getline(directories, directory, ':');) {
    for (const char* name : {"chromium", "chromium-browser", "google-chrome"}) {
      const fs::path candidate = fs::path(directory) / name;
      if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
  }
  throw InputError("render: needs Chromium to draw (Debian: apt-get install chromium), or --chromium PATH");
}

/// Runs `arguments` with stderr discarded and stdout written to `output` (discarded when empty);
/// false when it fails or outlives `seconds`.
bool runQuietly(const std::vector<std::string>& arguments, double seconds, const fs::path& output = {}) {
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, output.empty() ? "/dev/null" : output.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  pid_t child = 0;
  const int spawned = posix_spawn(&child, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (spawned != 0) return false;
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(seconds);
  int status = 0;
  while (::waitpid(child, &status, WNOHANG) == 0) {
    if (std::chrono::steady_clock::now() > deadline) {
      ::kill(child, SIGKILL);
      ::waitpid(child, &status, 0);
      return false;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  return WIFEXITED(status) && WEXITSTATUS(status) == 0;
}

/// The value of attribute `name` in the HTML tag `tag`, entities decoded ("" when absent).
std::string attributeOf(const std::string& tag, const std::string& name) {
  const std::size_t start = tag.find(" " + name + "=\"");
  if (start == std::string::npos) return "";
  const std::size_t from = start + name.size() + 3;
  const std::string raw = tag.substr(from, tag.find('"', from) - from);
  std::string text;
  for (std::size_t i = 0; i < raw.size(); ++i) {
    bool decoded = false;
    static constexpr std::pair<const char*, char> kEntities[] = {{"&quot;", '"'}, {"&amp;", '&'}, {"&lt;", '<'}, {"&gt;", '>'}, {"&#39;", '\''}};
    for (const auto& [entity, character] : kEntities) {
      if (raw.compare(i, std::strlen(entity), entity) == 0) {
        text += character;
        i += std::strlen(entity) - 1;
        decoded = true;
        break;
      }
    }
    if (!decoded) text += raw[i];
  }
  return text;
}

/// What the viewer reports on <body>: data-state ("ready", "rendered", "error", ...) and
/// data-error (viewer/README.md).
struct PageState {
  std::string state;
  std::string error;
};

class Snapshotter {
 public:
  Snapshotter(std::string chromium, fs::path page, fs::path profile, double timeout)
      : chromium_(std::move(chromium)), page_(std::move(page)), profile_(std::move(profile)), timeout_(timeout) {}

  /// What the viewer reports once the page with `hash` is drawn at `width` x `height`.
  [[nodiscard]] PageState pageState(const std::string& hash, int width, int height) const {
    const fs::path dom = profile_.parent_path() / "dom.html";
    if (!runQuietly(arguments(hash, width, height, "--dump-dom"), timeout_, dom)) {
      throw InputError("render: " + chromium_ + " did not load the viewer (within " + std::to_string(static_cast<int>(timeout_)) + " s)");
    }
    std::ifstream in(dom, std::ios::binary);
    std::ostringstream text;
    text << in.rdbuf();
    const std::string html = text.str();
    const std::size_t body = html.find("<body");
    const std::string tag = body == std::string::npos ? "" : html.substr(body, html.find('>', body) - body);
    return {attributeOf(tag, "data-state"), attributeOf(tag, "data-error")};
  }

  /// Draws the page with `hash` into `png` at `width` x `height`.
  void shoot(const std::string& hash, const fs::path& png, int width, int height) const {
    const std::vector<std::string> arguments = this->arguments(hash, width, height, "--screenshot=" + png.string());
    std::error_code error;
    fs::remove(png, error);
    if (!runQuietly(arguments, timeout_) || !fs::is_regular_file(png, error) || fs::file_size(png, error) < 100) {
      throw InputError("render: " + chromium_ + " did not draw " + png.string() + " (within " + std::to_string(static_cast<int>(timeout_)) + " s)");
    }
  }

 private:
  [[nodiscard]] std::vector<std::string> arguments(const std::string& hash, int width, int height, const std::string& output) const {
    std::vector<std::string> arguments{chromium_, "--headless", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--hide-scrollbars",
                                       "--mute-audio", "--no-first-run", "--user-data-dir=" + profile_.string(),
                                       "--window-size=" + std::to_string(width) + "," + std::to_string(height),
                                       "--virtual-time-budget=30000", output, "file://" + page_.string() + "#" + hash};
    if (::geteuid() == 0) arguments.insert(arguments.begin() + 1, "--no-sandbox");  // Chromium refuses root otherwise
    return arguments;
  }

  std::string chromium_;
  fs::path page_;
  fs::path profile_;
  double timeout_;
};

std::string fileLabel(const std::string& label) {
  std::string name;
  for (const char c : label) name += std::isalnum(static_cast<unsigned char>(c)) ? static_cast<char>(std::tolower(static_cast<unsigned char>(c))) : '-';
  return name.substr(0, 40);
}

std::string hashText(double time) {
  std::ostringstream text;
  text.precision(6);
  text << time;
  return text.str();
}

/// AZIMUTH,ELEVATION[,DISTANCE] as the viewer's camera= takes it; "" stays "" (the default view).
std::string checkedCamera(const std::string& text) {
  const auto refuse = [&text] {
    return InputError("render: --camera " + text + ": expected AZIMUTH,ELEVATION[,DISTANCE]: degrees, degrees from -90 to 90, metres > 0");
  };
  if (text.empty()) return text;
  if (text.back() == ',') throw refuse();
  std::vector<double> values;
  std::istringstream in(text);
  for (std::string item; std::getline(in, item, ',');) {
    double value = 0.0;
    const auto [end, error] = std::from_chars(item.data(), item.data() + item.size(), value);
    if (error != std::errc() || end != item.data() + item.size() || !std::isfinite(value)) throw refuse();
    values.push_back(value);
  }
  if (values.size() < 2 || values.size() > 3 || std::abs(values[1]) > 90.0 || (values.size() == 3 && values[2] <= 0.0)) throw refuse();
  return text;
}

void checkOptions(const RenderOptions& options) {
  if (options.columns < 1 || options.columns > 8) throw InputError("render: --columns must be 1 to 8");
  if (!(options.timeoutSeconds > 0.0 && options.timeoutSeconds <= 3600.0)) {
    throw InputError("render: --timeout " + hashText(options.timeoutSeconds) + ": expected more than 0 and at most 3600 seconds");
  }
  (void)checkedCamera(options.camera);
}

/// A run directory's viewer.json and scene.glb, checked.
struct RenderInput {
  json document;
  std::vector<ViewerMoment> moments;
  std::string glb;
};

RenderInput readRun(const fs::path& run) {
  RenderInput input;
  const fs::path documentFile = run / "viewer.json";
  input.document = parseJsonWithinLimits(readWhole(documentFile, "the run document"), {}, documentFile.string());
  input.moments = viewerMoments(input.document, documentFile.string());
  input.glb = readWhole(run / "scene.glb", "the scene");
  checkGlb(input.glb, (run / "scene.glb").string());
  return input;
}

/// The contact sheet's hash: every moment's time and label.
std::string sheetHash(const std::vector<ViewerMoment>& moments, int columns, const std::string& camera) {
  std::string times;
  std::string labels;
  for (std::size_t i = 0; i < moments.size(); ++i) {
    times += (i ? "," : "") + hashText(moments[i].time);
    labels += (i ? "|" : "") + moments[i].label;
  }
  return "sheet=" + times + "&labels=" + labels + "&cols=" + std::to_string(columns) + camera;
}

void render(const RenderOptions& options, std::ostream& out) {
  const fs::path run(options.runDirectory);
  const auto [width, height] = sizeOf(options.size);
  checkOptions(options);
  const RenderInput input = readRun(run);
  const std::vector<ViewerMoment>& moments = input.moments;
  const std::string chromium = findChromium(options.chromium);
  const fs::path out_ = options.out.empty() ? run / "render" : fs::path(options.out);
  OutputDirectory set(out_, "render: --out", options.force);
  std::string workTemplate = (fs::temp_directory_path() / "lang2manip-render-XXXXXX").string();
  if (::mkdtemp(workTemplate.data()) == nullptr) throw InputError("render: cannot create a temporary directory: " + std::string(std::strerror(errno)));
  const fs::path work = workTemplate;
  struct Cleanup {
    fs::path path;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } cleanup{work};
  writeFileAtomically(work / "run.html", runPageHtml(input.document, input.glb, viewerScript()), "render");
  const Snapshotter snapshots(chromium, work / "run.html", work / "profile", options.timeoutSeconds);
  const std::string camera = options.camera.empty() ? "" : "&camera=" + options.camera;
  const int columns = std::min(options.columns, static_cast<int>(moments.size()));
  const int rows = (static_cast<int>(moments.size()) + columns - 1) / columns;
  const int sheetHeight = 56 + rows * ((width / columns) * 3 / 4 + 36);
  const std::string sheet = sheetHash(moments, columns, camera);
  // Asked first, so that no picture of the viewer's error banner is written.
  const PageState page = snapshots.pageState(sheet, width, sheetHeight);
  if (page.state == "error") throw InputError("render: the viewer cannot show " + run.string() + ": " + page.error);
  if (page.state != "rendered") throw InputError("render: the viewer did not finish drawing " + run.string() + " (its state: \"" + page.state + "\")");
  ProgressDisplay progress("render", moments.size() + 1, "pictures");
  for (std::size_t i = 0; i < moments.size(); ++i) {
    const std::string index = (i + 1 < 10 ? "0" : "") + std::to_string(i + 1);
    const std::string png = index + "-" + fileLabel(moments[i].label) + ".png";
    snapshots.shoot("t=" + hashText(moments[i].time) + "&ui=0" + camera, set.stagingDirectory() / png, width, height);
    out << "  " << (out_ / png).string() << "  (" << moments[i].label << ", t = " << hashText(moments[i].time) << " s)\n";
    progress.advance();
  }
  snapshots.shoot(sheet, set.stagingDirectory() / "contact-sheet.png", width, sheetHeight);
  progress.advance();
  progress.finish();
  set.commit();
  out << "  " << (out_ / "contact-sheet.png").string() << "  (contact sheet of " << moments.size() << " moments)\n";
}

}  // namespace

void addRenderCommand(CLI::App& app, std::ostream& out) {
  auto options = std::make_shared<RenderOptions>();
  CLI::App* command = app.add_subcommand(
      "render", "PNG snapshots of a run's key moments (start, each grasp and release, end) and a contact sheet, drawn by the "
                "viewer in headless Chromium");
  command->add_option("RUN_DIR", options->runDirectory, "A directory written by `lang2manip run` (viewer.json, scene.glb)")->required();
  command->add_option("--size", options->size, "Width x height of each snapshot in pixels")->capture_default_str();
  command->add_option("--camera", options->camera, "AZIMUTH,ELEVATION[,DISTANCE]: degrees from +x towards +y, degrees up, metres");
  command->add_option("--columns", options->columns, "Columns of the contact sheet")->capture_default_str();
  command->add_option("--out", options->out,
                      "Output directory (default: RUN_DIR/render); replaced whole, the earlier pictures kept in DIR.previous");
  command->add_flag("--force", options->force, "Use --out even when it holds files lang2manip did not write (kept in DIR.previous)");
  command->add_option("--chromium", options->chromium, "The Chromium program (default: chromium on the PATH)");
  command->add_option("--timeout", options->timeoutSeconds, "Seconds one snapshot may take")->capture_default_str();
  command->callback([options, &out] { render(*options, out); });
}

}  // namespace lang2manip
