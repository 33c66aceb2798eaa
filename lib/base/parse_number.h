#pragma once
// Conversion of the text of a floating-point value (config keys, goal locations,
// weights and references) with its failures told apart: a value that is not a number,
// one that overflows, and one that underflows to a subnormal number or to 0.
#include <cerrno>
#include <cfloat>
#include <cmath>
#include <cstdlib>
#include <string>

namespace anisodwr
{
enum class NumberStatus
{
  ok,       ///< a finite number (0 or of magnitude >= DBL_MIN)
  invalid,  ///< not a number, or text after it, or nan/inf
  overflow, ///< magnitude beyond the largest double
  underflow ///< nonzero but below DBL_MIN: subnormal or rounded to 0
};

/// Reads all of `text` (blanks around it allowed) as a double into `v` (0 unless ok).
inline NumberStatus parse_double(const std::string &text, double &v)
{
  v = 0;
  const char *begin = text.c_str();
  char *end = nullptr;
  errno = 0;
  const double x = std::strtod(begin, &end);
  const int err = errno;
  const char *last = end;
  while (end != begin && (*last == ' ' || *last == '\t'))
    ++last;
  if (end == begin || last != begin + text.size())
    return NumberStatus::invalid;
  if (std::isnan(x) || (std::isinf(x) && err != ERANGE))
    return NumberStatus::invalid;
  if (std::isinf(x))
    return NumberStatus::overflow;
  // strtod sets ERANGE for results below DBL_MIN (glibc: subnormal or 0 from a
  // nonzero mantissa); a subnormal result is refused as well
  if ((err == ERANGE && std::abs(x) < DBL_MIN) || (x != 0 && std::abs(x) < DBL_MIN))
    return NumberStatus::underflow;
  v = x;
  return NumberStatus::ok;
}

/// The reason for a number that underflows, for messages: "underflows double
/// precision; expected 0 or a number of magnitude >= 2.2e-308".
inline std::string underflow_text()
{
  return "underflows double precision; expected 0 or a normal number of magnitude "
         ">= 2.2e-308";
}
} // namespace anisodwr
