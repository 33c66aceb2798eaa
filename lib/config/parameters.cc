#include "config/parameters.h"

#include "config/errors.h"
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
      values[e.section + "." + e.key] = e.default_value;
  }

  void set(const std::string &section, const std::string &key, const std::string &value,
           const std::string &origin)
  {
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
    if (!found)
      throw InputError(origin + ": unknown key '" + section + "." + key + "'" +
                       suggestion(key, keys));
    if (!found->pattern->match(value))
      throw InputError(origin + ": invalid value '" + value + "' for key '" + section +
                       "." + key + "'; expected " + found->expected() + " (" +
                       found->doc + ")");
    values[section + "." + key] = value;
    origins[section + "." + key] = origin;
  }

  /// Deepest nesting of [ and { accepted in a config (sections hold values: depth 2).
  static constexpr unsigned int max_depth = 64;

  /// The top level must be an object and the nesting at most max_depth deep (the JSON
  /// reader recurses once per level; without the limit deep input overflows the stack).
  static void check_structure(const std::string &file, const std::string &text)
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
    unsigned int depth = 0;
    bool in_string = false;
    for (std::size_t i = start; i < text.size(); ++i)
    {
      const char c = text[i];
      if (in_string)
      {
        if (c == '\\')
          ++i;
        else if (c == '"')
          in_string = false;
      }
      else if (c == '"')
        in_string = true;
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
    check_structure(file, text);
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

  Parameters typed() const
  {
    Parameters p;
    p.scene = get("scene.name");
    p.variant = get("scene.variant");
    p.epsilon = real("scene.epsilon");
    p.end_time = real("scene.end_time");
    p.p = integer("discretization.p");
    p.r = integer("discretization.r");
    p.delta0 = real("discretization.delta0");
    p.supg_length = get("discretization.supg_length");
    p.supg_tau_factor = real("discretization.supg_tau_factor");
    p.initial_refinements = integer("discretization.initial_refinements");
    p.n_slabs = integer("discretization.n_slabs");
    p.solver_type = get("solver.type");
    p.reuse_factorization = boolean("solver.reuse_factorization");
    p.solver_auto_threshold = real("solver.auto_threshold");
    p.solver_auto_memory_mb = real("solver.auto_memory_mb");
    p.krylov = get("solver.krylov");
    p.preconditioner = get("solver.preconditioner");
    p.solver_tolerance = real("solver.tolerance");
    p.restart = integer("solver.restart");
    p.max_iterations = integer("solver.max_iterations");
    p.ilu_fill = real("solver.ilu_fill");
    p.spatial_preconditioner = get("solver.spatial_preconditioner");
    p.amg_smoother = get("solver.amg_smoother");
    p.stagnation_window = integer("solver.stagnation_window");
    p.stagnation_factor = real("solver.stagnation_factor");
    p.fallback = get("solver.fallback");
    p.mode = get("study.mode");
    p.refine = get("study.refine");
    p.levels = integer("study.levels");
    p.goal_kind = get("goal.kind");
    p.goal_locations = get("goal.locations");
    p.goal_over_time = boolean("goal.over_time");
    p.goal_radius = real("goal.radius");
    p.goal_weights = get("goal.weights");
    p.adaptivity_mode = get("adaptivity.mode");
    p.marking = get("adaptivity.marking");
    p.kappa = fraction("adaptivity.kappa");
    p.loops = integer("adaptivity.loops");
    p.theta_h = fraction("adaptivity.theta_h");
    p.theta_tau = fraction("adaptivity.theta_tau");
    p.theta_coarsen = fraction("adaptivity.theta_coarsen");
    p.tolerance = real("adaptivity.tolerance");
    p.max_dofs = real("adaptivity.max_dofs");
    p.max_memory_mb = real("adaptivity.max_memory_mb");
    p.max_wall_time = real("adaptivity.max_wall_time");
    p.adjoint_degree = integer("adaptivity.adjoint_degree");
    p.adjoint_stabilization = get("adaptivity.adjoint_stabilization");
    p.space_indicator = get("adaptivity.space_indicator");
    p.dof_numbering = get("solver.dof_numbering");
    p.measure_time_error = boolean("adaptivity.measure_time_error");
    p.time_indicator = get("adaptivity.time_indicator");
    p.per_goal_estimates = boolean("adaptivity.per_goal_estimates");
    p.vtu_loops = integer("output.vtu_loops");
    p.output_directory = get("output.directory");
    p.vtu_every = integer("output.vtu_every");
    p.progress = boolean("output.progress");
    bounded_positive("scene.epsilon", p.epsilon);
    bounded_positive("scene.end_time", p.end_time);
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
  double real(const std::string &k) const { return std::stod(get(k)); }
  unsigned int integer(const std::string &k) const { return std::stoul(get(k)); }
  bool boolean(const std::string &k) const
  {
    return get(k) == "true" || get(k) == "True" || get(k) == "yes";
  }
  double fraction(const std::string &k) const
  {
    const double v = real(k);
    if (v > 1.)
      throw InputError(origin(k) + ": invalid value '" + get(k) + "' for key '" + k +
                       "'; expected a fraction in [0, 1]");
    return v;
  }
  /// 0 < v <= 1e6 (scene.epsilon, scene.end_time)
  void bounded_positive(const std::string &k, double v) const
  {
    if (!(v > 0.) || !(v <= 1e6))
      throw InputError(origin(k) + ": invalid value '" + get(k) + "' for key '" + k +
                       "'; expected a number with 0 < v <= 1e6");
  }
};

std::string json_value(const Entry &e, const std::string &value)
{
  if (e.kind == Kind::text)
    return "\"" + value + "\"";
  if (e.kind == Kind::boolean)
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
          << pad << "    \"#" << e.key << "\": \"" << e.doc
          << " Allowed: " << e.expected()
          << "\",";
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
    values[e.section + "." + e.key] = e.default_value;
  out << format(values, true, 0) << std::endl;
}

std::string Parameters::to_json(unsigned int indent) const
{
  auto num = [](double v)
  {
    std::ostringstream s;
    s.precision(17);
    s << v;
    return s.str();
  };
  std::map<std::string, std::string> v{
      {"scene.name", scene},
      {"scene.variant", variant},
      {"scene.epsilon", num(epsilon)},
      {"scene.end_time", num(end_time)},
      {"discretization.p", std::to_string(p)},
      {"discretization.r", std::to_string(r)},
      {"discretization.delta0", num(delta0)},
      {"discretization.supg_length", supg_length},
      {"discretization.supg_tau_factor", num(supg_tau_factor)},
      {"discretization.initial_refinements", std::to_string(initial_refinements)},
      {"discretization.n_slabs", std::to_string(n_slabs)},
      {"solver.type", solver_type},
      {"solver.reuse_factorization", reuse_factorization ? "true" : "false"},
      {"solver.auto_threshold", num(solver_auto_threshold)},
      {"solver.auto_memory_mb", num(solver_auto_memory_mb)},
      {"solver.krylov", krylov},
      {"solver.preconditioner", preconditioner},
      {"solver.tolerance", num(solver_tolerance)},
      {"solver.restart", std::to_string(restart)},
      {"solver.max_iterations", std::to_string(max_iterations)},
      {"solver.ilu_fill", num(ilu_fill)},
      {"solver.spatial_preconditioner", spatial_preconditioner},
      {"solver.amg_smoother", amg_smoother},
      {"solver.stagnation_window", std::to_string(stagnation_window)},
      {"solver.stagnation_factor", num(stagnation_factor)},
      {"solver.fallback", fallback},
      {"solver.dof_numbering", dof_numbering},
      {"study.mode", mode},
      {"study.refine", refine},
      {"study.levels", std::to_string(levels)},
      {"goal.kind", goal_kind},
      {"goal.locations", goal_locations},
      {"goal.over_time", goal_over_time ? "true" : "false"},
      {"goal.radius", num(goal_radius)},
      {"goal.weights", goal_weights},
      {"adaptivity.mode", adaptivity_mode},
      {"adaptivity.marking", marking},
      {"adaptivity.kappa", num(kappa)},
      {"adaptivity.loops", std::to_string(loops)},
      {"adaptivity.theta_h", num(theta_h)},
      {"adaptivity.theta_tau", num(theta_tau)},
      {"adaptivity.theta_coarsen", num(theta_coarsen)},
      {"adaptivity.tolerance", num(tolerance)},
      {"adaptivity.max_dofs", num(max_dofs)},
      {"adaptivity.max_memory_mb", num(max_memory_mb)},
      {"adaptivity.max_wall_time", num(max_wall_time)},
      {"adaptivity.adjoint_degree", std::to_string(adjoint_degree)},
      {"adaptivity.adjoint_stabilization", adjoint_stabilization},
      {"adaptivity.space_indicator", space_indicator},
      {"adaptivity.measure_time_error", measure_time_error ? "true" : "false"},
      {"adaptivity.time_indicator", time_indicator},
      {"adaptivity.per_goal_estimates", per_goal_estimates ? "true" : "false"},
      {"output.vtu_loops", std::to_string(vtu_loops)},
      {"output.directory", output_directory},
      {"output.vtu_every", std::to_string(vtu_every)},
      {"output.progress", progress ? "true" : "false"}};
  return format(v, false, indent);
}
} // namespace anisodwr
