#include "lang2manip/language/stack_order.hpp"

#include <algorithm>

#include "lang2manip/language/vocabulary.hpp"

namespace lang2manip::language_detail {
namespace {

const std::vector<Words> kOrderWords{{"in", "this", "order"}, {"in", "that", "order"}, {"in", "the", "following", "order"}, {"in", "the", "order"},
                                     {"in", "order"}, {"in", "this", "sequence"}, {"in", "sequence"}, {"as", "follows"}};
const std::vector<Words> kBottomFirst{{"from", "the", "bottom", "up"}, {"from", "the", "bottom"}, {"from", "bottom", "to", "top"},
                                      {"bottom", "to", "top"}, {"bottom", "up"}, {"from", "the", "base"}};
const std::vector<Words> kTopFirst{{"from", "the", "top", "down"}, {"from", "the", "top"}, {"from", "top", "to", "bottom"}, {"top", "to", "bottom"}};
const std::vector<Words> kAtBottom{{"at", "the", "bottom"}, {"on", "the", "bottom"}, {"at", "the", "base"}, {"as", "the", "base"}, {"first"}};
const std::vector<Words> kOnTop{{"on", "top"}, {"on", "the", "top"}, {"at", "the", "top"}, {"last"}};
const std::vector<Words> kMiddle{{"in", "the", "middle"}, {"in", "between"}, {"next"}};

/// The singular of a noun as the lexicon may hold it ("blocks" -> "block", "boxes" -> "box").
std::string singular(const std::string& noun) {
  for (const char* ending : {"xes", "ches", "shes", "sses"}) {
    const std::string e(ending);
    if (noun.size() > e.size() && noun.compare(noun.size() - e.size(), e.size(), e) == 0) return noun.substr(0, noun.size() - 2);
  }
  return noun.size() > 1 && noun.back() == 's' && noun[noun.size() - 2] != 's' ? noun.substr(0, noun.size() - 1) : noun;
}

/// One item of the list with what it says of its place: -1 at the bottom, +1 on top, 0 neither.
struct Item {
  Words words;
  int place = 0;
};

/// The items of words[at...] joined by ",", "and" and "then", their place words taken off.
std::vector<Item> itemsOf(const Words& words, std::size_t at) {
  std::vector<Item> items(1);
  for (std::size_t i = at; i < words.size();) {
    if (words[i] == "," || words[i] == "and" || words[i] == "then" || words[i] == ":" || words[i] == ";") {
      if (!items.back().words.empty()) items.emplace_back();
      ++i;
    } else if (const std::size_t bottom = longestPhraseAt(words, i, kAtBottom)) {
      items.back().place = -1, i += bottom;
    } else if (const std::size_t top = longestPhraseAt(words, i, kOnTop)) {
      items.back().place = 1, i += top;
    } else if (const std::size_t middle = longestPhraseAt(words, i, kMiddle)) {
      i += middle;
    } else {
      items.back().words.push_back(words[i++]);
    }
  }
  if (items.back().words.empty()) items.pop_back();
  return items;
}

}  // namespace

std::optional<Words> orderedStack(const Words& words, const NounPhraseReader& reader) {
  const std::optional<vocabulary::VerbMatch> verb = vocabulary::matchVerb(words, 0);
  if (!verb || !verb->verb.stacks) return std::nullopt;
  std::size_t at = verb->length;
  std::string head;  // the noun an item of bare adjectives stands for ("blue" -> "blue block")
  bool ordered = false, topFirst = false;
  if (const std::optional<NounPhrase> objects = reader.read(words, at); objects && longestPhraseAt(words, objects->end, kOrderWords) > 0) {
    head = singular(words[objects->end - 1]);
    at = objects->end;
  }
  for (bool more = true; more;) {  // "in this order", "from the top", ":" in any order
    more = false;
    if (const std::size_t order = longestPhraseAt(words, at, kOrderWords)) at += order, ordered = more = true;
    if (const std::size_t bottom = longestPhraseAt(words, at, kBottomFirst)) at += bottom, ordered = more = true;
    if (const std::size_t top = longestPhraseAt(words, at, kTopFirst)) at += top, ordered = more = true, topFirst = true;
    if (at < words.size() && (words[at] == ":" || words[at] == ",")) ++at, more = true;
  }
  std::vector<Item> items = itemsOf(words, at);
  const bool placed = std::any_of(items.begin(), items.end(), [](const Item& item) { return item.place != 0; });
  const bool thenSaid = std::find(words.begin() + static_cast<std::ptrdiff_t>(at), words.end(), "then") != words.end();
  if (items.size() < 2 || !(ordered || placed || thenSaid)) return std::nullopt;
  // Bottom first unless the list goes from the top: said so, or its first item is on top.
  if (topFirst || items.front().place > 0 || items.back().place < 0) std::reverse(items.begin(), items.end());
  Words rewritten{"stack"};
  for (std::size_t i = 0; i < items.size(); ++i) {
    Words item = items[i].words;
    std::optional<NounPhrase> phrase = reader.read(item, 0);
    if ((!phrase || !phrase->noun) && !head.empty()) item.push_back(head), phrase = reader.read(item, 0);
    if (!phrase || phrase->end != item.size() || phrase->unknownNoun) return std::nullopt;
    if (i > 0) rewritten.emplace_back(i + 1 == items.size() ? "and" : ",");
    rewritten.insert(rewritten.end(), item.begin(), item.end());
  }
  return rewritten;
}

}  // namespace lang2manip::language_detail
