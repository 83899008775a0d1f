#pragma once
/// \file json_reader.h
/// The one strict reader of JSON requests (qp_solve, reach_check, plan_transition, model_info
/// --state, ...). A JsonReader is one value of a parsed document plus its key path; every read
/// checks the type, the exact size and that numbers are finite, and every error is a ReachError
/// naming the source and the key path with the expected shape, e.g.
///   "request.json: swing.velocity: expected 3 numbers, got 0".
/// Objects are read with requireOnlyKeys() first, so an unknown (misspelled) key is an error
/// instead of a silently used default.

#include <Eigen/Core>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

/// Upper bound on a request document [bytes]: larger inputs are rejected before parsing (the
/// oracle tests send qp_solve batches of 80 MB).
constexpr std::size_t kMaxJsonRequestBytes = 256u << 20;

/// Whether a number read may be NaN or infinite (qp_solve reads "nan", "inf", "-inf" and null as
/// those values, for its invalid-input and infinite-bound tests); everything else is finite.
enum class NonFinite { kReject, kAllow };

class JsonReader {
 public:
  /// Parses `text`; throws ReachError "<source>: not valid JSON: ..." (also for numbers that
  /// overflow a double, e.g. 1e400, and for inputs over kMaxJsonRequestBytes).
  static nlohmann::json parse(const std::string& text, const std::string& source);
  /// Reads and parses a file ("-" is stdin); throws ReachError naming the file.
  static nlohmann::json parseFile(const std::string& path);

  /// `value` must outlive the reader. `source` names the document, `path` the key path ("" at
  /// the top).
  JsonReader(const nlohmann::json& value, std::string source, std::string path = "");

  const nlohmann::json& value() const { return *value_; }
  /// "<source>: <path>" (or "<source>" at the top), for messages.
  std::string where() const;
  /// Throws ReachError "<where>: <message>".
  [[noreturn]] void fail(const std::string& message) const;

  bool isObject() const { return value_->is_object(); }
  bool isArray() const { return value_->is_array(); }
  /// Throws unless the value is an object; `shape` describes what was expected.
  void requireObject(const std::string& shape = "an object") const;
  /// Throws naming the first key not in `allowed` (and listing the known ones).
  void requireOnlyKeys(const std::vector<std::string>& allowed) const;
  /// True when the object has `key` (false for non-objects).
  bool has(const std::string& key) const;
  /// The member `key` (throws "missing key" when absent; the value must be an object).
  JsonReader at(const std::string& key) const;
  /// Element i of an array (throws when out of range).
  JsonReader at(std::size_t i) const;
  /// Number of elements of an array (throws when not an array).
  std::size_t arraySize() const;
  /// Throws unless an array of min_size..max_size elements.
  std::size_t requireArray(std::size_t min_size, std::size_t max_size) const;

  /// This value as a number (finite unless `nf` allows).
  double number(NonFinite nf = NonFinite::kReject) const;
  /// This value as an integer in [lo, hi] (JSON integer, or a double with an integral value).
  long long integer(long long lo, long long hi) const;
  /// This value as a string.
  std::string string() const;
  /// This value as a string, one of `choices`.
  std::string choice(const std::vector<std::string>& choices) const;
  /// This value as a boolean.
  bool boolean() const;
  /// This value as a list of exactly `size` numbers (any size when size < 0).
  Eigen::VectorXd vector(Eigen::Index size = -1, NonFinite nf = NonFinite::kReject) const;
  /// This value as a list of rows of numbers, `rows` x `cols` (-1: any; rows must agree).
  Eigen::MatrixXd matrix(Eigen::Index rows = -1, Eigen::Index cols = -1,
                         NonFinite nf = NonFinite::kReject) const;

  /// Member shortcuts: the optional forms leave `out` unchanged and return false when absent.
  double number(const std::string& key) const { return at(key).number(); }
  bool optionalNumber(const std::string& key, double& out) const;
  Eigen::VectorXd vector(const std::string& key, Eigen::Index size) const {
    return at(key).vector(size);
  }
  bool optionalVector(const std::string& key, Eigen::Index size, Eigen::VectorXd& out) const;
  bool optionalChoice(const std::string& key, const std::vector<std::string>& choices,
                      std::string& out) const;

 private:
  std::string typeName() const;
  std::string childPath(const std::string& key) const;
  const nlohmann::json* value_;
  std::string source_, path_;
};

}  // namespace reach_trajopt
