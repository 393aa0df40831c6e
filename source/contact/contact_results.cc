#include <plate_on_halfspace/base/result_record.h>
#include <plate_on_halfspace/contact/contact_region.h>
#include <plate_on_halfspace/contact/contact_results.h>
#include <plate_on_halfspace/halfspace/interface.h>

#include <numeric>

namespace PlateOnHalfspace
{
  namespace
  {
    const bool declared = declare_results(
      "cycles",
      30,
      {{{"contact_iterations"},
        "–",
        "active-set steps or element-exclusion iterations (1 when bonded)",
        ResultKind::count},
       {{"contact_nodes"},
        "–",
        "foundation nodes of the whole plate where pressure acts: the active "
        "set and every node with q > 0",
        ResultKind::count},
       {{"contact_area_fraction"},
        "–",
        "area in contact over the plate's area, located from the fields "
        "inside the cells ([Contact area](#contact-area)); 1 when bonded"},
       {{"contact_force"},
        "force",
        "the integral of q over the footprint (the sum of the nodal forces); "
        "equilibrium means it equals `applied_load`"},
       {{"complementarity_violation"},
        "–",
        "distance from the exact discrete contact conditions: the largest of "
        "(−min q̃)⁺ / max \\|q̃\\|, (−min gap)⁺ / max \\|B w\\| and max "
        "\\|q̃ gap\\| / (max \\|q̃\\| max \\|B w\\|), q̃ the pressure "
        "coefficients of the contact basis "
        "([formulation.md](formulation.md#tensionless-contact)); rounding "
        "(≈ 1e-16) for the active set with the direct solver; the "
        "iterative solver's last solve's accuracy with it (about 1e-9 with "
        "the dense storage, up to about 1e-7 with the hierarchical and fft "
        "storages at the default `Tolerance`: "
        "[performance.md](performance.md#the-last-solves-accuracy))"},
       {{"tensile_nodes"},
        "–",
        "nodes of the whole plate with a tensile pressure coefficient "
        "(q̃ < 0); 0 for the active set",
        ResultKind::count},
       {{"max_penetration"},
        "–",
        "largest penetration (−gap)⁺ relative to max \\|B w\\|"},
       {{"converged"},
        "–",
        "whether this cycle's contact iteration converged",
        ResultKind::flag},
       {{"coupled_matrix_rcond"},
        "–",
        "LAPACK's estimate of 1/κ₁ of the coupled matrix K̄ + S of the last "
        "solve (direct solver; reads 1 with the iterative solver)"},
       {{"foundation_block_rcond"},
        "–",
        "the same estimate for the half-space block F_CC of the last contact "
        "set (direct solver; 1 for the iterative one)"}},
      {{"contact its",
        "`contact_iterations`",
        [](const ResultRecord &r, double &v) {
          v = r.number("contact_iterations");
          return true;
        },
        0},
       {"contact fraction",
        "`contact_area_fraction`",
        [](const ResultRecord &r, double &v) {
          v = r.number("contact_area_fraction");
          return true;
        },
        6,
        true,
        true},
       {"contact force",
        "`contact_force`",
        [](const ResultRecord &r, double &v) {
          v = r.number("contact_force");
          return true;
        },
        6,
        true}});
  } // namespace

  void
  add_contact_results(const FoundationSpace    &space,
                      const FoundationOperator &foundation,
                      const ContactState       &contact,
                      ResultRecord             &record)
  {
    (void)declared;
    const unsigned int copies = space.symmetry.n_copies();
    // Nodes in contact on the whole plate: a node of the computed part
    // stands for its distinct mirror images; the same for the nodes whose
    // pressure coefficient is tensile.
    unsigned long long contact_nodes = 0, tensile_nodes = 0;
    for (unsigned int i = 0; i < space.n_nodes(); ++i)
      {
        const unsigned int images = space.node_images(i).size();
        if (contact.in_contact[i])
          contact_nodes += images;
        if (contact.pressure_coefficients[i] < 0)
          tensile_nodes += images;
      }
    // Equilibrium: the integral of q is the sum of the nodal forces M q.
    Vector<double> forces;
    foundation.nodal_forces(contact.pressure_coefficients, forces);
    record.set_count("contact_iterations", contact.iterations);
    record.set_count("contact_nodes", contact_nodes);
    record.set("contact_area_fraction", contact_area(contact) / space.area());
    record.set("contact_force",
               copies * std::accumulate(forces.begin(), forces.end(), 0.));
    record.set("complementarity_violation", contact.complementarity_violation);
    record.set_count("tensile_nodes", tensile_nodes);
    record.set("max_penetration", contact.max_penetration);
    record.set("converged", contact.converged);
    record.set("coupled_matrix_rcond", contact.coupled_rcond);
    record.set("foundation_block_rcond", contact.contact_block_rcond);
  }
} // namespace PlateOnHalfspace
