#pragma once
// scene.name: the benchmark scenes (doc/method.md §10), with their name table.
#include "base/choice.h"

namespace anisodwr
{
enum class SceneName
{
  moving_hump,
  manufactured,
  heat,
  boundary_layer,
  hemker,
  custom ///< defined in the config (lib/scene/custom_scene.h)
};

inline const std::vector<Named<SceneName>> &names(SceneName)
{
  static const std::vector<Named<SceneName>> table{
      {SceneName::moving_hump, "moving_hump"},
      {SceneName::manufactured, "manufactured"},
      {SceneName::heat, "heat"},
      {SceneName::boundary_layer, "boundary_layer"},
      {SceneName::hemker, "hemker"},
      {SceneName::custom, "custom"}};
  return table;
}
} // namespace anisodwr
