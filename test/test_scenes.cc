// The scene registry (lib/scene/scene_registry.h): its names are unique and documented,
// each builds the scene of its name, and every registered scene runs two DWR loops on a
// coarse mesh with two slabs (a smoke test: a new scene is run by adding its line to the
// registry).
#include "config/parameters.h"
#include "scene/scene.h"
#include "scene/scene_registry.h"
#include "dwr/dwr.h"
#include "study/options.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

using namespace anisodwr;

namespace
{
/// Column `column` of a CSV file, one value per row.
std::vector<double> csv_column(const std::string &file, const std::string &column)
{
  std::ifstream in(file);
  std::string line, cell;
  std::getline(in, line);
  std::istringstream header(line);
  int index = -1;
  for (int i = 0; std::getline(header, cell, ','); ++i)
    if (cell == column)
      index = i;
  std::vector<double> values;
  while (index >= 0 && std::getline(in, line))
  {
    std::istringstream row(line);
    for (int i = 0; i <= index; ++i)
      std::getline(row, cell, ',');
    values.push_back(cell.empty() ? NAN : std::stod(cell));
  }
  return values;
}

/// The settings of the smoke run of `scene`. The custom scene takes its keys from
/// config/custom_example.json (its defaults define u = 0).
Parameters smoke_settings(const std::string &scene, const std::string &dir)
{
  const std::vector<std::string> tiny{
      "study.mode=dwr",           "adaptivity.loops=2",
      "discretization.n_slabs=2", "discretization.initial_refinements=1",
      "output.progress=false",    "output.vtu_every=0",
      "output.vtu_loops=0",       "output.directory=" + dir};
  if (scene == "custom")
    return Parameters::read(std::string(ANISODWR_SOURCE_DIR) + "/config/custom_example.json",
                            tiny);
  std::vector<std::string> settings = tiny;
  settings.push_back("scene.name=" + scene);
  return Parameters::from_overrides(settings);
}
} // namespace

TEST(SceneRegistry, NamesAreUniqueAndDocumented)
{
  std::set<std::string> seen;
  for (const SceneEntry &entry : scene_registry())
  {
    EXPECT_TRUE(seen.insert(entry.name).second) << entry.name;
    EXPECT_GT(std::string(entry.doc).size(), 10u) << entry.name;
    EXPECT_EQ(find_scene(entry.name), &entry);
    EXPECT_NE(scene_key_doc().find(std::string(entry.name) + ": " + entry.doc),
              std::string::npos)
        << entry.name;
  }
  EXPECT_TRUE(seen.count(Parameters().scene.name)); // the default scene
  EXPECT_EQ(find_scene("hemkerr"), nullptr);
}

TEST(SceneRegistry, EveryEntryBuildsTheSceneOfItsName)
{
  for (const SceneEntry &entry : scene_registry())
  {
    const auto scene =
        create_scene<2>(Parameters::from_overrides({std::string("scene.name=") + entry.name}));
    ASSERT_TRUE(scene) << entry.name;
    EXPECT_EQ(scene->name(), entry.name);
  }
}

TEST(SceneRegistry, EverySceneRunsTwoDwrLoops)
{
  for (const SceneEntry &entry : scene_registry())
  {
    const std::string dir =
        (std::filesystem::temp_directory_path() / ("anisodwr_smoke_" + std::string(entry.name)))
            .string();
    std::filesystem::remove_all(dir);
    run_dwr(smoke_settings(entry.name, dir));
    const std::vector<double> eta = csv_column(dir + "/loops.csv", "eta_tauh");
    ASSERT_EQ(eta.size(), 2u) << entry.name;
    for (const double e : eta)
      EXPECT_TRUE(std::isfinite(e)) << entry.name;
    std::filesystem::remove_all(dir);
  }
}
