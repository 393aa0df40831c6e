// MindlinPlate::resultant(), the applied_load that Verification/Checks
// compares to 1e-12 (parameters/example2.prm), sums one entry per
// foundation node. A plain sum of entries of one sign drifts with their
// number: 5e-13 for the 29 201 copies of 0.1 below, 6e-12 for example 2's
// load at 10^6 nodes (which then failed its own check). The compensated
// sum keeps it to a few eps whatever the number.
// - 0.1 (not a binary fraction) at every foundation node of example 2's
//   plate on 120 x 80 cells: the resultant is n 0.1 to 1e-14 (a plain sum:
//   5e-13).
// - 0.1 and 0.3 at alternate nodes: 0.1 ceil(n/2) + 0.3 floor(n/2) to
//   3e-15 (the reference's own rounding; a plain sum: 4e-13).
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

  // two values at alternate nodes
  Vector<double> alternating(load.size());
  for (unsigned int i = 0; i < n; ++i)
    alternating[nodes[i]] = i % 2 == 0 ? 0.1 : 0.3;
  const double two_values = 0.1 * ((n + 1) / 2) + 0.3 * (n / 2);
  check_below("|resultant - reference| / reference, 0.1 and 0.3 alternately",
              std::abs(plate.resultant(alternating) - two_values) / two_values,
              3e-15);
}
