/// \file json_reader.cpp
/// The strict JSON request reader (json_reader.h).

#include "reach_trajopt/common/json_reader.h"

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>

#include "reach_trajopt/common/text_file.h"

namespace reach_trajopt {

using nlohmann::json;

json JsonReader::parse(const std::string& text, const std::string& source) {
  if (text.size() > kMaxJsonRequestBytes) {
    std::ostringstream os;
    os << source << ": request of " << text.size() << " bytes exceeds the limit of "
       << kMaxJsonRequestBytes << " bytes";
    throw RequestError(os.str());
  }
  try {
    return json::parse(text);
  } catch (const json::exception& e) {
    // nlohmann's text names a byte position and, for 1e400, "number overflow".
    std::string what = e.what();
    const std::size_t bracket = what.find("] ");
    if (what.rfind("[json.exception.", 0) == 0 && bracket != std::string::npos)
      what = what.substr(bracket + 2);
    throw RequestError(source + ": not valid JSON: " + what);
  }
}

json JsonReader::parseFile(const std::string& path) {
  if (path == "-")
    return parse(readBounded<RequestError>(std::cin, "<stdin>", kMaxJsonRequestBytes), "<stdin>");
  return parse(
      readTextFile<RequestError>(path, "request file '" + path + "'", kMaxJsonRequestBytes), path);
}

JsonReader::JsonReader(const json& value, std::string source, std::string path)
    : value_(&value), source_(std::move(source)), path_(std::move(path)) {}

std::string JsonReader::where() const {
  if (path_.empty()) return source_;
  return source_ + ": " + path_;
}

void JsonReader::fail(const std::string& message) const {
  throw RequestError(where() + ": " + message);
}

std::string JsonReader::typeName() const {
  switch (value_->type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return "a boolean";
    case json::value_t::string:
      return "a string";
    case json::value_t::array:
      return "a list of " + std::to_string(value_->size());
    case json::value_t::object:
      return "an object";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return "a number";
    default:
      return "an unsupported value";
  }
}

std::string JsonReader::childPath(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void JsonReader::requireObject(const std::string& shape) const {
  if (!value_->is_object()) fail("expected " + shape + ", got " + typeName());
}

void JsonReader::requireOnlyKeys(const std::vector<std::string>& allowed) const {
  requireObject();
  for (auto it = value_->begin(); it != value_->end(); ++it) {
    if (std::find(allowed.begin(), allowed.end(), it.key()) != allowed.end()) continue;
    std::ostringstream os;
    os << where() << (path_.empty() ? ": " : ".") << it.key() << ": unknown key (known:";
    for (const auto& a : allowed) os << " " << a;
    os << ")";
    throw RequestError(os.str());
  }
}

bool JsonReader::has(const std::string& key) const {
  return value_->is_object() && value_->contains(key);
}

JsonReader JsonReader::at(const std::string& key) const {
  requireObject();
  const auto it = value_->find(key);
  if (it == value_->end()) throw RequestError(source_ + ": " + childPath(key) + ": missing key");
  return JsonReader(*it, source_, childPath(key));
}

JsonReader JsonReader::at(std::size_t i) const {
  const std::size_t n = arraySize();
  if (i >= n) fail("index " + std::to_string(i) + " out of range (" + std::to_string(n) + ")");
  return JsonReader((*value_)[i], source_, path_ + "[" + std::to_string(i) + "]");
}

std::size_t JsonReader::arraySize() const {
  if (!value_->is_array()) fail("expected a list, got " + typeName());
  return value_->size();
}

std::size_t JsonReader::requireArray(std::size_t min_size, std::size_t max_size) const {
  const std::size_t n = arraySize();
  if (n < min_size || n > max_size) {
    std::ostringstream os;
    os << "expected ";
    if (min_size == max_size)
      os << min_size;
    else if (max_size == std::numeric_limits<std::size_t>::max())
      os << "at least " << min_size;
    else
      os << min_size << " to " << max_size;
    os << " entries, got " << n;
    fail(os.str());
  }
  return n;
}

double JsonReader::number(NonFinite nf) const {
  double v = 0.0;
  if (value_->is_number()) {
    v = value_->get<double>();
  } else if (nf == NonFinite::kAllow && value_->is_null()) {
    v = std::numeric_limits<double>::quiet_NaN();
  } else if (nf == NonFinite::kAllow && value_->is_string()) {
    const std::string& s = value_->get_ref<const std::string&>();
    if (s == "nan" || s == "NaN")
      v = std::numeric_limits<double>::quiet_NaN();
    else if (s == "inf" || s == "+inf" || s == "Infinity")
      v = std::numeric_limits<double>::infinity();
    else if (s == "-inf" || s == "-Infinity")
      v = -std::numeric_limits<double>::infinity();
    else
      fail("expected a number, got the string '" + s + "'");
    return v;
  } else {
    fail("expected a number, got " + typeName());
  }
  if (nf == NonFinite::kReject && !std::isfinite(v)) fail("expected a finite number");
  return v;
}

long long JsonReader::integer(long long lo, long long hi) const {
  long long v = 0;
  if (value_->is_number_integer()) {
    if (value_->is_number_unsigned() &&
        value_->get<unsigned long long>() >
            static_cast<unsigned long long>(std::numeric_limits<long long>::max()))
      v = std::numeric_limits<long long>::max();
    else
      v = value_->get<long long>();
  } else if (value_->is_number_float()) {
    const double d = value_->get<double>();
    if (!std::isfinite(d) || d != std::floor(d)) fail("expected an integer, got " + value_->dump());
    if (d < -9.2e18 || d > 9.2e18)
      v = d < 0 ? std::numeric_limits<long long>::min() : std::numeric_limits<long long>::max();
    else
      v = static_cast<long long>(d);
  } else {
    fail("expected an integer, got " + typeName());
  }
  if (v < lo || v > hi) {
    std::ostringstream os;
    os << "expected an integer in [" << lo << ", " << hi << "], got " << value_->dump();
    fail(os.str());
  }
  return v;
}

std::string JsonReader::string() const {
  if (!value_->is_string()) fail("expected a string, got " + typeName());
  return value_->get<std::string>();
}

std::string JsonReader::choice(const std::vector<std::string>& choices) const {
  const std::string s = string();
  if (std::find(choices.begin(), choices.end(), s) != choices.end()) return s;
  std::ostringstream os;
  os << "expected one of";
  for (const auto& c : choices) os << " '" << c << "'";
  os << ", got '" << s << "'";
  fail(os.str());
}

bool JsonReader::boolean() const {
  if (!value_->is_boolean()) fail("expected true or false, got " + typeName());
  return value_->get<bool>();
}

Eigen::VectorXd JsonReader::vector(Eigen::Index size, NonFinite nf) const {
  if (!value_->is_array()) {
    fail(size >= 0 ? "expected " + std::to_string(size) + " numbers, got " + typeName()
                   : "expected a list of numbers, got " + typeName());
  }
  const auto n = static_cast<Eigen::Index>(value_->size());
  if (size >= 0 && n != size)
    fail("expected " + std::to_string(size) + " numbers, got " + std::to_string(n));
  Eigen::VectorXd v(n);
  for (Eigen::Index i = 0; i < n; ++i) v[i] = at(static_cast<std::size_t>(i)).number(nf);
  return v;
}

Eigen::MatrixXd JsonReader::matrix(Eigen::Index rows, Eigen::Index cols, NonFinite nf) const {
  if (!value_->is_array()) fail("expected a list of rows, got " + typeName());
  const auto n = static_cast<Eigen::Index>(value_->size());
  if (rows >= 0 && n != rows)
    fail("expected " + std::to_string(rows) + " rows, got " + std::to_string(n));
  if (n == 0) return Eigen::MatrixXd(0, cols > 0 ? cols : 0);
  const JsonReader first = at(std::size_t{0});
  if (!first.value().is_array())
    first.fail("expected a row (list of numbers), got " + first.typeName());
  const Eigen::Index c = cols >= 0 ? cols : static_cast<Eigen::Index>(first.value().size());
  Eigen::MatrixXd M(n, c);
  for (Eigen::Index i = 0; i < n; ++i) {
    const JsonReader row = at(static_cast<std::size_t>(i));
    if (row.value().is_array() && static_cast<Eigen::Index>(row.value().size()) != c) {
      std::ostringstream os;
      os << "row " << i << " has " << row.value().size() << " entries, expected " << c;
      fail(os.str());
    }
    M.row(i) = row.vector(c, nf).transpose();
  }
  return M;
}

bool JsonReader::optionalNumber(const std::string& key, double& out) const {
  if (!has(key)) return false;
  out = at(key).number();
  return true;
}

bool JsonReader::optionalVector(const std::string& key, Eigen::Index size,
                                Eigen::VectorXd& out) const {
  if (!has(key)) return false;
  out = at(key).vector(size);
  return true;
}

bool JsonReader::optionalChoice(const std::string& key, const std::vector<std::string>& choices,
                                std::string& out) const {
  if (!has(key)) return false;
  out = at(key).choice(choices);
  return true;
}

}  // namespace reach_trajopt
