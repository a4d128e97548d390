// `lang2manip render RUN_DIR`: PNG snapshots of a run's key moments and a contact sheet of them,
// drawn by the viewer in headless Chromium.

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/run_page.hpp"
#include "lang2manip/core/error.hpp"
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

/// Runs `arguments` with its output discarded; false when it fails or outlives `seconds`.
bool runQuietly(const std::vector<std::string>& arguments, double seconds) {
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
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

class Snapshotter {
 public:
  Snapshotter(std::string chromium, fs::path page, fs::path profile, double timeout)
      : chromium_(std::move(chromium)), page_(std::move(page)), profile_(std::move(profile)), timeout_(timeout) {}

  /// Draws the page with `hash` into `png` at `width` x `height`.
  void shoot(const std::string& hash, const fs::path& png, int width, int height) const {
    std::vector<std::string> arguments{chromium_, "--headless", "--use-angle=swiftshader", "--enable-unsafe-swiftshader", "--hide-scrollbars",
                                       "--mute-audio", "--no-first-run", "--user-data-dir=" + profile_.string(),
                                       "--window-size=" + std::to_string(width) + "," + std::to_string(height),
                                       "--virtual-time-budget=30000", "--screenshot=" + png.string(), "file://" + page_.string() + "#" + hash};
    if (::geteuid() == 0) arguments.insert(arguments.begin() + 1, "--no-sandbox");  // Chromium refuses root otherwise
    std::error_code error;
    fs::remove(png, error);
    if (!runQuietly(arguments, timeout_) || !fs::is_regular_file(png, error) || fs::file_size(png, error) < 100) {
      throw InputError("render: " + chromium_ + " did not draw " + png.string() + " (within " + std::to_string(static_cast<int>(timeout_)) + " s)");
    }
  }

 private:
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

void render(const RenderOptions& options, std::ostream& out) {
  const fs::path run(options.runDirectory);
  const auto [width, height] = sizeOf(options.size);
  if (options.columns < 1 || options.columns > 8) throw InputError("render: --columns must be 1 to 8");
  const fs::path documentFile = run / "viewer.json";
  const json document = parseJsonWithinLimits(readWhole(documentFile, "the run document"), {}, documentFile.string());
  const std::vector<ViewerMoment> moments = viewerMoments(document, documentFile.string());
  const std::string glb = readWhole(run / "scene.glb", "the scene");
  checkGlbHeader(glb, (run / "scene.glb").string());
  const std::string chromium = findChromium(options.chromium);
  const fs::path out_ = options.out.empty() ? run / "render" : fs::path(options.out);
  std::error_code error;
  fs::create_directories(out_, error);
  if (error) throw InputError("render: cannot create " + out_.string() + ": " + error.message());
  const fs::path work = fs::temp_directory_path() / ("lang2manip-render-" + std::to_string(::getpid()));
  fs::create_directories(work);
  struct Cleanup {
    fs::path path;
    ~Cleanup() {
      std::error_code ignored;
      fs::remove_all(path, ignored);
    }
  } cleanup{work};
  std::ofstream(work / "run.html", std::ios::binary) << runPageHtml(document, glb, viewerScript());
  const Snapshotter snapshots(chromium, work / "run.html", work / "profile", options.timeoutSeconds);
  const std::string camera = options.camera.empty() ? "" : "&camera=" + options.camera;
  std::string times;
  std::string labels;
  for (std::size_t i = 0; i < moments.size(); ++i) {
    const std::string index = (i + 1 < 10 ? "0" : "") + std::to_string(i + 1);
    const fs::path png = out_ / (index + "-" + fileLabel(moments[i].label) + ".png");
    snapshots.shoot("t=" + hashText(moments[i].time) + "&ui=0" + camera, png, width, height);
    out << "  " << png.string() << "  (" << moments[i].label << ", t = " << hashText(moments[i].time) << " s)\n";
    times += (i ? "," : "") + hashText(moments[i].time);
    labels += (i ? "|" : "") + moments[i].label;
  }
  const int columns = std::min(options.columns, static_cast<int>(moments.size()));
  const int rows = (static_cast<int>(moments.size()) + columns - 1) / columns;
  const int cellHeight = (width / columns) * 3 / 4;
  const fs::path sheet = out_ / "contact-sheet.png";
  snapshots.shoot("sheet=" + times + "&labels=" + labels + "&cols=" + std::to_string(columns) + camera, sheet, width,
                  56 + rows * (cellHeight + 36));
  out << "  " << sheet.string() << "  (contact sheet of " << moments.size() << " moments)\n";
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
  command->add_option("--out", options->out, "Output directory (default: RUN_DIR/render)");
  command->add_option("--chromium", options->chromium, "The Chromium program (default: chromium on the PATH)");
  command->add_option("--timeout", options->timeoutSeconds, "Seconds one snapshot may take")->capture_default_str();
  command->callback([options, &out] { render(*options, out); });
}

}  // namespace lang2manip
