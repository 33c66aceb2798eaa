#pragma once
// The entry table of the run parameters (internal to lib/config/): every key with its
// section, default, pattern, documentation and the member of Parameters it sets, in
// the order of the printed defaults.
#include "config/parameters.h"

#include <deal.II/base/patterns.h>

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace anisodwr::config
{
using dealii::Patterns::PatternBase;

enum class Kind
{
  integer,
  real,
  boolean,
  text
};

/// A check on the typed value beyond the pattern, run by Parameters::read.
enum class Check
{
  none,
  fraction,        ///< v <= 1 (the pattern checks v >= 0)
  bounded_positive ///< 0 < v <= 1e6, checked after all keys were read
};

/// How an entry reaches its member: the member's kind, a setter from the (pattern
/// checked) text, the value as text for to_json, and for an enum the Selection of
/// its names.
struct Binding
{
  Kind kind;
  std::function<void(Parameters &, const std::string &)> set;
  std::function<std::string(const Parameters &)> get;
  std::shared_ptr<PatternBase> choices;
};

struct Entry
{
  std::string section, key, default_value;
  Binding member;
  /// null for an enum member: the Selection of its names
  std::shared_ptr<PatternBase> pattern;
  std::string doc;
  /// What the value must be, in words (overrides the pattern's description).
  std::string range = "";
  Check check = Check::none;

  Kind kind() const { return member.kind; }
  std::string name() const { return section + "." + key; }
  std::string expected() const
  {
    return range.empty() ? pattern->description(PatternBase::OutputStyle::Text) : range;
  }
};

/// The table (built once).
const std::vector<Entry> &entries();
} // namespace anisodwr::config
