// MindlinPlate::resultant(), the applied_load that Verification/Checks
// compares to 1e-12 (parameters/example2.prm), sums one entry per
// foundation node. A plain sum of n entries of one sign drifts by about
// n eps / 4 of the total: 5e-13 at the 3e4 nodes here, 6e-12 at 10^6 (a
// refined example 2 then failed its own check). The compensated sum keeps
// it to a few eps whatever n.
// - 0.1 (not a binary fraction) at every foundation node of example 2's
//   plate on 120 x 80 cells: the resultant is n 0.1 to 1e-14 (a plain sum:
//   5e-13).
// - The same entries in the other order: the same value to 2e-15.
// Only verdicts are printed.

#include <plate_on_halfspace/plate/mindlin_plate.h>
#include <plate_on_halfspace/plate/plate_mesh.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <cmath>

#include "../tests.h"

using namespace PlateOnHalfspace;

int
main()
{
  initlog();
  SceneParameters parameters;
  parameters.read_from_string(
    "include " SOURCE_DIR "/../../parameters/example2-bonded.prm\n"
    "set Output directory = results\n"
    "subsection Discretization\n set Symmetry = none\n"
    " set Subdivisions x = 120\n set Subdivisions y = 80\nend\n");
  Triangulation<2> mesh;
  make_plate_mesh(parameters.plate, parameters.discretization, mesh);
  MindlinPlate plate(parameters.plate, parameters.discretization);
  plate.setup(mesh);
  const auto        &nodes = plate.get_foundation_dofs();
  const unsigned int n     = nodes.size();
  check_greater("foundation nodes", n, 29000);

  Vector<double> load(plate.get_dof_handler().n_dofs());
  for (const auto dof : nodes)
    load[dof] = 0.1;
  const double reference = n * 0.1;
  const double sum       = plate.resultant(load);
  check_below("|resultant - n 0.1| / (n 0.1)",
              std::abs(sum - reference) / reference,
              1e-14);

  // the entries placed in the reverse order of the foundation nodes: a
  // plain sum would round differently
  Vector<double> reversed(load.size());
  for (unsigned int i = 0; i < n; ++i)
    reversed[nodes[i]] = 0.1 * (1 + 1e-3 * i);
  Vector<double> forward(load.size());
  for (unsigned int i = 0; i < n; ++i)
    forward[nodes[n - 1 - i]] = 0.1 * (1 + 1e-3 * i);
  check_below("the resultant in either order",
              std::abs(plate.resultant(reversed) - plate.resultant(forward)) /
                plate.resultant(forward),
              2e-15);
}
