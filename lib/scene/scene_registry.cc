#include "scene/scene_registry.h"

#include "base/errors.h"
#include "scene/custom_scene.h"
#include "scene/scenes.h"

namespace anisodwr
{
namespace
{
/// The factory of a scene of lib/scene/scenes.h: built from scene.epsilon and
/// scene.variant (each checks its variant).
template <class S> std::unique_ptr<Scene<2>> make_built_in(const SceneOptions &o)
{
  return std::make_unique<S>(o.epsilon, o.variant);
}

std::unique_ptr<Scene<2>> make_custom(const SceneOptions &o)
{
  if (!o.variant.empty())
    throw InputError(o.variant_source + ": invalid value '" + o.variant +
                     "' for key 'scene.variant' of scene 'custom'; expected \"\"");
  return std::make_unique<CustomScene>(o);
}
} // namespace

// A scene in a file of its own defines its factory there and is declared here, e.g.
//   std::unique_ptr<Scene<2>> make_my_scene(const SceneOptions &options);
// next to its line in the table below.

const std::vector<SceneEntry> &scene_registry()
{
  static const std::vector<SceneEntry> table{
      {"moving_hump", make_built_in<MovingHump>,
       "hump with a circular interior layer on (0,1)^2 (John, Maubach & Tobiska 1997)"},
      {"manufactured", make_built_in<Manufactured>,
       "smooth solutions on (0,1)^2 for convergence studies"},
      {"heat", make_built_in<Heat>, "pure diffusion on (0,1)^2 (b = 0, alpha = 0)"},
      {"boundary_layer", make_built_in<BoundaryLayer>,
       "exponential outflow layer at x = 1, for anisotropic refinement"},
      {"hemker", make_built_in<Hemker>,
       "flow past the unit circle in (-3,8)x(-3,3), no exact solution"},
      {"custom", make_custom,
       "the scene defined by the keys scene.grid ... scene.check_tolerance below"},
  };
  return table;
}

const SceneEntry *find_scene(const std::string &name)
{
  for (const auto &e : scene_registry())
    if (name == e.name)
      return &e;
  return nullptr;
}

std::string scene_names(const std::string &separator)
{
  std::string list;
  for (const auto &e : scene_registry())
    list += (list.empty() ? "" : separator) + e.name;
  return list;
}

std::string scene_key_doc()
{
  std::string doc = "The scene (benchmarks: doc/method.md §10). ";
  for (const auto &e : scene_registry())
    doc += std::string(e.name) + ": " + e.doc + (&e == &scene_registry().back() ? "." : "; ");
  return doc;
}
} // namespace anisodwr
