#pragma once
// Test fixture shared by the slab-solver tests (test_iterative, test_modes): a scene's
// coarse mesh refined globally, with one cell cut in x so that the constraints hold
// hanging nodes, and its Q_p space.
#include "config/parameters.h"
#include "scene/scene.h"
#include "space/space.h"

#include <deal.II/grid/tria.h>

#include <memory>
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
    space = std::make_unique<anisodwr::Space<2>>(*scene, tria, p, 1.0);
    space->setup();
  }
};
