#include "lang2manip/model/viewer_document.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

#include "lang2manip/core/error.hpp"

namespace lang2manip {

namespace {

/// The run's "duration" (infinite when the document has none).
double durationOf(const nlohmann::json& document, const std::string& file) {
  const auto duration = document.find("duration");
  if (duration == document.end()) return std::numeric_limits<double>::infinity();
  if (!duration->is_number() || !std::isfinite(duration->get<double>()) || duration->get<double>() < 0.0) {
    throw InputError(file + ": \"duration\": expected seconds >= 0");
  }
  return duration->get<double>();
}

void checkActions(const nlohmann::json& document, const std::string& file) {
  const auto actions = document.find("actions");
  if (actions == document.end()) return;
  if (!actions->is_array()) throw InputError(file + ": \"actions\": expected an array of actions");
  for (std::size_t i = 0; i < actions->size(); ++i) {
    if (!(*actions)[i].is_object()) throw InputError(file + ": actions[" + std::to_string(i) + "]: expected an object");
  }
}

std::string secondsText(double seconds) {
  std::ostringstream text;
  text << seconds;
  return text.str();
}

}  // namespace

std::vector<ViewerMoment> viewerMoments(const nlohmann::json& document, const std::string& file) {
  const auto version = document.is_object() ? document.find("format_version") : document.end();
  if (!document.is_object() || version == document.end() || !version->is_number_integer() || version->get<long long>() != 1) {
    throw InputError(file + ": not a viewer document of format_version 1");
  }
  checkActions(document, file);
  const double duration = durationOf(document, file);
  const auto moments = document.find("moments");
  if (moments == document.end() || !moments->is_array() || moments->empty()) throw InputError(file + ": no \"moments\" to render");
  std::vector<ViewerMoment> list;
  for (std::size_t i = 0; i < moments->size(); ++i) {
    const nlohmann::json& moment = (*moments)[i];
    const auto time = moment.is_object() ? moment.find("time") : moment.end();
    const auto label = moment.is_object() ? moment.find("label") : moment.end();
    if (!moment.is_object() || time == moment.end() || !time->is_number() || !std::isfinite(time->get<double>()) ||
        time->get<double>() < 0.0 || label == moment.end() || !label->is_string()) {
      throw InputError(file + ": moments[" + std::to_string(i) + "]: expected {\"time\": seconds >= 0, \"label\": text}");
    }
    // A moment may be a rounding error past the end, not beyond it.
    if (time->get<double>() > duration + 1e-6 * std::max(1.0, duration)) {
      throw InputError(file + ": moments[" + std::to_string(i) + "].time " + secondsText(time->get<double>()) + " s: after the run's end (duration " +
                       secondsText(duration) + " s)");
    }
    list.push_back({time->get<double>(), label->get<std::string>()});
  }
  return list;
}

void checkGlbHeader(const std::string& bytes, const std::string& file) {
  const auto word = [&bytes](std::size_t at) {
    std::uint32_t value = 0;
    for (std::size_t k = 4; k-- > 0;) value = (value << 8) | static_cast<unsigned char>(bytes[at + k]);
    return value;
  };
  if (bytes.size() < 20 || bytes.compare(0, 4, "glTF") != 0) throw InputError(file + ": not a glTF binary (no \"glTF\" header)");
  if (word(4) != 2) throw InputError(file + ": glTF version " + std::to_string(word(4)) + ", expected 2");
  if (word(8) != bytes.size()) {
    throw InputError(file + ": truncated or padded: the header says " + std::to_string(word(8)) + " bytes, the file has " +
                     std::to_string(bytes.size()));
  }
}

}  // namespace lang2manip
