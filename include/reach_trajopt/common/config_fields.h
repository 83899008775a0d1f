#pragma once
/// \file config_fields.h
/// One list of fields per config struct, the single place where a YAML key is spelled. The
/// list drives the YAML reading (fromYaml), the unknown-key error and the generated parameter
/// table docs/parameters.md (`parameter_table > docs/parameters.md`; test_parameter_table fails
/// when the file is out of date, or when a struct default differs from the shipped YAML).
///
/// How to give a config struct its table (ContactConfig is the smallest example):
///
///   // header: forward-declare, no YAML in public headers
///   template <typename Config> class ConfigFields;
///   struct MyConfig {
///     double mu = 0.7;  ///< ...
///     void validate() const;  // fields().checkRanges(*this), then what ties fields together
///     static const ConfigFields<MyConfig>& fields();  ///< its YAML keys (section `my:`)
///     static MyConfig fromYaml(const YamlSection& section) { ... fields().read(section) }
///   };
///
///   // .cpp
///   const ConfigFields<MyConfig>& MyConfig::fields() {
///     static const ConfigFields<MyConfig> f =
///         ConfigFields<MyConfig>("MyConfig", "my", "include/reach_trajopt/x/my.h", "what it is")
///             .add("mu", &MyConfig::mu, "", Range::positive(), "friction coefficient")
///             .add("gravity", &MyConfig::gravity, "m/s^2", "world frame")   // Eigen vectors
///             .choice("side", &MyConfig::side, {{"left", Side::kLeft}, {"right", Side::kRight}},
///                     "first swing")                                       // enums by name
///             .removed("old_key", "removed: use my.mu");  // an old file gets this error
///     return f;
///   }
///   MyConfig MyConfig::fromYaml(const YamlSection& s) { return fields().read(s); }
///
/// then add `MyConfig::fields().table()` to parameterTables()
/// (test/support/src/parameter_tables.cpp) and regenerate docs/parameters.md. Member types: double,
/// int, bool, std::string, std::vector<double>, unsigned and std::uint64_t (seeds: read as an int,
/// negative is an error), fixed-size Eigen vectors (the YAML sequence must have their size), enums
/// through choice(), anything else through custom(). read(section, base) reads over `base` (missing
/// keys keep its values) and ends with validate(), its error prefixed by the section's
/// location (validatedIn). A field's allowed range is data too: add(key, member, unit,
/// Range::positive(), description) puts it in the table's range column, and validate() checks
/// every such range with `fields().checkRanges(*this)` ("MyConfig: mu must be positive and
/// finite, got 0"); validate() itself keeps only what ties fields together. A key is spelled only
/// in its add() call; fromYaml() is fields().read().

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <limits>
#include <memory>
#include <optional>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "reach_trajopt/common/config_yaml.h"
#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

/// One documented parameter: a row of docs/parameters.md.
struct ParameterRow {
  std::string key;          ///< YAML key inside its section
  std::string type;         ///< "number", "integer", "bool", "string", "3 numbers", ...
  std::string value;        ///< the value in the struct (the default: equal to the shipped one)
  std::string unit;         ///< SI unit; "" when dimensionless
  std::string range;        ///< allowed values ("> 0", "in [0, 1]"); "" when not one range
  std::string description;  ///< what it does, what it costs
};

/// The allowed values of a number field (double, int, or each entry of a list of numbers):
/// finite and within [lo, hi], an open end excluded. ConfigFields::checkRanges checks it.
struct Range {
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false, hi_open = false;

  static Range positive() { return {0.0, std::numeric_limits<double>::infinity(), true, false}; }
  static Range nonNegative() { return atLeast(0.0); }
  static Range atLeast(double lo) { return {lo, std::numeric_limits<double>::infinity()}; }
  static Range between(double lo, double hi) { return {lo, hi}; }             ///< [lo, hi]
  static Range below(double lo, double hi) { return {lo, hi, false, true}; }  ///< [lo, hi)
  static Range positiveAtMost(double hi) { return {0.0, hi, true, false}; }   ///< (0, hi]
  /// Finite and within the range.
  bool contains(double v) const;
  /// For the table: "> 0", ">= 0", ">= 2", "in [0, 1]", "in [0, 1)".
  std::string text() const;
  /// For errors: "positive and finite", ">= 0 and finite" (integers: ">= 2"), "in [0, 1]".
  std::string words(bool integer) const;
};

