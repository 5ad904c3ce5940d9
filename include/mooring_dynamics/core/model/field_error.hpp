// The text of a validation error of the model layer: "<key> = <value>: <constraint>", the value
// to 10 significant digits (the Options::validate messages name the field, its value and the
// constraint).
#pragma once

#include <sstream>
#include <string>

namespace mooring_dynamics {
namespace core {

/// v to 10 significant digits.
inline std::string fieldNumber(double v) {
  std::ostringstream os;
  os.precision(10);
  os << v;
  return os.str();
}

/// "<key> = <v>: <constraint>".
inline std::string fieldError(const std::string& key, double v, const std::string& constraint) {
  return key + " = " + fieldNumber(v) + ": " + constraint;
}

/// "" when `ok`, else fieldError(key, v, constraint): the validations' one-line checks.
inline std::string fieldCheck(bool ok, const std::string& key, double v, const std::string& constraint) {
  return ok ? std::string() : fieldError(key, v, constraint);
}

}  // namespace core
}  // namespace mooring_dynamics
