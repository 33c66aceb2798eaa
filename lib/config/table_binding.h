#pragma once
// Internal to lib/config/: the helpers that bind a key of the parameter table to its
// member of Parameters, its patterns, and the sections' entry lists that live in
// their own files (parameter_table.cc gathers them).
#include "config/parameter_table.h"

#include "base/parse_number.h"

#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <type_traits>
#include <vector>

namespace anisodwr::config::table
{
namespace P = dealii::Patterns;

/// The member of Parameters that `ref` (a generic callable: Parameters & -> T &, also
/// for const) refers to, read from and printed to text (numbers as in to_json: 17
/// significant digits; enums by their names).
template <class T, class Ref> Binding bind(Ref ref)
{
  Binding b;
  b.set = [ref](Parameters &p, const std::string &v)
  {
    T &x = ref(p);
    if constexpr (std::is_same_v<T, double>)
    {
      if (parse_double(v, x) != NumberStatus::ok)
        throw std::logic_error("'" + v +
                               "' is not a finite double (checked by the reader)");
    }
    else if constexpr (std::is_same_v<T, unsigned int>)
      x = std::stoul(v);
    else if constexpr (std::is_same_v<T, bool>)
      x = v == "true" || v == "True" || v == "yes";
    else if constexpr (std::is_same_v<T, std::string>)
      x = v;
    else if (const auto e = parse_choice<T>(v))
      x = *e;
    else
      throw std::logic_error("no name '" + v + "' in the table of an enum");
  };
  b.get = [ref](const Parameters &p) -> std::string
  {
    const T &x = ref(p);
    if constexpr (std::is_same_v<T, double>)
    {
      std::ostringstream s;
      s.precision(17);
      s << x;
      return s.str();
    }
    else if constexpr (std::is_same_v<T, unsigned int>)
      return std::to_string(x);
    else if constexpr (std::is_same_v<T, bool>)
      return x ? "true" : "false";
    else if constexpr (std::is_same_v<T, std::string>)
      return x;
    else
      return name(x);
  };
  if constexpr (std::is_same_v<T, double>)
    b.kind = Kind::real;
  else if constexpr (std::is_same_v<T, unsigned int>)
    b.kind = Kind::integer;
  else if constexpr (std::is_same_v<T, bool>)
    b.kind = Kind::boolean;
  else
    b.kind = Kind::text;
  if constexpr (std::is_enum_v<T>)
    b.choices = std::make_shared<P::Selection>(choice_list<T>("|"));
  return b;
}

/// The member `member` of the section `section` (a member of the section's struct or
/// of one of its bases).
template <class Section, class Base, class T>
Binding at(Section Parameters::*section, T Base::*member)
{
  return bind<T>([section, member](auto &p) -> auto & { return p.*section.*member; });
}

/// The member `member` of the sub-struct `sub` of the section `section`.
template <class Section, class Base, class Sub, class T>
Binding at(Section Parameters::*section, Sub Base::*sub, T Sub::*member)
{
  return bind<T>([section, sub, member](auto &p) -> auto &
                 { return (p.*section.*sub).*member; });
}

inline std::shared_ptr<PatternBase> integer(int lo, int hi)
{
  return std::make_shared<P::Integer>(lo, hi);
}
inline std::shared_ptr<PatternBase> real(double lo)
{
  return std::make_shared<P::Double>(lo);
}
inline std::shared_ptr<PatternBase> real(double lo, double hi)
{
  return std::make_shared<P::Double>(lo, hi);
}
inline const std::shared_ptr<PatternBase> boolean = std::make_shared<P::Bool>();
inline const std::shared_ptr<PatternBase> text = std::make_shared<P::Anything>();
/// the pattern of an enum member: the Selection of its names (Binding::choices)
inline const std::shared_ptr<PatternBase> by_name = nullptr;

/// The sections' entry lists (one function per section; parameter_table.cc).
std::vector<Entry> solver_entries();
std::vector<Entry> adaptivity_entries();
} // namespace anisodwr::config::table
