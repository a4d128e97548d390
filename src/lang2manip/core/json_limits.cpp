#include "lang2manip/core/json_limits.hpp"

#include <set>
#include <streambuf>
#include <vector>

namespace lang2manip {
namespace {

using nlohmann::json;

/// Nesting a bounded dump follows before it writes "..." instead (independent of maxChars).
constexpr std::size_t kMaxDumpDepth = 32;

bool isContinuationByte(char c) {
  return (static_cast<unsigned char>(c) & 0xC0U) == 0x80U;
}

/// Appends `value` to `out` while out is shorter than `maxChars`; sets `cut` when something was
/// left out.
class BoundedWriter {
 public:
  BoundedWriter(std::size_t maxChars, std::string& out) : maxChars_(maxChars), out_(out) {}

  void write(const json& value, std::size_t depth) {
    if (full()) return;
    if (depth > kMaxDumpDepth && value.is_structured()) {
      out_ += value.is_array() ? "[...]" : "{...}";
      cut_ = true;
      return;
    }
    switch (value.type()) {
      case json::value_t::object: writeObject(value, depth); break;
      case json::value_t::array: writeArray(value, depth); break;
      case json::value_t::string: writeString(value.get_ref<const json::string_t&>()); break;
      default: out_ += value.dump(); break;  // numbers, booleans, null, binary: short
    }
  }

  [[nodiscard]] bool cut() const { return cut_; }

 private:
  [[nodiscard]] bool full() {
    if (out_.size() < maxChars_) return false;
    cut_ = true;
    return true;
  }

  void writeObject(const json& value, std::size_t depth) {
    out_ += '{';
    bool first = true;
    for (auto it = value.begin(); it != value.end(); ++it) {
      if (full()) return;
      if (!first) out_ += ',';
      first = false;
      writeString(it.key());
      out_ += ':';
      write(it.value(), depth + 1);
    }
    if (!full()) out_ += '}';
  }

  void writeArray(const json& value, std::size_t depth) {
    out_ += '[';
    bool first = true;
    for (const json& element : value) {
      if (full()) return;
      if (!first) out_ += ',';
      first = false;
      write(element, depth + 1);
    }
    if (!full()) out_ += ']';
  }

  void writeString(const std::string& text) {
    const std::size_t room = maxChars_ > out_.size() ? maxChars_ - out_.size() : 0;
    const std::string_view shown = utf8Prefix(text, room + 1);
    if (shown.size() < text.size()) cut_ = true;
    out_ += json(std::string(shown)).dump(-1, ' ', false, json::error_handler_t::replace);
  }

  std::size_t maxChars_;
  std::string& out_;
  bool cut_ = false;
};

}  // namespace

std::optional<JsonLimitViolation> findJsonLimitViolation(std::string_view text,
                                                         const JsonLimits& limits) noexcept {
  if (text.size() > limits.maxBytes) {
    return JsonLimitViolation{JsonLimitViolation::Kind::kTooLarge, limits.maxBytes, text.size()};
  }
  std::size_t depth = 0;
  bool inString = false;
  for (std::size_t i = 0; i < text.size(); ++i) {
    const char c = text[i];
    if (inString) {
      if (c == '\\') {
        ++i;
      } else if (c == '"') {
        inString = false;
      }
      continue;
    }
    if (c == '"') {
      inString = true;
    } else if (c == '[' || c == '{') {
      if (++depth > limits.maxDepth) {
        return JsonLimitViolation{JsonLimitViolation::Kind::kTooDeep, limits.maxDepth, i};
      }
    } else if ((c == ']' || c == '}') && depth > 0) {
      --depth;
    }
  }
  return std::nullopt;
}

std::string describeJsonLimitViolation(const JsonLimitViolation& violation, std::string_view document) {
  const std::string prefix = std::string(document) + ": ";
  if (violation.kind == JsonLimitViolation::Kind::kTooLarge) {
    return prefix + std::to_string(violation.at) + " bytes, more than the limit of " +
           std::to_string(violation.limit) + " bytes";
  }
  return prefix + "nested deeper than " + std::to_string(violation.limit) + " levels (at byte " +
         std::to_string(violation.at) + ")";
}

void checkJsonLimits(std::string_view text, const JsonLimits& limits, std::string_view document) {
  if (const auto violation = findJsonLimitViolation(text, limits)) {
    throw InputError(describeJsonLimitViolation(*violation, document));
  }
}

std::string jsonErrorText(const json::exception& error) {
  const std::string message = error.what();
  const auto end = message.find("] ");
  return message.rfind("[json.exception.", 0) == 0 && end != std::string::npos ? message.substr(end + 2)
                                                                               : message;
}

json parseJsonWithinLimits(std::string_view text, const JsonLimits& limits, std::string_view document) {
  checkJsonLimits(text, limits, document);
  // A key given twice in one object is refused: nlohmann keeps the last, so a reader and a
  // reviewer of the same text could see two different documents.
  std::vector<std::set<std::string>> keysOfOpenObjects;
  const json::parser_callback_t refuseDuplicateKeys = [&](int, json::parse_event_t event, json& parsed) {
    if (event == json::parse_event_t::object_start) {
      keysOfOpenObjects.emplace_back();
    } else if (event == json::parse_event_t::object_end && !keysOfOpenObjects.empty()) {
      keysOfOpenObjects.pop_back();
    } else if (event == json::parse_event_t::key && !keysOfOpenObjects.empty()) {
      const std::string& key = parsed.get_ref<const std::string&>();
      if (!keysOfOpenObjects.back().insert(key).second) {
        throw InputError(std::string(document) + ": not valid JSON here: the key \"" + std::string(utf8Prefix(key, 60)) +
                         "\" appears twice in one object");
      }
    }
    return true;
  };
  try {
    return json::parse(text.begin(), text.end(), refuseDuplicateKeys);
  } catch (const json::exception& error) {
    throw InputError(std::string(document) + ": not valid JSON: " + jsonErrorText(error));
  }
}

std::string boundedJsonDump(const json& value, std::size_t maxChars) {
  const std::size_t limit = maxChars < 4 ? 4 : maxChars;
  std::string text;
  BoundedWriter writer(limit, text);
  writer.write(value, 0);
  if (!writer.cut() && text.size() <= limit) return text;
  return std::string(utf8Prefix(text, limit - 3)) + "...";
}

std::string_view utf8Prefix(std::string_view text, std::size_t maxBytes) noexcept {
  if (text.size() <= maxBytes) return text;
  std::size_t end = maxBytes;
  // Back off over continuation bytes to the start of the cut character (at most 3 bytes).
  for (int i = 0; i < 4 && end > 0 && isContinuationByte(text[end]); ++i) --end;
  return text.substr(0, end);
}

LineReadStatus readBoundedLine(std::istream& in, std::string& line, std::size_t maxBytes) {
  using Traits = std::istream::traits_type;
  line.clear();
  std::streambuf* buffer = in.rdbuf();
  if (buffer == nullptr || !in.good()) return LineReadStatus::kEnd;
  bool any = false;
  bool tooLong = false;
  while (true) {
    const Traits::int_type c = buffer->sbumpc();
    if (Traits::eq_int_type(c, Traits::eof())) {
      in.setstate(std::ios::eofbit);
      break;
    }
    any = true;
    const char character = Traits::to_char_type(c);
    if (character == '\n') break;
    if (line.size() < maxBytes) {
      line.push_back(character);
    } else {
      tooLong = true;
    }
  }
  if (!any) return LineReadStatus::kEnd;
  return tooLong ? LineReadStatus::kTooLong : LineReadStatus::kLine;
}

}  // namespace lang2manip
