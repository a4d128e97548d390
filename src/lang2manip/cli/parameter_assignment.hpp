#pragma once
/// @file `--param NAME=VALUE` arguments of the planning commands.

#include <string>
#include <utility>

#include "lang2manip/core/error.hpp"

namespace lang2manip {

/// (NAME, VALUE) of a `--param NAME=VALUE` argument; throws InputError naming it when it has no
/// '=' or no name.
inline std::pair<std::string, std::string> parseParameterAssignment(const std::string& argument) {
  const auto equals = argument.find('=');
  if (equals == std::string::npos || equals == 0) {
    throw InputError("--param \"" + argument + "\": expected NAME=VALUE");
  }
  return {argument.substr(0, equals), argument.substr(equals + 1)};
}

}  // namespace lang2manip
