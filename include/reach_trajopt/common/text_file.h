#pragma once
/// \file text_file.h
/// Whole input files (URDFs, YAML configurations, JSON requests) read with a bound on their
/// size: a path to a device or a runaway stream (/dev/zero, a log still growing) gives an error
/// naming the file instead of an unbounded allocation.

#include <cstddef>
#include <fstream>
#include <istream>
#include <string>

namespace reach_trajopt {

/// The largest input file read [bytes]: 64 MiB (TALOS's URDF is about 0.1 MiB).
constexpr std::size_t kMaxInputFileBytes = std::size_t{64} << 20;

/// Reads `in` to its end. `what` names the input in the errors: Error("<what>: larger than
/// <max_bytes> bytes, not read") past `max_bytes`, Error("cannot read <what>") on a read error.
template <class Error>
std::string readBounded(std::istream& in, const std::string& what,
                        std::size_t max_bytes = kMaxInputFileBytes) {
  std::string text;
  char chunk[1 << 16];
  while (in.read(chunk, sizeof chunk) || in.gcount() > 0) {
    const auto n = static_cast<std::size_t>(in.gcount());
    if (text.size() + n > max_bytes)
      throw Error(what + ": larger than " + std::to_string(max_bytes) + " bytes, not read");
    text.append(chunk, n);
  }
  if (in.bad()) throw Error("cannot read " + what);
  return text;
}

/// Opens `path` and reads it whole (readBounded); Error("cannot open <what>") when it cannot be
/// opened.
template <class Error>
std::string readTextFile(const std::string& path, const std::string& what,
                         std::size_t max_bytes = kMaxInputFileBytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw Error("cannot open " + what);
  return readBounded<Error>(in, what, max_bytes);
}

}  // namespace reach_trajopt
