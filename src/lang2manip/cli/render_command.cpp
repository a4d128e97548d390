// `lang2manip render RUN_DIR|PAGE.html`: PNG snapshots of a run's key moments (or of the start,
// middle and end of a page written by `solve --html`) and a contact sheet of them, drawn by the
// viewer in one headless Chromium (chromium_session.hpp).

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

#include "lang2manip/cli/chromium_session.hpp"
#include "lang2manip/cli/commands.hpp"
#include "lang2manip/cli/progress_display.hpp"
#include "lang2manip/cli/run_page.hpp"
#include "lang2manip/core/error.hpp"
#include "lang2manip/core/output_files.hpp"
#include "lang2manip/core/json_limits.hpp"
#include "lang2manip/model/viewer_document.hpp"

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

/// What the viewer reports on <body>: data-state ("ready", "rendered", "error", ...) and
/// data-error (viewer/README.md).
struct PageState {
  std::string state;
  std::string error;
};

/// The viewer's state once it has left "loading" (or the time is up).
PageState viewerState(ChromiumSession& browser, double timeoutSeconds) {
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::duration<double>(timeoutSeconds);
  for (;;) {
    const json value = browser.evaluate(
        "document.readyState === 'complete' && document.body ? [document.body.dataset.state || '', document.body.dataset.error || ''] : ['', '']");
    PageState page;
    if (value.is_array() && value.size() == 2 && value[0].is_string() && value[1].is_string()) page = {value[0], value[1]};
    if ((!page.state.empty() && page.state != "loading") || std::chrono::steady_clock::now() > deadline) return page;
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
}

/// Shows the run at `time` (s) and waits until it is on the screen.
void showMoment(ChromiumSession& browser, double time) {
  std::ostringstream script;
  script.precision(17);
  script << "new Promise((resolve) => { const viewer = window.lang2manipViewer; viewer.pause(); viewer.seek(" << time
         << "); viewer.render(); requestAnimationFrame(() => requestAnimationFrame(() => resolve(viewer.state().state))); })";
  (void)browser.evaluate(script.str());
}

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

/// A temporary directory, removed with what it holds when destroyed.
class WorkDirectory {
 public:
  WorkDirectory() {
    std::string name = (fs::temp_directory_path() / "lang2manip-render-XXXXXX").string();
    if (::mkdtemp(name.data()) == nullptr) throw InputError("render: cannot create a temporary directory: " + std::string(std::strerror(errno)));
    path_ = name;
  }
  ~WorkDirectory() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  WorkDirectory(const WorkDirectory&) = delete;
  WorkDirectory& operator=(const WorkDirectory&) = delete;
  [[nodiscard]] const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

/// What is drawn: a page of the viewer and the moments to show.
struct RenderSource {
  std::string page;
  std::vector<ViewerMoment> moments;
  fs::path defaultOut;
};

/// A run directory (its run page written into `work`), or a page written by `solve --html` or
/// `run --html` (moments: start, middle and end, unless it is a run's).
RenderSource renderSource(const fs::path& given, const fs::path& work) {
  std::error_code error;
  if (fs::is_regular_file(given, error) && given.extension() == ".html") {
    return {"file://" + fs::absolute(given).string(), {}, given.parent_path() / (given.stem().string() + "-render")};
  }
  const RenderInput input = readRun(given);
  writeFileAtomically(work / "run.html", runPageHtml(input.document, input.glb, viewerScript()), "render");
  return {"file://" + (work / "run.html").string(), input.moments, given / "render"};
}

/// Start, middle and end of a page's timeline (its start only when it has none).
std::vector<ViewerMoment> timelineMoments(ChromiumSession& browser) {
  const json duration = browser.evaluate("window.lang2manipViewer ? window.lang2manipViewer.duration : 0");
  const double seconds = duration.is_number() ? duration.get<double>() : 0.0;
  if (!(seconds > 0.0)) return {{0.0, "start"}};
  return {{0.0, "start"}, {seconds / 2, "middle"}, {seconds, "end"}};
}

/// Opens `url` and waits for the viewer to show it; throws InputError with the viewer's reason
/// when it cannot, or when it is not in `expected` state.
void openViewer(ChromiumSession& browser, const std::string& url, int width, int height, double timeout,
                const std::string& what, const std::string& expected) {
  browser.open(url, width, height);
  const PageState page = viewerState(browser, timeout);
  if (page.state == "error") throw InputError("render: the viewer cannot show " + what + ": " + page.error);
  if (page.state.empty() || page.state == "loading" || (!expected.empty() && page.state != expected)) {
    throw InputError("render: the viewer did not finish drawing " + what + " (its state: \"" + page.state + "\")");
  }
}

void render(const RenderOptions& options, std::ostream& out) {
  const fs::path given(options.runDirectory);
  const auto [width, height] = sizeOf(options.size);
  checkOptions(options);
  const WorkDirectory work;
  RenderSource source = renderSource(given, work.path());
  const std::string chromium = findChromium(options.chromium);
  const fs::path out_ = options.out.empty() ? source.defaultOut : fs::path(options.out);
  OutputDirectory set(out_, "render: --out", options.force);
  ChromiumSession browser(chromium, work.path() / "profile", options.timeoutSeconds);
  const std::string camera = options.camera.empty() ? "" : "&camera=" + options.camera;
  // Every moment in one page: the scene is loaded once.
  openViewer(browser, source.page + "#ui=0" + camera, width, height, options.timeoutSeconds, given.string(), "");
  if (source.moments.empty()) source.moments = timelineMoments(browser);
  const std::vector<ViewerMoment>& moments = source.moments;
  ProgressDisplay progress("render", moments.size() + 1, "pictures");
  for (std::size_t i = 0; i < moments.size(); ++i) {
    const std::string index = (i + 1 < 10 ? "0" : "") + std::to_string(i + 1);
    const std::string png = index + "-" + fileLabel(moments[i].label) + ".png";
    showMoment(browser, moments[i].time);
    writeFileAtomically(set.stagingDirectory() / png, browser.screenshot(), "render");
    out << "  " << (out_ / png).string() << "  (" << moments[i].label << ", t = " << hashText(moments[i].time) << " s)\n";
    progress.advance();
  }
  const int columns = std::min(options.columns, static_cast<int>(moments.size()));
  const int rows = (static_cast<int>(moments.size()) + columns - 1) / columns;
  const int sheetHeight = 56 + rows * ((width / columns) * 3 / 4 + 36);
  openViewer(browser, source.page + "#" + sheetHash(moments, columns, camera), width, sheetHeight, options.timeoutSeconds,
             given.string(), "rendered");
  writeFileAtomically(set.stagingDirectory() / "contact-sheet.png", browser.screenshot(), "render");
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
  command->add_option("RUN_DIR", options->runDirectory, "A directory written by `lang2manip run` (viewer.json, scene.glb), or a page written by `solve --html` or `run --html`")
      ->required();
  command->add_option("--size", options->size, "Width x height of each snapshot in pixels")->capture_default_str();
  command->add_option("--camera", options->camera, "AZIMUTH,ELEVATION[,DISTANCE]: degrees from +x towards +y, degrees up, metres");
  command->add_option("--columns", options->columns, "Columns of the contact sheet")->capture_default_str();
  command->add_option("--out", options->out,
                      "Output directory (default: RUN_DIR/render, or PAGE-render beside a page); replaced whole, the earlier pictures kept in DIR.previous");
  command->add_flag("--force", options->force, "Use --out even when it holds files lang2manip did not write (kept in DIR.previous)");
  command->add_option("--chromium", options->chromium, "The Chromium program (default: chromium on the PATH)");
  command->add_option("--timeout", options->timeoutSeconds, "Seconds one snapshot may take")->capture_default_str();
  command->callback([options, &out] { render(*options, out); });
}

}  // namespace lang2manip
