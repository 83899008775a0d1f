#pragma once
/// \file config_yaml.h
/// A small, strict reader for the YAML files under config/. It keeps yaml-cpp out of the public
/// headers (the core library links it privately): a YamlSection is one mapping of a file, and
/// every read names the file and the key path in its error message, e.g.
///   "config/biped.yaml: planner.t_s: expected a number, got 'abc'".
/// Missing keys keep the caller's default (the paper's value); keys the reader does not know
/// are reported by requireOnlyKeys(), so a typo in a YAML file cannot pass silently.

#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

/// The top-level sections a config file may hold (config/biped.yaml, config/sim.yaml); any
/// other top-level key of a file read by YamlSection::loadFile is an error.
const std::vector<std::string>& configSections();

/// One YAML mapping (the whole file or a nested section) with typed, checked reads.
class YamlSection {
 public:
  /// Parses a config file; throws ReachError naming the file when missing or malformed, when
  /// its top level is not a mapping of configSections(), or when a key appears twice in one
  /// mapping (yaml-cpp would silently keep one).
  static YamlSection loadFile(const std::string& path);
  /// Parses YAML text (any top-level keys, duplicates rejected); `source` names it in errors.
  static YamlSection loadString(const std::string& text, const std::string& source = "<string>");

  /// True when the mapping has the key (a nested "a.b" path is not interpreted).
  bool has(const std::string& key) const;
  /// The nested mapping under `key`; throws ReachError when missing or not a mapping.
  YamlSection section(const std::string& key) const;
  /// Keys of this mapping, in file order.
  std::vector<std::string> keys() const;
  /// Throws ReachError naming the first key not in `allowed` (catches typos).
  void requireOnlyKeys(const std::vector<std::string>& allowed) const;

  /// Each read leaves `value` unchanged when the key is missing and throws ReachError when the
  /// key is present with the wrong type. Returns whether the key was present.
  bool read(const std::string& key, double& value) const;
  bool read(const std::string& key, int& value) const;
  bool read(const std::string& key, long long& value) const;
  bool read(const std::string& key, bool& value) const;
  bool read(const std::string& key, std::string& value) const;
  bool read(const std::string& key, std::vector<double>& value) const;
  /// A fixed-size vector: the YAML sequence must have exactly value.size() numbers.
  bool read(const std::string& key, Eigen::Ref<Eigen::VectorXd> value) const;

  /// "file: a.b" of this section, for error messages.
  std::string where() const;
  /// "file: a.b.key", for error messages about one value.
  std::string where(const std::string& key) const;

 private:
  struct Impl;
  explicit YamlSection(std::shared_ptr<const Impl> impl);
  std::shared_ptr<const Impl> impl_;
};

/// Runs config.validate() and returns the config; a ReachError it throws is re-thrown with the
/// section's location in front ("config/biped.yaml: planner: ..."). Every fromYaml() ends here.
template <typename Config>
Config validatedIn(const YamlSection& section, Config config) {
  try {
    config.validate();
  } catch (const ReachError& e) {
    throw ConfigError(section.where() + ": " + e.what());
  }
  return config;
}

}  // namespace reach_trajopt
