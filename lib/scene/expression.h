#pragma once
// A muparser expression in named variables (x, y, t, ...) with named constants, for the
// custom scene (scene.name = custom). Evaluation is thread-safe: every thread parses its
// own copy on first use (muparser's evaluation stack is not shared between threads).
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace anisodwr
{
/// Named constants, in the order they were defined.
using Constants = std::vector<std::pair<std::string, double>>;

class Expression
{
public:
  Expression() = default;
  /// Parses `text` in the variables `variables` (e.g. {"x", "y", "t"}) and the
  /// constants; throws InputError "<where>: invalid expression '<text>' for key '<key>':
  /// <muparser's message>" if it does not parse or uses an unknown name.
  Expression(const std::string &text, const std::vector<std::string> &variables,
             const Constants &constants, const std::string &key,
             const std::string &where);

  /// The value at the variables v (as many as `variables`, in that order); an
  /// expression in no variable is evaluated once, when it is parsed.
  double operator()(const double *v) const;
  double operator()(double x, double y, double t) const
  {
    const double v[3] = {x, y, t};
    return (*this)(v);
  }

  /// True if the expression uses the variable `name`.
  bool uses(const std::string &name) const;
  const std::string &text() const { return source; }
  const std::string &key() const { return key_name; }

private:
  std::string source, key_name;
  std::vector<std::string> variables;
  Constants constants;
  std::vector<std::string> used;
  std::uint64_t id = 0; ///< identifies this expression's parsers in each thread
  bool constant = false; ///< uses no variable: `value` is its value
  double value = 0;
};

/// Reads "name = value, name = value, ..." (scene.constants); each value is an
/// expression in the constants before it and `predefined` (e.g. eps, pi). Throws
/// InputError naming the key on a bad name or value. Returns `predefined` followed by
/// the new constants.
Constants parse_constants(const std::string &text, const Constants &predefined,
                          const std::string &key, const std::string &where);
} // namespace anisodwr
