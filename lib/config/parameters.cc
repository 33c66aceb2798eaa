#include "config/parameters.h"

#include "base/errors.h"
#include "base/json_escape.h"
#include "base/parse_number.h"
#include "config/parameter_table.h"

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <map>
#include <memory>
#include <set>
#include <sstream>

namespace anisodwr
{
namespace
{
using namespace config;

std::size_t edit_distance(const std::string &a, const std::string &b)
{
  std::vector<std::size_t> prev(b.size() + 1), cur(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j)
    prev[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i)
  {
    cur[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j)
      cur[j] =
          std::min({prev[j] + 1, cur[j - 1] + 1, prev[j - 1] + (a[i - 1] != b[j - 1])});
    std::swap(prev, cur);
  }
  return prev[b.size()];
}

std::string suggestion(const std::string &word, const std::vector<std::string> &known)
{
  std::string best;
  std::size_t best_d = 3;
  for (const auto &k : known)
    if (const auto d = edit_distance(word, k); d < best_d)
    {
      best_d = d;
      best = k;
    }
  std::string list;
  for (const auto &k : known)
    list += (list.empty() ? "" : ", ") + k;
  return (best.empty() ? "" : " (did you mean '" + best + "'?)") +
         "; expected one of: " + list;
}

/// Holds the values while reading; checks each value against its pattern.
class Reader
{
public:
  Reader()
  {
    for (const auto &e : entries())
      values[e.name()] = e.default_value;
  }

  /// The key section.key of the table (InputError naming `origin` if there is none;
  /// with section_only only the section is checked and nullptr returned).
  static const Entry *find(const std::string &section, const std::string &key,
                           const std::string &origin, bool section_only = false)
  {
    if (section.find('\0') != std::string::npos || key.find('\0') != std::string::npos)
      throw InputError(origin +
                       ": a section or key name contains a NUL character "
                       "(\\u0000); expected the names that anisodwr defaults prints");
    std::vector<std::string> sections, keys;
    const Entry *found = nullptr;
    for (const auto &e : entries())
    {
      if (std::find(sections.begin(), sections.end(), e.section) == sections.end())
        sections.push_back(e.section);
      if (e.section == section)
      {
        keys.push_back(e.key);
        if (e.key == key)
          found = &e;
      }
    }
    if (keys.empty())
      throw InputError(origin + ": unknown section '" + section + "'" +
                       suggestion(section, sections));
    if (!found && !section_only)
      throw InputError(origin + ": unknown key '" + section + "." + key + "'" +
                       suggestion(key, keys));
    return found;
  }

  void set(const std::string &section, const std::string &key, const std::string &value,
           const std::string &origin)
  {
    const Entry *found = find(section, key, origin);
    const std::string name = section + "." + key;
    if (value.find('\0') != std::string::npos)
      throw InputError(origin + ": invalid value for key '" + name +
                       "': it contains a NUL character (\\u0000); expected " +
                       (found->kind() == Kind::text
                            ? std::string("text without NUL characters")
                            : found->expected()));
    if (!found->pattern->match(value))
      throw InputError(origin + ": invalid value '" + value + "' for key '" + name +
                       "'; expected " + found->expected() + " (" + found->doc + ")");
    if (double v = 0; found->kind() == Kind::real)
      if (const auto status = parse_double(value, v); status != NumberStatus::ok)
        throw InputError(
            origin + ": invalid value '" + value + "' for key '" + name + "': " +
            (status == NumberStatus::underflow ? "it " + underflow_text()
                                               : "expected " + found->expected()));
    values[section + "." + key] = value;
    origins[section + "." + key] = origin;
  }

  /// Deepest nesting of [ and { accepted in a config (sections hold values: depth 2).
  static constexpr unsigned int max_depth = 64;

