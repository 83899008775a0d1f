#pragma once
/// \file enum_names.h
/// One name table per enum, used only at the edges (config files, JSON, messages, CSV, WALK
/// lines): the code compares enum values, the table turns them into the words users read and
/// write, and back.
///
///   const EnumNames<OcpStatus>& names() { static const EnumNames<OcpStatus> n = {...}; ... }
///   nameOf(names(), OcpStatus::kRelaxed)                  // "relaxed"
///   valueOf(names(), "relaxed", "ocp status")             // OcpStatus::kRelaxed, or throws

#include <string>
#include <utility>
#include <vector>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

/// (name, value) pairs, each value once, in the order they are listed to users.
template <typename E>
using EnumNames = std::vector<std::pair<const char*, E>>;

/// The name of `value`; "?" for a value the table lacks (a table that misses a value is a bug
/// its enum's test catches).
template <typename E>
const char* nameOf(const EnumNames<E>& names, E value) {
  for (const auto& n : names)
    if (n.second == value) return n.first;
  return "?";
}

/// "a|b|c": the names of the table, for messages.
template <typename E>
std::string namesList(const EnumNames<E>& names, const char* separator = "|") {
  std::string list;
  for (const auto& n : names) list += std::string(list.empty() ? "" : separator) + n.first;
  return list;
}

/// The value named `name`. \throws RequestError "<what> '<name>': expected a|b|c".
template <typename E>
E valueOf(const EnumNames<E>& names, const std::string& name, const std::string& what) {
  for (const auto& n : names)
    if (name == n.first) return n.second;
  throw RequestError(what + " '" + name + "': expected " + namesList(names));
}

}  // namespace reach_trajopt
