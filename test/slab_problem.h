#pragma once
// Test fixture shared by the slab-solver tests (test_iterative, test_modes): a scene's
// coarse mesh refined globally, with one cell cut in x so that the constraints hold
// hanging nodes, and its Q_p space; and reproducible random right-hand sides.
#include "config/parameters.h"
#include "scene/scene.h"
#include "space/space.h"

#include <deal.II/grid/tria.h>
#include <deal.II/lac/vector.h>

#include <memory>
#include <random>
#include <sstream>
#include <string>

struct SlabProblem
{
  std::unique_ptr<anisodwr::Scene<2>> scene;
  dealii::Triangulation<2> tria;
  std::unique_ptr<anisodwr::Space<2>> space;

  SlabProblem(const std::string &name, const std::string &variant, unsigned int p,
              double eps, unsigned int refinements = 2)
  {
    std::ostringstream e;
    e << "scene.epsilon=" << eps;
    scene = anisodwr::create_scene<2>(anisodwr::Parameters::from_overrides(
        {"scene.name=" + name, "scene.variant=" + variant, e.str()}));
    scene->make_coarse_grid(tria);
    tria.refine_global(refinements);
    // one anisotropic refinement: hanging nodes in the constraints
    tria.begin_active()->set_refine_flag(dealii::RefinementCase<2>::cut_x);
    tria.execute_coarsening_and_refinement();
    space = std::make_unique<anisodwr::Space<2>>(
        *scene, tria, p, anisodwr::Stabilization{1.0, anisodwr::SupgLength::volume, 0.});
    space->setup();
  }
};

/// n uniform random values in [-1, 1] from the seed.
inline dealii::Vector<double> random_vector(std::size_t n, unsigned int seed)
{
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-1., 1.);
  dealii::Vector<double> v(n);
  for (auto &x : v)
    x = d(gen);
  return v;
}
