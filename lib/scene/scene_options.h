#pragma once
// The scene section of a config (config/parameters.h: SceneSection is this struct).
#include "scene/custom_options.h"

#include <map>
#include <string>

namespace anisodwr
{
/// The scene section of a config and, for messages, where scene.variant came from (a
/// config file's path, "--set" or "default").
struct SceneOptions
{
  /// a name in the scene registry (lib/scene/scene_registry.h)
  std::string name = "moving_hump";
  std::string variant = "";
  double epsilon = 1e-6;
  double end_time = 0.5;
  std::string variant_source = "default";
  /// scene.name = custom: its keys, and where each came from (by key name, e.g.
  /// "scene.rhs": a config file's path, "--set" or "default"; a relative
  /// scene.mesh_file is found next to the config file it came from)
  CustomSceneOptions custom;
  std::map<std::string, std::string> sources;
  std::string source(const std::string &key) const
  {
    const auto it = sources.find(key);
    return it == sources.end() ? "default" : it->second;
  }
};
} // namespace anisodwr
