#include "reach_trajopt/common/config_yaml.h"

#include <yaml-cpp/eventhandler.h>
#include <yaml-cpp/yaml.h>

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>

#include "reach_trajopt/common/text_file.h"

namespace reach_trajopt {

struct YamlSection::Impl {
  YAML::Node node;
  std::string source;  // file name or "<string>"
  std::string path;    // "a.b" inside the file, "" at the top
};

namespace {

std::string describe(const YAML::Node& n) {
  if (n.IsScalar()) return "'" + n.Scalar() + "'";
  if (n.IsSequence()) return "a sequence";
  if (n.IsMap()) return "a mapping";
  return "null";
}

/// Throws naming `source`, the key path and the line of the first mapping key that appears
/// twice: yaml-cpp keeps both entries and lookups silently take one of them.
void rejectDuplicateKeys(const YAML::Node& n, const std::string& source, const std::string& path) {
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      rejectDuplicateKeys(n[i], source, path + "[" + std::to_string(i) + "]");
    return;
  }
  if (!n.IsMap()) return;
  std::set<std::string> seen;
  for (const auto& kv : n) {
    const std::string key =
        kv.first.IsScalar() ? kv.first.Scalar() : std::string("<non-scalar key>");
    const std::string where = path.empty() ? key : path + "." + key;
    if (!kv.first.IsScalar())
      throw ConfigError(source + ": " + where + ": mapping keys must be plain scalars");
    if (!seen.insert(key).second) {
      std::ostringstream os;
      os << source << ": " << where << ": duplicate key (line " << kv.first.Mark().line + 1 << ")";
      throw ConfigError(os.str());
    }
    rejectDuplicateKeys(kv.second, source, where);
  }
}

/// Throws at the first alias: `&a [*b, *b]` nine levels deep is 306 bytes that yaml-cpp's node
/// graph shares but every walk over it (duplicate keys, the section reads) expands 2^9-fold.
/// The event parser reads the text once, linearly, and stops there.
class AliasRefuser : public YAML::EventHandler {
 public:
  explicit AliasRefuser(const std::string& source) : source_(source) {}
  void OnDocumentStart(const YAML::Mark&) override {}
  void OnDocumentEnd() override {}
  void OnNull(const YAML::Mark&, YAML::anchor_t) override {}
  void OnAlias(const YAML::Mark& mark, YAML::anchor_t) override {
    std::ostringstream os;
    os << source_ << ": line " << mark.line + 1 << ": YAML aliases (*name) are not accepted "
       << "(an alias can expand a few bytes into gigabytes): write the value out";
    throw ConfigError(os.str());
  }
  void OnScalar(const YAML::Mark&, const std::string&, YAML::anchor_t,
                const std::string&) override {}
  void OnSequenceStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                       YAML::EmitterStyle::value) override {}
  void OnSequenceEnd() override {}
  void OnMapStart(const YAML::Mark&, const std::string&, YAML::anchor_t,
                  YAML::EmitterStyle::value) override {}
  void OnMapEnd() override {}

 private:
  std::string source_;
};

/// Parses `text` (named `source` in errors) refusing aliases first. Only the first document is
/// read, as YAML::Load reads it (looping over HandleNextDocument never ended on ",:", an input
/// the fuzzer found).
YAML::Node parseWithoutAliases(const std::string& text, const std::string& source) {
  std::istringstream in(text);
  YAML::Parser parser(in);
  AliasRefuser refuser(source);
  parser.HandleNextDocument(refuser);
  return YAML::Load(text);
}

YAML::Node checkedRoot(const YAML::Node& root, const std::string& source) {
  if (!root.IsMap()) throw ConfigError("YAML " + source + ": top level is not a mapping");
  rejectDuplicateKeys(root, source, "");
  return root;
}

/// Reads the scalar `node` (the value of `key` in `section`) as a T into `value`: false when
/// missing, a ConfigError "<where>: expected <expected>, got <what>" when not a T.
template <typename T>
bool readScalar(const YamlSection& section, const YAML::Node& node, const std::string& key,
                const char* expected, T& value) {
  if (!node) return false;
  try {
    if (!node.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "not a scalar");
    value = node.as<T>();
  } catch (const YAML::Exception&) {
    throw ConfigError(section.where(key) + ": expected " + expected + ", got " + describe(node));
  }
  return true;
}

}  // namespace

const std::vector<std::string>& configSections() {
  static const std::vector<std::string> sections = {
      "robot", "contact", "planner", "kinematic_feasibility", "reach", "wbc",
      "walk",  "ocp",     "sim",     "nearest_foothold"};
  return sections;
}

YamlSection::YamlSection(std::shared_ptr<const Impl> impl) : impl_(std::move(impl)) {}

