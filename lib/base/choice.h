#pragma once
// Choice-valued options: an enum class with one name table. Each enum E declares, in
// its own namespace,
//   const std::vector<Named<E>> &names(E);
// (found by argument-dependent lookup) listing every value with its name in the order
// in which it is documented; parsing, printing and the list of accepted values all
// come from that table.
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace anisodwr
{
template <class E> struct Named
{
  E value;
  const char *name;
};

/// The name of `value` in its table.
template <class E> std::string name(E value)
{
  for (const auto &n : names(E{}))
    if (n.value == value)
      return n.name;
  return "?";
}

/// The value named `text`, if any.
template <class E> std::optional<E> parse_choice(const std::string &text)
{
  for (const auto &n : names(E{}))
    if (text == n.name)
      return n.value;
  return std::nullopt;
}

/// All names of E joined by `separator` ("a|b|c" for a deal.II Selection pattern).
template <class E> std::string choice_list(const std::string &separator)
{
  std::string list;
  for (const auto &n : names(E{}))
    list += (list.empty() ? "" : separator) + n.name;
  return list;
}

/// The value named `text`; std::invalid_argument naming the accepted values otherwise
/// (for code and tests that name choices; configs are checked by their patterns).
template <class E> E choice_named(const std::string &text)
{
  if (const auto e = parse_choice<E>(text))
    return *e;
  throw std::invalid_argument("'" + text + "' is none of " + choice_list<E>(", "));
}
} // namespace anisodwr
