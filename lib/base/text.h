#pragma once
// Small text helpers of the input readers: blanks trimmed, lists split at a separator.
#include <sstream>
#include <string>
#include <vector>

namespace anisodwr
{
/// `s` without leading and trailing blanks (space, tab, newline, carriage return).
inline std::string trim_ws(const std::string &s)
{
  const auto a = s.find_first_not_of(" \t\n\r"), b = s.find_last_not_of(" \t\n\r");
  return a == std::string::npos ? "" : s.substr(a, b - a + 1);
}

/// The items of `s` between the separators `sep`, each trimmed; a trailing separator
/// gives a last empty item ("a;" is {"a", ""}), an empty `s` no item.
inline std::vector<std::string> split_ws(const std::string &s, char sep)
{
  std::vector<std::string> out;
  std::string item;
  std::istringstream in(s);
  while (std::getline(in, item, sep))
    out.push_back(trim_ws(item));
  if (!s.empty() && s.back() == sep)
    out.push_back("");
  return out;
}

/// The numbers of `ids` separated by ", " (e.g. a set of boundary ids), `none` if empty.
template <class Ids> std::string ids_text(const Ids &ids, const std::string &none = "")
{
  std::string s;
  for (const auto id : ids)
    s += (s.empty() ? "" : ", ") + std::to_string(id);
  return s.empty() ? none : s;
}
} // namespace anisodwr