/// The table of one config struct, without its type: what docs/parameters.md and the tests see.
struct ParameterTable {
  std::string struct_name;         ///< "ContactConfig"
  std::string section;             ///< YAML section it is read from, "contact"
  std::string header;              ///< header that documents it, "include/reach_trajopt/..."
  std::string summary;             ///< one line
  std::vector<ParameterRow> rows;  ///< the default values
  /// Keys that were removed, each with the error an old file gets.
  std::vector<std::pair<std::string, std::string>> removed;
  /// Reads a YAML section as fromYaml() does (unknown keys throw, validates) and returns the
  /// value text of every row, in row order: compare with `rows` to check the shipped file.
  std::function<std::vector<std::string>(const YamlSection&)> values_in;
};

/// Text of a value as the table shows it: numbers in the shortest form that reads back to the
/// same double ("0.001", "1e-06", "-0.16"), bools true/false, sequences "[a, b]".
std::string parameterText(double v);
std::string parameterText(const std::vector<double>& v);

/// ConfigError("<owner>: <key> must be <words>, got <v>").
[[noreturn]] void throwOutOfRange(const std::string& owner, const std::string& key,
                                  const std::string& words, double v);

/// `text` as a double-quoted YAML scalar (backslash, quote and control characters escaped).
std::string quotedYaml(const std::string& text);

/// The Markdown of docs/parameters.md for these tables (one section each).
std::string parameterTableMarkdown(const std::vector<ParameterTable>& tables);

namespace config_detail {

/// Reading, text and type name of one member type.
template <typename T, typename Enable = void>
struct Value;

template <>
struct Value<double> {
  static const char* type() { return "number"; }
  static bool read(const YamlSection& s, const std::string& k, double& v) { return s.read(k, v); }
  static std::string text(double v) { return parameterText(v); }
};
template <>
struct Value<int> {
  static const char* type() { return "integer"; }
  static bool read(const YamlSection& s, const std::string& k, int& v) { return s.read(k, v); }
  static std::string text(int v) { return std::to_string(v); }
};
/// Seeds: an integer, a negative value or one above the type's range is an error
/// ("<where>: must be >= 0").
template <typename U>
struct Value<U, std::enable_if_t<std::is_same_v<U, unsigned> || std::is_same_v<U, std::uint64_t>>> {
  static const char* type() { return "integer >= 0"; }
  static bool read(const YamlSection& s, const std::string& k, U& v) {
    long long i = 0;
    if (!s.read(k, i)) return false;
    if (i < 0) throw ConfigError(s.where(k) + ": must be >= 0");
    if (static_cast<unsigned long long>(i) > std::numeric_limits<U>::max())
      throw ConfigError(s.where(k) +
                        ": must be <= " + std::to_string(std::numeric_limits<U>::max()));
    v = static_cast<U>(i);
    return true;
  }
  static std::string text(U v) { return std::to_string(v); }
};
template <>
struct Value<bool> {
  static const char* type() { return "bool"; }
  static bool read(const YamlSection& s, const std::string& k, bool& v) { return s.read(k, v); }
  static std::string text(bool v) { return v ? "true" : "false"; }
};
template <>
struct Value<std::string> {
  static const char* type() { return "string"; }
  static bool read(const YamlSection& s, const std::string& k, std::string& v) {
    return s.read(k, v);
  }
  static std::string text(const std::string& v) { return v; }
};
template <>
struct Value<std::vector<double>> {
  static const char* type() { return "list of numbers"; }
  static bool read(const YamlSection& s, const std::string& k, std::vector<double>& v) {
    return s.read(k, v);
  }
  static std::string text(const std::vector<double>& v) { return parameterText(v); }
};
/// Fixed-size Eigen vectors (Eigen::Vector2d, Vector3d): a sequence of exactly that size.
template <typename T>
struct Value<T, std::enable_if_t<(std::is_base_of_v<Eigen::MatrixBase<T>, T> &&
                                  T::ColsAtCompileTime == 1 && T::RowsAtCompileTime > 0)>> {
  static std::string type() { return std::to_string(T::RowsAtCompileTime) + " numbers"; }
  static bool read(const YamlSection& s, const std::string& k, T& v) {
    Eigen::VectorXd x = v;
    if (!s.read(k, Eigen::Ref<Eigen::VectorXd>(x))) return false;
    v = x;
    return true;
  }
  static std::string text(const T& v) {
    return parameterText(std::vector<double>(v.data(), v.data() + v.size()));
  }
};

/// An optional value: unset (the table shows it empty) until the YAML gives it.
template <typename T>
struct Value<std::optional<T>> {
  static std::string type() { return std::string(Value<T>::type()) + " or unset"; }
  static bool read(const YamlSection& s, const std::string& k, std::optional<T>& v) {
    T x{};
    if (!Value<T>::read(s, k, x)) return false;
    v = x;
    return true;
  }
  static std::string text(const std::optional<T>& v) { return v ? Value<T>::text(*v) : ""; }
};

}  // namespace config_detail

