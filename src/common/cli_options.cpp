/// \file cli_options.cpp
/// A tool's option table and its parser (cli_options.h).

#include "reach_trajopt/common/cli_options.h"

#include <algorithm>
#include <iostream>
#include <set>
#include <sstream>

#include "reach_trajopt/common/error.h"

namespace reach_trajopt {

bool CliArgs::given(const std::string& name) const { return given_.count(name) > 0; }

std::string CliArgs::value(const std::string& name) const {
  const auto it = given_.find(name);
  if (it == given_.end()) {
    const auto d = defaults_.find(name);
    return d == defaults_.end() ? std::string() : d->second;
  }
  std::string out;
  for (const std::string& v : it->second) out += (out.empty() ? "" : " ") + v;
  return out;
}

const std::vector<std::string>& CliArgs::values(const std::string& name) const {
  static const std::vector<std::string> kNone;
  const auto it = given_.find(name);
  return it == given_.end() ? kNone : it->second;
}

CliTool::CliTool(std::string name, std::string synopsis, std::string description,
                 std::vector<CliOption> options)
    : name_(std::move(name)),
      synopsis_(std::move(synopsis)),
      description_(std::move(description)),
      options_(std::move(options)) {
  std::set<std::string> seen = {"-h", "--help"};
  for (const CliOption& o : options_) {
    std::vector<std::string> names = {o.name};
    if (!o.alias.empty()) names.push_back(o.alias);
    for (const std::string& n : names)
      if (n.size() < 2 || n[0] != '-' || !seen.insert(n).second)
        throw ReachError(name_ + ": bad or repeated option name '" + n + "' in its table");
    if (!o.argument.empty() && o.arity < 1)
      throw ReachError(name_ + ": option " + o.name + " takes an argument but arity < 1");
  }
}

const CliOption* CliTool::find(const std::string& arg) const {
  for (const CliOption& o : options_)
    if (arg == o.name || (!o.alias.empty() && arg == o.alias)) return &o;
  return nullptr;
}

int CliTool::run(int argc, char** argv, const std::function<int(const CliArgs&)>& body) const {
  return run(argc, argv, body,
             [this](const std::exception& e) { std::cerr << name_ << ": " << e.what() << "\n"; });
}

int CliTool::run(int argc, char** argv, const std::function<int(const CliArgs&)>& body,
                 const std::function<void(const std::exception&)>& reportError) const {
  try {
    const CliArgs args = parse(argc, argv);
    if (args.help()) {
      std::cout << usage();
      return 0;
    }
    return body(args);
  } catch (const std::exception& e) {
    reportError(e);
    return 2;
  }
}

CliArgs CliTool::parse(int argc, const char* const* argv) const {
  CliArgs out;
  for (const CliOption& o : options_)
    if (!o.default_value.empty()) out.defaults_[o.name] = o.default_value;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--help" || a == "-h") {
      out.help_ = true;
      continue;
    }
    if (a.size() < 2 || a[0] != '-') {
      out.positional_.push_back(a);
      continue;
    }
    const CliOption* o = find(a);
    if (!o) throw RequestError("unknown option '" + a + "' (see " + name_ + " --help)");
    std::vector<std::string> values;
    if (!o->argument.empty()) {
      if (i + o->arity >= argc) throw RequestError(a + ": missing value");
      for (int k = 0; k < o->arity; ++k) values.push_back(argv[++i]);
    }
    out.given_[o->name] = values;
  }
  return out;
}

std::string CliTool::usageLine() const {
  std::string line = "usage: " + name_ + " [options]";
  if (!synopsis_.empty()) line += " " + synopsis_;
  return line;
}

std::string CliTool::usage() const {
  std::ostringstream os;
  os << usageLine() << "\n";
  if (!description_.empty()) os << "\n" << description_ << "\n";
  std::vector<std::string> heads;
  std::size_t width = std::string("-h, --help").size();
  for (const CliOption& o : options_) {
    std::string h = o.alias.empty() ? o.name : o.name + ", " + o.alias;
    if (!o.argument.empty()) h += " " + o.argument;
    width = std::max(width, h.size());
    heads.push_back(h);
  }
  os << "\noptions:\n";
  for (std::size_t k = 0; k < options_.size(); ++k) {
    const CliOption& o = options_[k];
    os << "  " << heads[k] << std::string(width + 2 - heads[k].size(), ' ') << o.help;
    if (!o.default_value.empty()) os << " (default: " << o.default_value << ")";
    os << "\n";
  }
  os << "  "
     << "-h, --help" << std::string(width + 2 - 10, ' ') << "print this help and exit\n";
  return os.str();
}

}  // namespace reach_trajopt