  /// The top level must be an object and the nesting at most max_depth deep (the JSON
  /// reader recurses once per level; without the limit deep input overflows the stack).
  /// Returns the top-level keys (as written, escapes not decoded) whose value is an
  /// object: the JSON reader does not tell {} from "" or [].
  static std::set<std::string> check_structure(const std::string &file,
                                               const std::string &text)
  {
    std::size_t start = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;
    start = text.find_first_not_of(" \t\r\n", start);
    if (start == std::string::npos || text[start] != '{')
      throw InputError(file + ": the top level of a config must be a JSON object "
                              "{\"section\": {\"key\": value}}, found " +
                       (start == std::string::npos
                            ? std::string("an empty file")
                            : "'" + text.substr(start, std::min<std::size_t>(
                                                           20, text.find_first_of(
                                                                   "\r\n", start) -
                                                                   start)) +
                                  "'"));
    std::set<std::string> objects;
    unsigned int depth = 0;
    bool in_string = false;
    std::size_t string_start = 0;
    for (std::size_t i = start; i < text.size(); ++i)
    {
      const char c = text[i];
      if (in_string)
      {
        if (c == '\\')
          ++i;
        else if (c == '"')
        {
          in_string = false;
          const auto colon = text.find_first_not_of(" \t\r\n", i + 1);
          if (depth == 1 && colon != std::string::npos && text[colon] == ':')
          {
            const auto value = text.find_first_not_of(" \t\r\n", colon + 1);
            if (value != std::string::npos && text[value] == '{')
              objects.insert(text.substr(string_start, i - string_start));
          }
        }
      }
      else if (c == '"')
      {
        in_string = true;
        string_start = i + 1;
      }
      else if (c == '[' || c == '{')
      {
        if (++depth > max_depth)
          throw InputError(file + ": JSON nested deeper than " +
                           std::to_string(max_depth) +
                           " levels (a config is {\"section\": {\"key\": value}})");
      }
      else if ((c == ']' || c == '}') && depth > 0)
        --depth;
    }
    return objects;
  }