/// The fields of one config struct (see the file comment). Immutable once built; build it
/// once in a function-local static.
template <typename Config>
class ConfigFields {
 public:
  ConfigFields(std::string struct_name, std::string section, std::string header,
               std::string summary) {
    table_.struct_name = std::move(struct_name);
    table_.section = std::move(section);
    table_.header = std::move(header);
    table_.summary = std::move(summary);
  }

  /// A field read from `key` into `member`; `unit` SI ("" dimensionless), `description` what it
  /// does (checks beyond one range stay in validate(), said here in words).
  template <typename T>
  ConfigFields& add(std::string key, T Config::*member, std::string unit, std::string description) {
    using V = config_detail::Value<T>;
    Field f;
    f.row = {std::move(key), V::type(), "", std::move(unit), "", std::move(description)};
    f.read = [member](const YamlSection& s, const std::string& k, Config& c) {
      V::read(s, k, c.*member);
    };
    f.text = [member](const Config& c) { return V::text(c.*member); };
    fields_.push_back(std::move(f));
    return *this;
  }

  /// The same for a number (double, int, a list of numbers: each entry) allowed in `range`:
  /// the table shows it, checkRanges() checks it.
  template <typename T>
  ConfigFields& add(std::string key, T Config::*member, std::string unit, Range range,
                    std::string description) {
    static_assert(std::is_same_v<T, double> || std::is_same_v<T, int> ||
                      std::is_same_v<T, std::vector<double>>,
                  "a range applies to a double, an int or a list of numbers");
    add(key, member, std::move(unit), std::move(description));
    Field& f = fields_.back();
    f.row.range = range.text();
    f.check = [owner = table_.struct_name, key, member, range](const Config& c) {
      const T& v = c.*member;
      if constexpr (std::is_same_v<T, std::vector<double>>) {
        for (double x : v)
          if (!range.contains(x)) throwOutOfRange(owner, key + " (each)", range.words(false), x);
      } else if (!range.contains(static_cast<double>(v))) {
        throwOutOfRange(owner, key, range.words(std::is_same_v<T, int>), static_cast<double>(v));
      }
    };
    return *this;
  }

  /// An enum field written by name in the YAML: "expected 'a' or 'b', got 'c'" otherwise.
  template <typename E>
  ConfigFields& choice(std::string key, E Config::*member,
                       std::vector<std::pair<std::string, E>> names, std::string description) {
    auto shared = std::make_shared<const std::vector<std::pair<std::string, E>>>(std::move(names));
    std::string type = "one of";
    for (const auto& n : *shared) type += " " + n.first;
    Field f;
    f.row = {std::move(key), type, "", "", "", std::move(description)};
    f.read = [member, shared](const YamlSection& s, const std::string& k, Config& c) {
      std::string name;
      if (!s.read(k, name)) return;
      for (const auto& n : *shared)
        if (n.first == name) {
          c.*member = n.second;
          return;
        }
      std::string expected;
      for (std::size_t i = 0; i < shared->size(); ++i)
        expected += (i == 0                    ? "'"
                     : i + 1 == shared->size() ? " or '"
                                               : ", '") +
                    (*shared)[i].first + "'";
      throw ConfigError(s.where(k) + ": expected " + expected + ", got '" + name + "'");
    };
    f.text = [member, shared](const Config& c) {
      for (const auto& n : *shared)
        if (n.second == c.*member) return n.first;
      return std::string("?");
    };
    fields_.push_back(std::move(f));
    return *this;
  }

  /// A field read its own way (a unit conversion, a combined check): `read` runs only when
  /// the key is present and throws ConfigError naming s.where(key) on a bad value; `text`
  /// shows the member's value for the table; `type` names the YAML type for the table.
  ConfigFields& custom(std::string key, std::string type,
                       std::function<void(const YamlSection&, const std::string&, Config&)> read,
                       std::function<std::string(const Config&)> text, std::string unit,
                       std::string description) {
    Field f;
    f.row = {std::move(key), std::move(type), "", std::move(unit), "", std::move(description)};
    f.read = [read = std::move(read)](const YamlSection& s, const std::string& k, Config& c) {
      if (s.has(k)) read(s, k, c);
    };
    f.text = std::move(text);
    fields_.push_back(std::move(f));
    return *this;
  }

