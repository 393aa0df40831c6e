#include <plate_on_halfspace/base/result_record.h>
#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/plate/slab_results.h>

namespace PlateOnHalfspace
{
  namespace
  {
    const bool declared_cycle = declare_results(
      "cycles",
      80,
      {{{"slabs"},
        "–",
        "with `Plate/Shape = slabs` and more than one slab only: one object "
        "per slab (in the order x fastest, then y) ([Joints](#joints))",
        ResultKind::array},
       {{"joints"},
        "–",
        "with more than one slab only: one object per joint "
        "([Joints](#joints))",
        ResultKind::array}});

    const bool declared_slab = declare_results(
      "cycles.slabs",
      0,
      {{{"x1", "y1", "x2", "y2"}, "length", "the slab's corners"},
       {{"max_principal_stress_bottom", "max_principal_stress_top"},
        "force/length²",
        "the peaks over the slab of the largest principal stress of the "
        "bottom and the top fibre, tension positive"},
       {{"max_principal_stress_bottom_at", "max_principal_stress_top_at"},
        "length",
        "`[x, y]`: where they are",
        ResultKind::location}});

    const bool declared_joint = declare_results(
      "cycles.joints",
      0,
      {{{"x1", "y1", "x2", "y2"}, "length", "the joint's ends"},
       {{"kind"},
        "–",
        "`transverse` (x = const) or `longitudinal` (y = const)",
        ResultKind::text},
       {{"load_transfer"},
        "–",
        "`free`, `aggregate interlock`, `dowels` or `tied`",
        ResultKind::text},
       {{"lte"},
        "–",
        "load transfer efficiency w_unloaded / w_loaded at `lte_at`, the "
        "point of the joint where the larger side's w is largest, of the "
        "deflections the moving loads add to the standing state "
        "([formulation.md](formulation.md#joints)); `null` where neither "
        "side deflects downward"},
       {{"lte_at"}, "length", "`[x, y]` of that point", ResultKind::location},
       {{"w_loaded", "w_unloaded"},
        "length",
        "the two sides' deflections there (added by the moving loads)"},
       {{"max_shear_force"},
        "force/length",
        "the largest shear force per length of joint it transfers (aggregate "
        "interlock: k_s \\|Δw\\|; dowels: the largest bar force over the "
        "spacing; tied: the plates' shear resultant)"},
       {{"dowels"},
        "–",
        "dowels only: one object per bar (below)",
        ResultKind::array},
       {{"max_dowel_force", "max_dowel_bearing_stress"},
        "force, force/length²",
        "dowels only: their largest values"}});

    const bool declared_dowel = declare_results(
      "cycles.joints.dowels",
      0,
      {{{"x", "y"}, "length", "the bar's position"},
       {{"force"},
        "force",
        "positive when the lower-side slab deflects more and the bar pushes "
        "the upper side down"},
       {{"bearing_stress"},
        "force/length²",
        "the concrete's bearing stress under the bar, K y0"}});
  } // namespace

  void
  add_slab_and_joint_results(const MindlinPlate   &plate,
                             const Vector<double> &solution,
                             const Vector<double> &standing,
                             ResultRecord         &record)
  {
    (void)declared_cycle;
    (void)declared_slab;
    (void)declared_joint;
    (void)declared_dowel;
    const SlabGrid *grid = plate.get_slab_grid();
    if (grid == nullptr || grid->n_slabs() <= 1)
      return;
    const MirrorSymmetry &symmetry = plate.get_foundation_space().symmetry;
    for (const Slab &slab : grid->get_slabs())
      {
        // the slab of the computed part that holds this one's image
        const Point<2>     centre   = 0.5 * (slab.lower + slab.upper);
        const Point<2>     image    = symmetry.to_computed_part(centre);
        types::material_id computed = 0;
        for (unsigned int s = 0; s < grid->n_slabs(); ++s)
          {
            const Slab &other = grid->get_slabs()[s];
            if (image[0] > other.lower[0] && image[0] < other.upper[0] &&
                image[1] > other.lower[1] && image[1] < other.upper[1])
              computed = s;
          }
        ResultRecord &entry = record.add_item("slabs");
        entry.set("x1", slab.lower[0]);
        entry.set("y1", slab.lower[1]);
        entry.set("x2", slab.upper[0]);
        entry.set("y2", slab.upper[1]);
        for (const auto &[key, quantity] :
             {std::make_pair(std::string("max_principal_stress_bottom"),
                             PlateQuantity::principal_stress_bottom),
              std::make_pair(std::string("max_principal_stress_top"),
                             PlateQuantity::principal_stress_top)})
          {
            const FieldExtremum peak =
              field_maximum(plate, solution, quantity, computed);
            entry.set_or_null(key, peak.value);
            entry.set(key + "_at",
                      symmetry.from_computed_part(peak.location, centre));
          }
      }

    const std::vector<JointResponse> responses =
      plate.joint_responses(solution, standing);
    for (unsigned int k = 0; k < responses.size(); ++k)
      {
        const Joint         &joint = grid->get_joints()[k];
        const JointResponse &r     = responses[k];
        ResultRecord        &entry = record.add_item("joints");
        entry.set("x1", joint.start[0]);
        entry.set("y1", joint.start[1]);
        entry.set("x2", joint.end[0]);
        entry.set("y2", joint.end[1]);
        entry.set("kind", joint.axis == 0 ? "transverse" : "longitudinal");
        entry.set("load_transfer", Parameters::Joints::name(joint.transfer));
        entry.set_or_null("lte", r.lte);
        entry.set("lte_at", r.lte_at);
        entry.set("w_loaded", r.w_loaded);
        entry.set("w_unloaded", r.w_unloaded);
        entry.set("max_shear_force", r.max_shear_force);
        if (joint.transfer != Parameters::Joints::LoadTransfer::dowels)
          continue;
        double largest = 0, bearing = 0;
        entry.set_empty_array("dowels");
        for (const DowelForce &d : r.dowels)
          {
            ResultRecord &bar = entry.add_item("dowels");
            bar.set("x", d.location[0]);
            bar.set("y", d.location[1]);
            bar.set("force", d.force);
            bar.set("bearing_stress", d.bearing_stress);
            largest = std::max(largest, std::abs(d.force));
            bearing = std::max(bearing, d.bearing_stress);
          }
        entry.set("max_dowel_force", largest);
        entry.set("max_dowel_bearing_stress", bearing);
      }
  }
} // namespace PlateOnHalfspace