  void read_file(const std::string &file)
  {
    std::error_code ec;
    if (std::filesystem::is_directory(file, ec))
      throw InputError(file + ": is a directory, not a config file");
    std::ifstream in(file, std::ios::binary);
    if (!in)
      throw InputError(file + ": cannot open the config file for reading: " +
                       std::strerror(errno));
    std::string text;
    try
    {
      in.exceptions(std::ios::badbit);
      text.assign(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
    }
    catch (const std::exception &)
    {
      throw InputError(file + ": cannot read the config file: " + std::strerror(errno));
    }
    const std::set<std::string> objects = check_structure(file, text);
    boost::property_tree::ptree tree;
    try
    {
      std::istringstream stream(text);
      boost::property_tree::read_json(stream, tree);
    }
    catch (const boost::property_tree::json_parser_error &e)
    {
      throw InputError(file + ": invalid JSON at line " + std::to_string(e.line()) +
                       ": " + e.message());
    }
    for (const auto &[section, sub] : tree)
    {
      if (!section.empty() && section[0] == '#')
        continue;
      if (sub.empty() && objects.count(section))
      {
        find(section, "", file, true); // an empty section: only its name is checked
        continue;
      }
      if (sub.empty())
        throw InputError(file + ": top-level key '" + section +
                         "' must be a section object like {\"key\": value}");
      for (const auto &[key, leaf] : sub)
      {
        if (!key.empty() && key[0] == '#')
          continue;
        if (!leaf.empty())
          throw InputError(
              file + ": key '" + section + "." + key +
              "' must hold a number, boolean or string, not an object or list");
        set(section, key, leaf.data(), file);
      }
    }
  }

  void apply_override(const std::string &assignment)
  {
    const auto eq = assignment.find('='), dot = assignment.find('.');
    if (eq == std::string::npos || dot == std::string::npos || dot > eq)
      throw InputError("--set '" + assignment + "': expected the form section.key=value");
    set(assignment.substr(0, dot), assignment.substr(dot + 1, eq - dot - 1),
        assignment.substr(eq + 1), "--set");
  }

  /// The values as Parameters, in the order of the table; then the checks of
  /// Check::bounded_positive (after all keys, so a bad fraction is reported first).
  Parameters typed() const
  {
    Parameters p;
    for (const auto &e : entries())
    {
      e.member.set(p, get(e.name()));
      if (e.check == Check::fraction)
        fraction(e.name());
    }
    for (const auto &e : entries())
      if (e.check == Check::bounded_positive)
        bounded_positive(e.name());
    if (get("output.directory").empty())
      throw InputError(origin("output.directory") +
                       ": invalid value '' for key 'output.directory'; expected the path "
                       "of a directory (not empty)");
    check_solver_combination(p);
    for (const auto &[key, value] : values)
      p.sources[key] = origin(key);
    return p;
  }

private:
  std::map<std::string, std::string> values, origins;

  std::string origin(const std::string &k) const
  {
    const auto it = origins.find(k);
    return it == origins.end() ? "default" : it->second;
  }

  std::string get(const std::string &k) const { return values.at(k); }

  /// Where the keys' values came from, for a message on their combination: the sources
  /// other than the defaults, each once ("--set", "a.json and --set").
  std::string origins_of(const std::vector<std::string> &keys) const
  {
    std::vector<std::string> seen;
    std::string all;
    for (const auto &k : keys)
      if (const std::string o = origin(k);
          o != "default" && std::find(seen.begin(), seen.end(), o) == seen.end())
      {
        seen.push_back(o);
        all += (all.empty() ? "" : " and ") + o;
      }
    return all.empty() ? "default" : all;
  }

  /// Combinations of solver keys that the slab solvers refuse, refused here before
  /// anything is written: an inner GMRES (solver.inner_iterations > 0) changes the
  /// preconditioner between applications, which BiCGStab cannot take. Checked for
  /// every solver.type that can solve by Krylov (iterative, auto).
  void check_solver_combination(const Parameters &p) const
  {
    const IterativeOptions &it = p.solver.iterative;
    if (it.inner_iterations == 0 || it.krylov != Krylov::bicgstab ||
        p.solver.type == SolverType::direct || p.solver.type == SolverType::modes)
      return;
    throw InputError(
        origins_of({"solver.krylov", "solver.inner_iterations", "solver.type"}) +
        ": invalid combination solver.type = " + get("solver.type") +
        ", solver.krylov = bicgstab, solver.inner_iterations = " +
        get("solver.inner_iterations") +
        ": inner GMRES iterations change the preconditioner between applications; "
        "expected solver.krylov = gmres or fgmres (run as flexible GMRES), or "
        "solver.inner_iterations = 0");
  }
  double real(const std::string &k) const
  {
    double v = 0;
    parse_double(get(k), v); // checked in set()
    return v;
  }
  /// v <= 1 (Check::fraction)
  void fraction(const std::string &k) const
  {
    if (real(k) > 1.)
      throw InputError(origin(k) + ": invalid value '" + get(k) + "' for key '" + k +
                       "'; expected a fraction in [0, 1]");
  }
  /// 0 < v <= 1e6 (Check::bounded_positive)
  void bounded_positive(const std::string &k) const
  {
    const double v = real(k);
    if (!(v > 0.) || !(v <= 1e6))
      throw InputError(origin(k) + ": invalid value '" + get(k) + "' for key '" + k +
                       "'; expected a number with 0 < v <= 1e6");
  }
};

std::string json_value(const Entry &e, const std::string &value)
{
  if (e.kind() == Kind::text)
    return "\"" + json_escape(value) + "\"";
  if (e.kind() == Kind::boolean)
    return (value == "true" || value == "True" || value == "yes") ? "true" : "false";
  return value;
}

std::string format(const std::map<std::string, std::string> &values, bool with_docs,
                   unsigned int indent)
{
  const std::string pad(indent, ' ');
  std::ostringstream out;
  out << "{";
  std::string section;
  for (const auto &e : entries())
  {
    if (e.section != section)
    {
      out << (section.empty() ? "\n" : "\n" + pad + "  },\n") << pad << "  \""
          << e.section << "\": {";
      section = e.section;
    }
    else
      out << ",";
    if (with_docs)
      out << "\n"
          << pad << "    \"#" << e.key << "\": \""
          << json_escape(e.doc + " Allowed: " + e.expected()) << "\",";
    out << "\n"
        << pad << "    \"" << e.key
        << "\": " << json_value(e, values.at(e.section + "." + e.key));
  }
  out << "\n" << pad << "  }\n" << pad << "}";
  return out.str();
}
} // namespace

std::string Parameters::source(const std::string &key) const
{
  const auto it = sources.find(key);
  return it == sources.end() ? "default" : it->second;
}

Parameters Parameters::read(const std::string &file,
                            const std::vector<std::string> &overrides)
{
  Reader reader;
  reader.read_file(file);
  for (const auto &o : overrides)
    reader.apply_override(o);
  return reader.typed();
}

Parameters Parameters::from_overrides(const std::vector<std::string> &overrides)
{
  Reader reader;
  for (const auto &o : overrides)
    reader.apply_override(o);
  return reader.typed();
}

void Parameters::print_defaults(std::ostream &out)
{
  std::map<std::string, std::string> values;
  for (const auto &e : entries())
    values[e.name()] = e.default_value;
  out << format(values, true, 0) << std::endl;
}

std::string Parameters::to_json(unsigned int indent) const
{
  std::map<std::string, std::string> values;
  for (const auto &e : entries())
    values[e.name()] = e.member.get(*this);
  return format(values, false, indent);
}
} // namespace anisodwr
