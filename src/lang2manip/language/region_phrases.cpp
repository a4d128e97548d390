#include "lang2manip/language/region_phrases.hpp"

#include <string>

namespace lang2manip::language_detail {
namespace {

using Kind = SurfaceRegion::Kind;

/// +1 far (top), -1 near (bottom); 0 when `word` is not a depth word.
int depthOf(const std::string& word) {
  if (word == "far" || word == "top" || word == "upper" || word == "front" || word == "farther" || word == "further") return 1;
  if (word == "near" || word == "bottom" || word == "lower" || word == "back" || word == "nearer") return -1;
  return 0;
}

/// +1 left, -1 right; 0 otherwise.
int sideOf(const std::string& word) {
  if (word == "left" || word == "lefthand") return 1;
  if (word == "right" || word == "righthand") return -1;
  return 0;
}

std::optional<Kind> nounKind(const std::string& word) {
  if (word == "corner" || word == "corners") return Kind::kCorner;
  if (word == "side" || word == "edge" || word == "end" || word == "border") return Kind::kEdge;
  if (word == "half") return Kind::kHalf;
  if (word == "quadrant" || word == "quarter") return Kind::kQuadrant;
  if (word == "middle" || word == "centre" || word == "center") return Kind::kCentre;
  return std::nullopt;
}

int superlativeOf(const std::string& word) {
  if (word == "closest" || word == "nearest") return 1;
  if (word == "farthest" || word == "furthest") return -1;
  return 0;
}

/// What the modifiers and the noun of a phrase said.
struct Reading {
  int depth = 0;
  int side = 0;
  bool middle = false;
  int superlative = 0;
  std::optional<Kind> noun;
};

std::optional<SurfaceRegion> regionOf(const Reading& r) {
  if (!r.noun) {
    if (r.depth != 0 && r.side != 0) return SurfaceRegion{Kind::kCorner, r.depth, r.side};  // "the upper right"
    return std::nullopt;
  }
  switch (*r.noun) {
    case Kind::kCorner: return SurfaceRegion{Kind::kCorner, r.depth, r.side};
    case Kind::kEdge:
      if (r.depth != 0 && r.side != 0) return SurfaceRegion{Kind::kCorner, r.depth, r.side};
      if (r.depth == 0 && r.side == 0) return std::nullopt;  // "the side": which one is the caller's question
      return SurfaceRegion{Kind::kEdge, r.depth, r.side};
    case Kind::kHalf:
      if ((r.depth == 0) == (r.side == 0)) return std::nullopt;
      return SurfaceRegion{Kind::kHalf, r.depth, r.side};
    case Kind::kQuadrant:
      if (r.depth == 0 || r.side == 0) return std::nullopt;
      return SurfaceRegion{Kind::kQuadrant, r.depth, r.side};
    case Kind::kCentre:
      if (r.depth != 0 || r.side != 0) return std::nullopt;
      return SurfaceRegion{Kind::kCentre, 0, 0};
  }
  return std::nullopt;
}

}  // namespace

std::size_t regionPreposition(const Words& words, std::size_t at) {
  return longestPhraseAt(words, at, {{"in"}, {"on"}, {"at"}, {"to"}, {"into"}, {"onto"}, {"toward"}, {"towards"}, {"in", "to"},
                                     {"over", "to"}, {"on", "to"}, {"along"}, {"by"}, {"near"}});
}

std::optional<RegionPhrase> matchRegionPhrase(const Words& words, std::size_t at) {
  std::size_t i = at;
  if (i < words.size() && (words[i] == "the" || words[i] == "a" || words[i] == "one" || words[i] == "its" || words[i] == "their")) ++i;
  Reading reading;
  for (; i < words.size(); ++i) {
    const std::string& word = words[i];
    if (word == "hand" || word == "most" || word == "-") continue;  // "left hand", "left-most"
    if (const int depth = depthOf(word)) {
      if (reading.depth != 0) return std::nullopt;
      reading.depth = depth;
    } else if (const int side = sideOf(word)) {
      if (reading.side != 0) return std::nullopt;
      reading.side = side;
    } else if (const int superlative = superlativeOf(word)) {
      reading.superlative = superlative;
    } else {
      break;
    }
  }
  if (i < words.size()) {
    if (const auto kind = nounKind(words[i])) {
      // "the middle" as a modifier ("the middle of the left side") is not read here.
      reading.noun = kind;
      ++i;
    }
  }
  const std::optional<SurfaceRegion> region = regionOf(reading);
  if (!region && !(reading.noun == Kind::kCorner)) return std::nullopt;
  RegionPhrase phrase;
  phrase.region = region.value_or(SurfaceRegion{Kind::kCorner, 0, 0});
  // "the corner closest to X", "the closest corner to X", "the corner nearest (to) X"
  if (i < words.size() && reading.superlative == 0) {
    if (const int superlative = superlativeOf(words[i])) {
      reading.superlative = superlative;
      ++i;
    }
  }
  if (reading.superlative != 0 && phrase.region.kind == Kind::kCorner) {
    if (i < words.size() && (words[i] == "to" || words[i] == "from")) ++i;
    phrase.nearestCorner = reading.superlative > 0;
    phrase.farthestCorner = reading.superlative < 0;
    phrase.referenceAt = i;
  } else if (reading.superlative != 0) {
    return std::nullopt;
  }
  phrase.length = i - at;
  return phrase;
}

}  // namespace lang2manip::language_detail
