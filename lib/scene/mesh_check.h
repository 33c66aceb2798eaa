#pragma once
// Checks of a user's coarse mesh (a Gmsh file or a generator) before anything uses it:
// a mesh deal.II reads without complaint can still be no domain the solver can work
// on (triangles, cracks, hanging coarse nodes, zero-area or inverted cells, a node
// defined twice). Each check throws InputError naming the mesh and the offending
// cell, node or point.
#include <deal.II/grid/tria.h>

#include <istream>
#include <string>

namespace anisodwr
{
/// Throws InputError("<prefix>the domain <domain> ...") where `tria`
/// - has a cell that is not a quadrilateral;
/// - has two vertices at one point (a crack: the cells on either side do not share
///   them, so the interface becomes boundary);
/// - has a vertex coordinate that is not finite or beyond 1e8 in size (areas and
///   quadrature weights overflow or lose their digits);
/// - has a vertex inside a boundary face of another cell (a hanging coarse node: the
///   coarse mesh must be conforming);
/// - has a cell with a corner whose two edges do not turn counter-clockwise by more than
///   1e-10 of their lengths' product (zero area, a bow-tie, an inverted cell).
/// Points are compared to 1e-12 of the mesh's diameter.
void check_coarse_mesh(const dealii::Triangulation<2> &tria, const std::string &prefix,
                       const std::string &domain);

/// Throws InputError(prefix + ...) naming the section and the
/// entry where the ASCII Gmsh file `in` (format 2.x or 4.1) departs from its structure:
/// a count or number that does not parse or is out of range, a section whose entries do
/// not end at its $End line, an unknown element type, an element node that $Nodes does
/// not define; and InputError naming the tag if a node tag is defined twice (deal.II
/// keeps the last definition). deal.II's reader does not check these: a malformed count
/// can make it allocate without bound. Binary files pass (deal.II refuses them).
void check_msh_file(std::istream &in, const std::string &prefix);

/// Throws InputError("<where>: key 'scene.grid_arguments' ...") if the generator `name`
/// is subdivided_hyper_rectangle or subdivided_hyper_cube and its first argument (the
/// repetitions: two whole numbers, or one) is not whole numbers >= 1 or asks for more
/// than 1e6 cells. Checked before the generator runs: deal.II would read -1 as 2^32 - 1
/// and a single number as the first of two, and allocate the cells.
void check_repetitions(const std::string &name, const std::string &arguments,
                       const std::string &where);
} // namespace anisodwr
