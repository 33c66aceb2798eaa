#pragma once
// The scene registry: every scene's name (the value of scene.name), factory and one-line
// documentation, in one table (lib/scene/scene_registry.cc). It gives the choice
// scene.name (its allowed values and documentation), create_scene and the tests that
// loop over all scenes.
#include "scene/scene_options.h"

#include <memory>
#include <string>
#include <vector>

namespace anisodwr
{
template <int dim> class Scene;

struct SceneEntry
{
  const char *name;
  std::unique_ptr<Scene<2>> (*make)(const SceneOptions &options);
  /// One line for the documentation of scene.name.
  const char *doc;
};

/// All scenes, in the order in which they are documented.
const std::vector<SceneEntry> &scene_registry();

/// The entry named `name`; nullptr if there is none.
const SceneEntry *find_scene(const std::string &name);

/// The registered names joined by `separator` ("a|b|c" for a deal.II Selection).
std::string scene_names(const std::string &separator);

/// The documentation of scene.name, from the entries' one-liners.
std::string scene_key_doc();
} // namespace anisodwr
