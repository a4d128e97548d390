#include "lang2manip/symbolic/symbolic_state.hpp"

#include <algorithm>

namespace lang2manip {

std::vector<std::string> SymbolicState::objectsOn(const std::string& object) const {
  std::vector<std::string> result;
  for (const auto& [item, container] : inside) {
    if (container == object) result.push_back(item);
  }
  for (const auto& [item, support] : onTopOf) {
    if (support == object) result.push_back(item);
  }
  return result;
}

bool SymbolicState::isClear(const std::string& object) const { return objectsOn(object).empty(); }

bool SymbolicState::hasObject(const std::string& object) const {
  return std::find(objects.begin(), objects.end(), object) != objects.end();
}

}  // namespace lang2manip
