/// \file config_fields.cpp
/// Value text and the Markdown of the parameter tables (see config_fields.h).

#include "reach_trajopt/common/config_fields.h"

#include <charconv>
#include <cmath>
#include <sstream>

namespace reach_trajopt {

std::string parameterText(double v) {
  char buf[64];
  const std::to_chars_result r = std::to_chars(buf, buf + sizeof(buf), v);  // shortest exact
  return std::string(buf, r.ptr);
}

std::string parameterText(const std::vector<double>& v) {
  std::string out = "[";
  for (std::size_t i = 0; i < v.size(); ++i) out += (i ? ", " : "") + parameterText(v[i]);
  return out + "]";
}

bool Range::contains(double v) const {
  if (!std::isfinite(v)) return false;
  return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::text() const {
  const bool has_lo = std::isfinite(lo), has_hi = std::isfinite(hi);
  if (has_lo && has_hi)
    return "in " + std::string(lo_open ? "(" : "[") + parameterText(lo) + ", " + parameterText(hi) +
           (hi_open ? ")" : "]");
  if (has_lo) return (lo_open ? "> " : ">= ") + parameterText(lo);
  if (has_hi) return (hi_open ? "< " : "<= ") + parameterText(hi);
  return "finite";
}

std::string Range::words(bool integer) const {
  if (!std::isfinite(lo) && !std::isfinite(hi)) return "finite";
  if (std::isfinite(lo) && std::isfinite(hi)) return text();
  if (integer) return text();
  if (lo == 0.0 && lo_open && !std::isfinite(hi)) return "positive and finite";
  return text() + " and finite";
}

void throwOutOfRange(const std::string& owner, const std::string& key, const std::string& words,
                     double v) {
  std::ostringstream os;
  os << owner << ": " << key << " must be " << words << ", got " << v;
  throw ConfigError(os.str());
}

std::string quotedYaml(const std::string& text) {
  static const char* kHex = "0123456789abcdef";
  std::string out = "\"";
  for (char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (c == '"' || c == '\\') {
      out += '\\';
      out += ch;
    } else if (c < 0x20 || c == 0x7f) {
      out += "\\x";
      out += kHex[c >> 4];
      out += kHex[c & 15];
    } else {
      out += ch;
    }
  }
  return out + "\"";
}

namespace {

/// A table cell: '|' would end the cell.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '|' ? std::string("\\|") : std::string(1, c);
  return out;
}

}  // namespace

std::string parameterTableMarkdown(const std::vector<ParameterTable>& tables) {
  std::ostringstream os;
  os << "# Parameters\n\n"
     << "Generated from the field tables of the config structs (include/reach_trajopt/common/"
        "config_fields.h)\nby `parameter_table > docs/parameters.md`; do not edit by hand "
        "(test_parameter_table fails\nwhen this file is out of date). Each section of "
        "config/biped.yaml and config/sim.yaml is read\nby the struct named in its heading; a "
        "missing key keeps the value below, which is the struct's\ndefault and the shipped "
        "value; an unknown key is an error. Units SI, angles in radians.\n";
  for (const ParameterTable& t : tables) {
    os << "\n## `" << t.section << ":` (" << t.struct_name << ")\n\n"
       << t.summary << " Documented in `" << t.header << "`.\n\n"
       << "| key | type | value | unit | range | meaning |\n|---|---|---|---|---|---|\n";
    for (const ParameterRow& r : t.rows)
      os << "| `" << r.key << "` | " << cell(r.type) << " | " << cell(r.value) << " | "
         << cell(r.unit) << " | " << cell(r.range) << " | " << cell(r.description) << " |\n";
    if (!t.removed.empty()) {
      os << "\nRemoved keys (a file that still has one is an error):\n\n";
      for (const auto& r : t.removed) os << "- `" << r.first << "`: " << r.second << "\n";
    }
  }
  return os.str();
}

}  // namespace reach_trajopt