YamlSection YamlSection::loadFile(const std::string& path) {
  YAML::Node root;
  const std::string text = readTextFile<ConfigError>(path, "YAML file '" + path + "'");
  try {
    root = parseWithoutAliases(text, "YAML file '" + path + "'");
  } catch (const YAML::Exception& e) {
    throw ConfigError("malformed YAML in '" + path + "': " + e.what());
  }
  if (!root.IsMap()) throw ConfigError("YAML file '" + path + "': top level is not a mapping");
  auto impl = std::make_shared<Impl>();
  impl->node = checkedRoot(root, path);
  impl->source = path;
  YamlSection file(impl);
  // A misspelled section would otherwise leave its component on the defaults.
  file.requireOnlyKeys(configSections());
  return file;
}

YamlSection YamlSection::loadString(const std::string& text, const std::string& source) {
  YAML::Node root;
  try {
    root = parseWithoutAliases(text, source);
  } catch (const YAML::Exception& e) {
    throw ConfigError("malformed YAML in " + source + ": " + e.what());
  }
  auto impl = std::make_shared<Impl>();
  impl->node = checkedRoot(root, source);
  impl->source = source;
  return YamlSection(impl);
}

std::string YamlSection::where() const {
  return impl_->source + (impl_->path.empty() ? std::string() : ": " + impl_->path);
}

std::string YamlSection::where(const std::string& key) const {
  return impl_->source + ": " + (impl_->path.empty() ? key : impl_->path + "." + key);
}

bool YamlSection::has(const std::string& key) const { return static_cast<bool>(impl_->node[key]); }

YamlSection YamlSection::section(const std::string& key) const {
  const YAML::Node n = impl_->node[key];
  if (!n) throw ConfigError(where(key) + ": missing section");
  if (!n.IsMap()) throw ConfigError(where(key) + ": expected a mapping, got " + describe(n));
  auto impl = std::make_shared<Impl>();
  impl->node = n;
  impl->source = impl_->source;
  impl->path = impl_->path.empty() ? key : impl_->path + "." + key;
  return YamlSection(impl);
}

std::vector<std::string> YamlSection::keys() const {
  std::vector<std::string> out;
  for (const auto& kv : impl_->node) out.push_back(kv.first.as<std::string>());
  return out;
}

void YamlSection::requireOnlyKeys(const std::vector<std::string>& allowed) const {
  for (const std::string& k : keys()) {
    if (std::find(allowed.begin(), allowed.end(), k) == allowed.end()) {
      std::ostringstream os;
      os << where(k) << ": unknown key (known:";
      for (const auto& a : allowed) os << " " << a;
      os << ")";
      throw ConfigError(os.str());
    }
  }
}

bool YamlSection::read(const std::string& key, double& value) const {
  const YAML::Node n = impl_->node[key];
  if (!n) return false;
  double v = 0.0;
  try {
    if (!n.IsScalar()) throw YAML::Exception(YAML::Mark::null_mark(), "not a scalar");
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    throw ConfigError(where(key) + ": expected a number, got " + describe(n));
  }
  if (std::isnan(v)) throw ConfigError(where(key) + ": NaN is not allowed");
  value = v;
  return true;
}

bool YamlSection::read(const std::string& key, int& value) const {
  return readScalar(*this, impl_->node[key], key, "an integer", value);
}

bool YamlSection::read(const std::string& key, long long& value) const {
  return readScalar(*this, impl_->node[key], key, "an integer", value);
}

bool YamlSection::read(const std::string& key, bool& value) const {
  return readScalar(*this, impl_->node[key], key, "true or false", value);
}

bool YamlSection::read(const std::string& key, std::string& value) const {
  const YAML::Node n = impl_->node[key];
  if (!n) return false;
  if (!n.IsScalar()) throw ConfigError(where(key) + ": expected a string, got " + describe(n));
  value = n.Scalar();
  return true;
}

bool YamlSection::read(const std::string& key, std::vector<double>& value) const {
  const YAML::Node n = impl_->node[key];
  if (!n) return false;
  if (!n.IsSequence()) {
    throw ConfigError(where(key) + ": expected a sequence of numbers, got " + describe(n));
  }
  std::vector<double> out;
  for (std::size_t i = 0; i < n.size(); ++i) {
    try {
      out.push_back(n[i].as<double>());
    } catch (const YAML::Exception&) {
      throw ConfigError(where(key) + "[" + std::to_string(i) + "]: expected a number, got " +
                        describe(n[i]));
    }
    if (std::isnan(out.back())) {
      throw ConfigError(where(key) + "[" + std::to_string(i) + "]: NaN is not allowed");
    }
  }
  value = out;
  return true;
}

bool YamlSection::read(const std::string& key, Eigen::Ref<Eigen::VectorXd> value) const {
  std::vector<double> v;
  if (!read(key, v)) return false;
  if (static_cast<Eigen::Index>(v.size()) != value.size()) {
    std::ostringstream os;
    os << where(key) << ": expected " << value.size() << " numbers, got " << v.size();
    throw ConfigError(os.str());
  }
  for (std::size_t i = 0; i < v.size(); ++i) value[static_cast<Eigen::Index>(i)] = v[i];
  return true;
}

}  // namespace reach_trajopt