  /// A sub-section `key:` whose keys `sub` reads into `member` (each optional, read over the
  /// member's value; unknown and removed keys of `sub` are errors there). Not validated by
  /// `sub`: this struct's validate() checks the member. The table shows the sub-section's rows
  /// as "key.subkey" (nested sections nest further: "a.b.c").
  template <typename Sub>
  ConfigFields& nested(std::string key, Sub Config::*member, const ConfigFields<Sub>& sub) {
    Field f;
    f.row.key = key;
    f.row.type = "section";
    f.shown = false;
    const ConfigFields<Sub>* sub_fields = &sub;  // fields() tables are function-local statics
    f.read = [member, sub_fields](const YamlSection& s, const std::string& k, Config& c) {
      if (s.has(k)) sub_fields->readInto(s.section(k), c.*member);
    };
    fields_.push_back(std::move(f));
    for (const auto& sf : sub.fields_) {
      if (!sf.shown) continue;
      Field row;
      row.row = sf.row;
      row.row.key = key + "." + sf.row.key;
      row.is_key = false;
      row.text = [member, text = sf.text](const Config& c) { return text(c.*member); };
      fields_.push_back(std::move(row));
    }
    return *this;
  }

  /// A key that was removed: a file that still has it gets ConfigError("<where>: <why>").
  ConfigFields& removed(std::string key, std::string why) {
    table_.removed.emplace_back(std::move(key), std::move(why));
    return *this;
  }

  const std::string& section() const { return table_.section; }

  /// Checks every field added with a Range: ConfigError("<struct>: <key> must be <range>, got
  /// <value>") for the first one outside it. validate() calls it.
  void checkRanges(const Config& config) const {
    for (const Field& f : fields_)
      if (f.check) f.check(config);
  }

  /// The accepted keys, in table order.
  std::vector<std::string> keys() const {
    std::vector<std::string> out;
    for (const Field& f : fields_)
      if (f.is_key) out.push_back(f.row.key);
    return out;
  }

  /// Reads every key present in `s` over `config` (missing keys keep its values); a removed
  /// key or an unknown key throws ConfigError naming it. Does not validate.
  void readInto(const YamlSection& s, Config& config) const {
    for (const std::string& k : s.keys())
      for (const auto& r : table_.removed)
        if (r.first == k) throw ConfigError(s.where(k) + ": " + r.second);
    s.requireOnlyKeys(keys());
    for (const Field& f : fields_)
      if (f.is_key) f.read(s, f.row.key, config);
  }

  /// readInto() over `config`, then validate() (errors prefixed with the section's location).
  Config read(const YamlSection& s, Config config = Config()) const {
    readInto(s, config);
    return validatedIn(s, std::move(config));
  }

  /// The rows of the table with the values of `config`.
  std::vector<ParameterRow> rows(const Config& config = Config()) const {
    std::vector<ParameterRow> out;
    for (const Field& f : fields_) {
      if (!f.shown) continue;
      out.push_back(f.row);
      out.back().value = f.text(config);
    }
    return out;
  }

  /// The type-erased table with the struct defaults (docs/parameters.md, tests).
  ParameterTable table() const {
    ParameterTable t = table_;
    t.rows = rows();
    const ConfigFields* self = this;  // fields() tables are function-local statics
    t.values_in = [self](const YamlSection& s) {
      std::vector<std::string> out;
      for (const ParameterRow& r : self->rows(self->read(s))) out.push_back(r.value);
      return out;
    };
    return t;
  }

 private:
  template <typename Other>
  friend class ConfigFields;
  struct Field {
    bool is_key = true;  ///< a key of this section (false: a row of a nested section)
    bool shown = true;   ///< a row of the table (false: a nested section's own key)
    ParameterRow row;
    std::function<void(const YamlSection&, const std::string&, Config&)> read;
    std::function<std::string(const Config&)> text;
    std::function<void(const Config&)> check;  ///< its Range's, when it has one
  };
  ParameterTable table_;
  std::vector<Field> fields_;
};

}  // namespace reach_trajopt
