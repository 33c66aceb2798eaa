#include "scene/expression.h"

#include "base/errors.h"
#include "base/text.h"

#include <muParser.h>

#include <atomic>
#include <cmath>
#include <memory>
#include <unordered_map>

namespace anisodwr
{
namespace
{
std::atomic<std::uint64_t> next_id{1};

double atan2_(double y, double x)
{
  return std::atan2(y, x);
}
double pow_(double a, double b)
{
  return std::pow(a, b);
}
double floor_(double a)
{
  return std::floor(a);
}
double ceil_(double a)
{
  return std::ceil(a);
}
double erf_(double a)
{
  return std::erf(a);
}
double erfc_(double a)
{
  return std::erfc(a);
}

/// One thread's parser of one expression, with the storage of its variables.
struct Slot
{
  mu::Parser parser;
  std::vector<double> values;
};

std::unique_ptr<Slot> make_slot(const std::string &text,
                                const std::vector<std::string> &variables,
                                const Constants &constants)
{
  auto slot = std::make_unique<Slot>();
  slot->values.assign(variables.size(), 0.);
  mu::Parser &p = slot->parser;
  p.DefineFun("atan2", atan2_);
  p.DefineFun("pow", pow_);
  p.DefineFun("floor", floor_);
  p.DefineFun("ceil", ceil_);
  p.DefineFun("erf", erf_);
  p.DefineFun("erfc", erfc_);
  for (const auto &[name, value] : constants)
    p.DefineConst(name, value);
  for (std::size_t i = 0; i < variables.size(); ++i)
    p.DefineVar(variables[i], &slot->values[i]);
  p.SetExpr(text);
  return slot;
}

bool is_name(const std::string &s)
{
  if (s.empty() || !(std::isalpha(static_cast<unsigned char>(s[0])) || s[0] == '_'))
    return false;
  for (const char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_'))
      return false;
  return true;
}
} // namespace

Expression::Expression(const std::string &text, const std::vector<std::string> &variables,
                       const Constants &constants, const std::string &key,
                       const std::string &where)
    : source(text), key_name(key), variables(variables), constants(constants),
      id(next_id++)
{
  const std::string bad =
      where + ": invalid expression '" + text + "' for key '" + key + "'";
  if (trim_ws(text).empty())
    throw InputError(bad + ": the expression is empty");
  // muparser's assignment (x = 3 sets x and gives 3), not a comparison ==, <=, >=, !=
  for (std::size_t i = 0; i < text.size(); ++i)
    if (text[i] == '=' && (i + 1 == text.size() || text[i + 1] != '=') &&
        (i == 0 || std::string("=<>!").find(text[i - 1]) == std::string::npos))
      throw InputError(bad + ": '=' at position " + std::to_string(i) +
                       " assigns; expected an expression of the variables (== compares)");
  try
  {
    auto slot = make_slot(text, variables, constants);
    slot->parser.Eval(); // parses; the value at 0 does not matter
    if (slot->parser.GetNumResults() > 1)
      throw InputError(bad + ": it has " + std::to_string(slot->parser.GetNumResults()) +
                       " comma-separated values; expected one expression (a function's "
                       "arguments are the only place for ',')");
    for (const auto &v : slot->parser.GetUsedVar())
      used.push_back(v.first);
    if (used.empty()) // a constant: evaluated once
    {
      constant = true;
      value = slot->parser.Eval();
    }
  }
  catch (const mu::Parser::exception_type &e)
  {
    std::string vars;
    for (const auto &v : variables)
      vars += (vars.empty() ? "" : ", ") + v;
    std::string msg = e.GetMsg();
    if (msg.find("position") == std::string::npos && e.GetPos() >= 0)
      msg += " at position " + std::to_string(e.GetPos());
    throw InputError(bad + ": " + msg + " (variables: " + (vars.empty() ? "none" : vars) +
                     "; constants: scene.constants, eps, pi)");
  }
}

double Expression::operator()(const double *v) const
{
  if (constant)
    return value;
  thread_local std::unordered_map<std::uint64_t, std::unique_ptr<Slot>> slots;
  auto &slot = slots[id];
  if (!slot)
    slot = make_slot(source, variables, constants);
  for (std::size_t i = 0; i < slot->values.size(); ++i)
    slot->values[i] = v[i];
  return slot->parser.Eval();
}

bool Expression::uses(const std::string &name) const
{
  for (const auto &u : used)
    if (u == name)
      return true;
  return false;
}

Constants parse_constants(const std::string &text, const Constants &predefined,
                          const std::string &key, const std::string &where)
{
  Constants all = predefined, defined;
  std::string item;
  std::size_t start = 0;
  while (start <= text.size())
  {
    const auto comma = text.find(',', start);
    item = trim_ws(text.substr(start, comma == std::string::npos ? std::string::npos
                                                              : comma - start));
    start = comma == std::string::npos ? text.size() + 1 : comma + 1;
    if (item.empty())
    {
      if (comma == std::string::npos && defined.empty() && trim_ws(text).empty())
        break;
      throw InputError(where + ": invalid value '" + text + "' for key '" + key +
                       "'; expected comma-separated definitions name = value, found an "
                       "empty one");
    }
    const auto eq = item.find('=');
    const std::string name = trim_ws(item.substr(0, eq));
    if (eq == std::string::npos || !is_name(name))
      throw InputError(where + ": invalid definition '" + item + "' in key '" + key +
                       "'; expected name = value with a name of letters, digits and _ "
                       "(not starting with a digit)");
    // muparser refuses longer identifiers, and would blame the first expression using
    // the constants instead of this key
    constexpr std::size_t longest = 64;
    if (name.size() > longest)
      throw InputError(where + ": invalid definition '" + name.substr(0, 20) + "... = ...' (a name of " +
                       std::to_string(name.size()) + " characters) in key '" + key +
                       "'; expected names of at most " + std::to_string(longest) +
                       " characters");
    for (const std::string reserved : {"x", "y", "t", "nx", "ny"})
      if (name == reserved)
        throw InputError(where + ": invalid definition '" + item + "' in key '" + key +
                         "'; '" + name + "' is a variable of the expressions");
    for (const auto &c : all)
      if (c.first == name)
        throw InputError(where + ": invalid definition '" + item + "' in key '" + key +
                         "'; '" + name + "' is already defined");
    const Expression e(item.substr(eq + 1), {}, all, key, where);
    const double value = e(nullptr);
    if (!std::isfinite(value))
      throw InputError(where + ": invalid definition '" + item + "' in key '" + key +
                       "'; its value is not finite");
    all.emplace_back(name, value);
    defined.emplace_back(name, value);
  }
  return all;
}
} // namespace anisodwr
