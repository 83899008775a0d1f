#pragma once
/// \file format_number.h
/// Numbers in the stack's messages (errors, reasons, reports): a double with a few significant
/// digits, as an ostream prints it.

#include <sstream>
#include <string>

namespace reach_trajopt {

/// `value` with `significant_digits` significant digits (ostream's default notation).
inline std::string formatNumber(double value, int significant_digits = 3) {
  std::ostringstream os;
  os.precision(significant_digits);
  os << value;
  return os.str();
}

}  // namespace reach_trajopt
