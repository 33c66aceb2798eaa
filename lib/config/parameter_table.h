#pragma once
// The entry table of the run parameters (internal to lib/config/): every key with its
// section, default, pattern and documentation, in the order of the printed defaults.
#include <deal.II/base/patterns.h>

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

struct Entry
{
  std::string section, key, default_value;
  Kind kind;
  std::shared_ptr<PatternBase> pattern;
  std::string doc;
  /// What the value must be, in words (overrides the pattern's description).
  std::string range = "";

  std::string expected() const
  {
    return range.empty() ? pattern->description(PatternBase::OutputStyle::Text) : range;
  }
};

/// The table (built once).
const std::vector<Entry> &entries();
} // namespace anisodwr::config
