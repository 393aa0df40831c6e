// Each subsection of the scene file (doc/parameters.md): its declaration
// with every help text and pattern, and its parsing with the range checks
// that name the entry. One pair of functions per subsection keeps a
// subsection in one place, which is why this file is longer than 600
// lines; the checks across subsections are in scene_parameters.cc.

#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <boost/algorithm/string/join.hpp>

#include <plate_on_halfspace/base/number_list.h>
#include <plate_on_halfspace/base/result_record.h>
#include <plate_on_halfspace/refinement/goal.h>
#include <plate_on_halfspace/scene/input_checks.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

namespace PlateOnHalfspace
{

  namespace
  {
    void
    require(const bool condition, const std::string &message)
    {
      AssertThrow(condition, ExcMessage(message));
    }

    /** @p value to 6 significant digits, as a bound in a message. */
    std::string
    rounded_text(const double value)
    {
      std::ostringstream s;
      s << value;
      return s.str();
    }

    /** " (got X)" for the messages of the checks below. */
    std::string
    got(const double value)
    {
      return " (got " + rounded_text(value) + ")";
    }

    std::string
    to_text(const double value)
    {
      std::ostringstream s;
      s << std::setprecision(12) << value;
      return s.str();
    }
  } // namespace

  namespace Parameters
  {
    void
    Plate::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Plate");
      prm.declare_entry("Shape",
                        "rectangle",
                        Patterns::Selection("rectangle|disk|mesh file|slabs"),
                        "Plan of the plate: a rectangle [-Lx/2,Lx/2]x[-Ly/2,"
                        "Ly/2], a disk centred at the origin, a Gmsh mesh, "
                        "or a grid of slabs with joints between them "
                        "(subsection Joints).");
      prm.declare_entry("Length x",
                        "12",
                        Patterns::Double(0),
                        "Shape = rectangle: side along x [length].");
      prm.declare_entry("Length y",
                        "8",
                        Patterns::Double(0),
                        "Shape = rectangle: side along y [length].");
      prm.declare_entry("Slab lengths x",
                        "4.5, 4.5",
                        Patterns::Anything(),
                        "Shape = slabs: the slabs' sizes along x [length], "
                        "a comma-separated list; the grid is centred at the "
                        "origin and transverse joints lie between them.");
      prm.declare_entry("Slab lengths y",
                        "3.6",
                        Patterns::Anything(),
                        "Shape = slabs: the slabs' sizes along y [length]; "
                        "longitudinal joints lie between them.");
      prm.declare_entry("Radius",
                        "1",
                        Patterns::Double(0),
                        "Shape = disk: radius [length].");
      prm.declare_entry("Mesh file",
                        "",
                        Patterns::Anything(),
                        "Shape = mesh file: Gmsh .msh file with straight-sided "
                        "quadrilaterals in the x-y plane (relative paths are "
                        "taken from the working directory).");
      prm.declare_entry("Thickness",
                        "0.5",
                        Patterns::Double(0),
                        "Plate thickness t [length].");
      prm.declare_entry("Young's modulus",
                        "2.5e7",
                        Patterns::Double(0),
                        "Young's modulus E of the plate [force/length^2].");
      prm.declare_entry("Poisson's ratio",
                        "0.15",
                        Patterns::Double(-1, 0.5),
                        "Poisson's ratio nu of the plate, -1 < nu < 0.5.");
      prm.declare_entry("Unit weight",
                        "0",
                        Patterns::Double(0),
                        "Unit weight of the plate material [force/length^3]; "
                        "> 0 adds the self weight unit weight x thickness as "
                        "a uniform downward pressure.");
      prm.leave_subsection();
    }

    void
    Plate::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Plate");
      const std::string s = prm.get("Shape");
      shape               = (s == "rectangle" ? Shape::rectangle :
                             s == "disk"      ? Shape::disk :
                             s == "slabs"     ? Shape::slabs :
                                                Shape::mesh_file);
      const auto lengths  = [&](const std::string &entry) {
        std::vector<double> values;
        for (const auto &item :
             parse_number_list(prm.get(entry), 0, "Plate/" + entry, ""))
          values.insert(values.end(), item.begin(), item.end());
        if (shape == Shape::slabs)
          {
            require(!values.empty() && values.size() <= 20,
                    "Plate/" + entry +
                      " must list 1 to 20 slab sizes for Shape = slabs"
                       " (got " +
                      std::to_string(values.size()) + ").");
            for (const double value : values)
              require(value > 0,
                      "Plate/" + entry + ": every slab size must be > 0" +
                        got(value) + ".");
          }
        return values;
      };
      slab_lengths_x = lengths("Slab lengths x");
      slab_lengths_y = lengths("Slab lengths y");
      length_x       = prm.get_double("Length x");
      length_y       = prm.get_double("Length y");
      // The grid's outline is a rectangle: what every check of the
      // rectangle (loads on the plate, cell size, probes, goals, sweep,
      // symmetry) reads. It replaces Length x/y, which a grid of slabs
      // ignores (doc/parameters.md), after they are read, so that their
      // defaults never stand for the grid.
      if (shape == Shape::slabs)
        {
          length_x =
            std::accumulate(slab_lengths_x.begin(), slab_lengths_x.end(), 0.);
          length_y =
            std::accumulate(slab_lengths_y.begin(), slab_lengths_y.end(), 0.);
        }
      radius         = prm.get_double("Radius");
      mesh_file      = prm.get("Mesh file");
      thickness      = prm.get_double("Thickness");
      youngs_modulus = prm.get_double("Young's modulus");
      poissons_ratio = prm.get_double("Poisson's ratio");
      unit_weight    = prm.get_double("Unit weight");
      prm.leave_subsection();

      if (shape == Shape::rectangle)
        require(length_x > 0 && length_y > 0,
                "Plate/Length x and Plate/Length y must be > 0 for "
                "Shape = rectangle" +
                  got(std::min(length_x, length_y)) + ".");
      if (shape == Shape::disk)
        require(radius > 0,
                "Plate/Radius must be > 0 for Shape = disk" + got(radius) +
                  ".");
      if (shape == Shape::mesh_file)
        require(!mesh_file.empty(),
                "Plate/Mesh file must name a Gmsh .msh file for "
                "Shape = mesh file.");
      require(thickness > 0,
              "Plate/Thickness must be > 0" + got(thickness) + ".");
      if (shape != Shape::mesh_file)
        {
          const double width =
            shape == Shape::disk ?
              2 * radius :
            shape == Shape::slabs ?
              std::min(*std::min_element(slab_lengths_x.begin(),
                                         slab_lengths_x.end()),
                       *std::min_element(slab_lengths_y.begin(),
                                         slab_lengths_y.end())) :
              std::min(length_x, length_y);
          const std::string entries =
            shape == Shape::disk  ? "Plate/Radius" :
            shape == Shape::slabs ? "Plate/Slab lengths x and y" :
                                    "Plate/Length x and y";
          const std::string problem =
            plate_width_problem(width,
                                thickness,
                                entries + ": the plate (or a slab)",
                                "the lengths");
          require(problem.empty(), problem);
        }
      require(youngs_modulus > 0,
              "Plate/Young's modulus must be > 0" + got(youngs_modulus) + ".");
      // Closer to -1 the bending stiffness of anticlastic curvature and
      // twist, D (1 - nu), exceeds that of synclastic curvature, D (1 + nu),
      // more than 1e6 times, and rounding takes the pressures' digits
      // (doc/errors-and-limits.md, "Poisson's ratios and load magnitude").
      require(poissons_ratio >= -0.999999 && poissons_ratio < 0.5,
              "Plate/Poisson's ratio must lie in [-0.999999, 0.5) (got " +
                to_text(poissons_ratio) + ")" +
                (poissons_ratio < -0.999999 && poissons_ratio > -1 ?
                   ": nearer -1 the plate's stiffness against twist "
                   "exceeds that against a dome-shaped bending more than "
                   "1e6 times, and rounding would take the results' "
                   "digits." :
                   "."));
    }

    double
    Plate::flexural_rigidity() const
    {
      return youngs_modulus * thickness * thickness * thickness /
             (12. * (1. - poissons_ratio * poissons_ratio));
    }

    void
    Foundation::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Foundation");
      prm.declare_entry("Model",
                        "half-space",
                        Patterns::Selection("half-space|dense liquid|layered"),
                        "half-space: the elastic half-space (Boussinesq; "
                        "Young's modulus and Poisson's ratio); dense liquid: "
                        "the Winkler foundation, q = k w where the soil "
                        "carries the plate (Modulus of subgrade reaction); "
                        "layered: elastic Layers over a Base (a half-space "
                        "of Young's modulus and Poisson's ratio, or rigid).");
      prm.declare_entry("Layers",
                        "",
                        Patterns::Anything(),
                        "Model = layered: the layers top down, each "
                        "thickness, Young's modulus, Poisson's ratio "
                        "[length, force/length^2, -], separated by ';' "
                        "(e.g. 0.3, 3e5, 0.35 ; 4, 4e4, 0.4). Thickness > 0, "
                        "E > 0, 0 <= nu < 0.5, at most 50 layers.");
      prm.declare_entry("Base",
                        "half-space",
                        Patterns::Selection("half-space|rigid"),
                        "Model = layered: what lies under the layers: an "
                        "elastic half-space (Young's modulus, Poisson's "
                        "ratio) or a rigid base (bedrock).");
      prm.declare_entry("Interfaces",
                        "bonded",
                        Patterns::Selection("bonded|frictionless"),
                        "Model = layered: between the layers and on a rigid "
                        "base, bonded (continuous displacements) or "
                        "frictionless (continuous settlement, no shear).");
      prm.declare_entry("Young's modulus",
                        "1e5",
                        Patterns::Double(0),
                        "Young's modulus E0 of the half-space "
                        "[force/length^2].");
      prm.declare_entry("Poisson's ratio",
                        "0.3",
                        Patterns::Double(0, 0.5),
                        "Poisson's ratio nu0 of the half-space, "
                        "0 <= nu0 < 0.5.");
      prm.declare_entry("Modulus of subgrade reaction",
                        "0",
                        Patterns::Double(),
                        "k of the dense liquid [force/length^3], > 0 with "
                        "Model = dense liquid; leave 0 for the half-space.");
      prm.declare_entry("Contact",
                        "tensionless",
                        Patterns::Selection("tensionless|bonded"),
                        "bonded: the soil also pulls (q of any sign); "
                        "tensionless: q >= 0 and the plate may lift off.");
      prm.leave_subsection();
    }

    void
    Foundation::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Foundation");
      const std::string model_name = prm.get("Model");
      model = model_name == "dense liquid" ? Model::dense_liquid :
              model_name == "layered"      ? Model::layered :
                                             Model::half_space;
      layers.clear();
      for (const auto &v : parse_number_list(
             prm.get("Layers"), 3, "Foundation/Layers", "thickness, E, nu"))
        {
          const std::string which =
            " (layer " + std::to_string(layers.size() + 1) + ")";
          require(v[0] > 0,
                  "Foundation/Layers: each thickness must be > 0" + which +
                    got(v[0]) + ".");
          require(v[1] > 0,
                  "Foundation/Layers: each Young's modulus must be > 0" +
                    which + got(v[1]) + ".");
          require(v[2] >= 0 && v[2] < 0.5,
                  "Foundation/Layers: each Poisson's ratio must lie in "
                  "[0, 0.5)" +
                    which + got(v[2]) + ".");
          layers.push_back({v[0], v[1], v[2]});
        }
      rigid_base              = prm.get("Base") == "rigid";
      frictionless_interfaces = prm.get("Interfaces") == "frictionless";
      youngs_modulus          = prm.get_double("Young's modulus");
      poissons_ratio          = prm.get_double("Poisson's ratio");
      subgrade_modulus        = prm.get_double("Modulus of subgrade reaction");
      tensionless             = (prm.get("Contact") == "tensionless");
      prm.leave_subsection();
      if (model == Model::layered)
        check_layers();
      else
        {
          require(layers.empty(),
                  "Foundation/Layers belong to Foundation/Model = layered "
                  "(set Model = layered, or leave Layers empty).");
          // Entries that only the layered soil reads are refused rather
          // than silently ignored.
          require(!rigid_base,
                  "Foundation/Base = rigid belongs to Foundation/Model = "
                  "layered (set Model = layered and list the Layers over "
                  "the rigid base, or leave Base = half-space).");
          require(!frictionless_interfaces,
                  "Foundation/Interfaces = frictionless belongs to "
                  "Foundation/Model = layered (set Model = layered, or "
                  "leave Interfaces = bonded).");
        }
      if (model == Model::dense_liquid)
        require(subgrade_modulus > 0,
                "Foundation/Modulus of subgrade reaction must be > 0 with "
                "Foundation/Model = dense liquid" +
                  got(subgrade_modulus) + ".");
      else
        require(subgrade_modulus == 0,
                "Foundation/Modulus of subgrade reaction belongs to "
                "Foundation/Model = dense liquid; the half-space takes "
                "Young's modulus and Poisson's ratio (set Model = dense "
                "liquid, or leave the modulus 0)" +
                  got(subgrade_modulus) + ".");
      require(youngs_modulus > 0,
              "Foundation/Young's modulus must be > 0" + got(youngs_modulus) +
                ".");
      // A soil's nu0 lies in [0, 0.5); 0.5 (undrained) is the limit the
      // Poisson sweep of tests/unit/extreme_scenes approaches continuously.
      require(poissons_ratio >= 0 && poissons_ratio < 0.5,
              "Foundation/Poisson's ratio must lie in [0, 0.5)" +
                got(poissons_ratio) + ".");
    }

    void
    Foundation::check_layers() const
    {
      require(!layers.empty(),
              "Foundation/Layers must list at least one layer (thickness, "
              "Young's modulus, Poisson's ratio) with Foundation/Model = "
              "layered.");
      require(layers.size() <= 50,
              "Foundation/Layers: at most 50 layers" + got(layers.size()) +
                ".");
      // The kernel's accuracy is stated relative to the settlements it
      // adds; a contrast beyond 1e6 is not a soil but a rigid inclusion
      // (doc/soil-models.md, "Limits").
      double softest =
               rigid_base ? std::numeric_limits<double>::max() : youngs_modulus,
             stiffest = rigid_base ? 0. : youngs_modulus;
      for (const Layer &layer : layers)
        {
          softest  = std::min(softest, layer.youngs_modulus);
          stiffest = std::max(stiffest, layer.youngs_modulus);
        }
      require(stiffest <= 1e6 * softest,
              "Foundation/Layers: the Young's moduli of the layers" +
                std::string(rigid_base ? "" :
                                         " and the half-space under "
                                         "them (Foundation/Young's "
                                         "modulus)") +
                " may differ by a factor of at most 1e6" +
                got(stiffest / softest) +
                "; model a much stiffer stratum as Base = rigid.");
    }

    std::string
    Joints::name(const LoadTransfer transfer)
    {
      switch (transfer)
        {
          case LoadTransfer::free:
            return "free";
          case LoadTransfer::aggregate_interlock:
            return "aggregate interlock";
          case LoadTransfer::dowels:
            return "dowels";
          case LoadTransfer::tied:
            return "tied";
        }
      return "";
    }

    void
    Joints::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Joints");
      prm.declare_entry("Load transfer",
                        "aggregate interlock",
                        Patterns::Selection(
                          "free|aggregate interlock|dowels|tied"),
                        "Plate/Shape = slabs: how the joints carry load from "
                        "slab to slab. free: two free edges; aggregate "
                        "interlock: a shear spring along the joint (Shear "
                        "stiffness); dowels: dowel bars across it (Dowel "
                        "...); tied: tie bars, continuous deflection and "
                        "rotations. Applies to every joint unless "
                        "Longitudinal load transfer says otherwise.");
      prm.declare_entry("Longitudinal load transfer",
                        "same",
                        Patterns::Selection(
                          "same|free|aggregate interlock|dowels|tied"),
                        "The load transfer of the longitudinal joints (along "
                        "x, between Slab lengths y); same: as Load transfer.");
      prm.declare_entry("Shear stiffness",
                        "1e6",
                        Patterns::Double(),
                        "Aggregate interlock: shear force per length of "
                        "joint per unit deflection difference across it "
                        "[force/length^2], > 0.");
      prm.declare_entry("Dowel diameter",
                        "0.032",
                        Patterns::Double(),
                        "Dowels: bar diameter [length], > 0.");
      prm.declare_entry("Dowel spacing",
                        "0.3",
                        Patterns::Double(),
                        "Dowels: distance between bars [length], > 0; the "
                        "bars are centred on each joint.");
      prm.declare_entry("Dowel modulus",
                        "2e8",
                        Patterns::Double(),
                        "Dowels: Young's modulus of the bar "
                        "[force/length^2], > 0.");
      prm.declare_entry("Joint opening",
                        "0.006",
                        Patterns::Double(),
                        "Dowels: width of the joint the bar spans [length], "
                        ">= 0.");
      prm.declare_entry("Dowel support modulus",
                        "4.07e8",
                        Patterns::Double(),
                        "Dowels: modulus of dowel support K, the concrete's "
                        "reaction per bar surface deflection "
                        "[force/length^3], > 0 (4.07e8 kN/m^3 = 1.5e6 pci).");
      prm.leave_subsection();
    }


    void
    Joints::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Joints");
      const auto transfer = [](const std::string &text) {
        return text == "free" ? LoadTransfer::free :
               text == "aggregate interlock" ?
                                LoadTransfer::aggregate_interlock :
               text == "dowels" ? LoadTransfer::dowels :
                                  LoadTransfer::tied;
      };
      transverse              = transfer(prm.get("Load transfer"));
      const std::string along = prm.get("Longitudinal load transfer");
      longitudinal          = (along == "same" ? transverse : transfer(along));
      shear_stiffness       = prm.get_double("Shear stiffness");
      dowel_diameter        = prm.get_double("Dowel diameter");
      dowel_spacing         = prm.get_double("Dowel spacing");
      dowel_modulus         = prm.get_double("Dowel modulus");
      joint_opening         = prm.get_double("Joint opening");
      dowel_support_modulus = prm.get_double("Dowel support modulus");
      prm.leave_subsection();
    }

    void
    Joints::check(const Plate &plate) const
    {
      const bool interlock = transverse == LoadTransfer::aggregate_interlock ||
                             longitudinal == LoadTransfer::aggregate_interlock;
      const bool dowelled = transverse == LoadTransfer::dowels ||
                            longitudinal == LoadTransfer::dowels;
      if (interlock)
        require(shear_stiffness > 0 && std::isfinite(shear_stiffness),
                "Joints/Shear stiffness must be > 0 with aggregate "
                "interlock" +
                  got(shear_stiffness) + ".");
      if (dowelled)
        {
          require(dowel_diameter > 0,
                  "Joints/Dowel diameter must be > 0 with dowels" +
                    got(dowel_diameter) + ".");
          require(dowel_spacing > 0,
                  "Joints/Dowel spacing must be > 0 with dowels" +
                    got(dowel_spacing) + ".");
          require(dowel_modulus > 0,
                  "Joints/Dowel modulus must be > 0 with dowels" +
                    got(dowel_modulus) + ".");
          require(joint_opening >= 0,
                  "Joints/Joint opening must be >= 0 with dowels" +
                    got(joint_opening) + ".");
          require(dowel_support_modulus > 0,
                  "Joints/Dowel support modulus must be > 0 with dowels" +
                    got(dowel_support_modulus) + ".");
        }

      // The bounds against the slabs, for the joints that exist: transverse
      // ones (x = const, as long as the slab sizes along y) between columns
      // of slabs, longitudinal ones (y = const, as long as the sizes along
      // x) between rows.
      std::vector<double> dowelled_lengths;
      bool                interlocked = false;
      const auto          joints      = [&](const LoadTransfer         transfer,
                              const std::vector<double> &lengths,
                              const bool                 exist) {
        if (!exist)
          return;
        interlocked =
          interlocked || transfer == LoadTransfer::aggregate_interlock;
        if (transfer == LoadTransfer::dowels)
          dowelled_lengths.insert(dowelled_lengths.end(),
                                  lengths.begin(),
                                  lengths.end());
      };
      joints(transverse, plate.slab_lengths_y, plate.slab_lengths_x.size() > 1);
      joints(longitudinal,
             plate.slab_lengths_x,
             plate.slab_lengths_y.size() > 1);
      const double E = plate.youngs_modulus;
      const double t = plate.thickness;
      // Stiffness bounds: a joint spring k_s (and a bar's modulus, and its
      // support per length of bar K d) beyond 1e6 times the slabs' own
      // modulus is rigid in every digit the slabs' stiffness can carry:
      // k_s = 1e7 E ran on 0.2 m slabs with cells from 0.5 m to 4.5 m
      // long, k_s = 1e8 E failed in the contact iteration, naming no
      // entry. With K d and the bar's modulus at 1e6 E, a bar per its
      // spacing (> d) is below about 2e5 E per length of joint.
      const std::string rigid =
        ": a stiffer joint is rigid in every digit the slabs' stiffness "
        "can carry; to join the slabs rigidly use Joints/Load transfer = "
        "tied.";
      if (interlocked)
        require(shear_stiffness <= 1e6 * E,
                "Joints/Shear stiffness must be at most 1e6 times "
                "Plate/Young's modulus = " +
                  rounded_text(1e6 * E) + " for this plate" +
                  got(shear_stiffness) + rigid);
      if (dowelled_lengths.empty())
        return;
      // A bar below 1e-6 t carries nothing the slabs can feel, and its
      // d^4 underflows (1e-300 gave "The plate is a mechanism").
      require(dowel_diameter >= 1e-6 * t,
              "Joints/Dowel diameter must be at least 1e-6 times "
              "Plate/Thickness = " +
                rounded_text(1e-6 * t) + " for this plate" +
                got(dowel_diameter) +
                ": so thin a bar transfers no load in any digit; for joints "
                "without load transfer use Joints/Load transfer = free.");
      require(dowel_diameter < t,
              "Joints/Dowel diameter must be less than Plate/Thickness = " +
                rounded_text(t) + got(dowel_diameter) +
                ": the bar lies inside the slab.");
      require(dowel_diameter < dowel_spacing,
              "Joints/Dowel diameter must be less than Joints/Dowel "
              "spacing = " +
                rounded_text(dowel_spacing) + got(dowel_diameter) +
                ": neighbouring bars would overlap.");
      const double longest =
        *std::max_element(dowelled_lengths.begin(), dowelled_lengths.end());
      require(dowel_spacing <= longest,
              "Joints/Dowel spacing must be at most the length of the "
              "longest dowelled joint, " +
                rounded_text(longest) + " for these slabs" +
                got(dowel_spacing) +
                ": a joint shorter than the spacing has one bar at its "
                "middle, so a larger spacing means nothing; check the "
                "units.");
      require(dowel_modulus <= 1e6 * E,
              "Joints/Dowel modulus must be at most 1e6 times Plate/Young's "
              "modulus = " +
                rounded_text(1e6 * E) + " for this plate" + got(dowel_modulus) +
                rigid);
      // The model puts both slabs' faces on the joint line and the opening
      // into the bar's compliance only (doc/formulation.md, "Joints"): a
      // gap narrow against the slab. A gap as wide as the slab is thick is
      // no joint.
      require(joint_opening < t,
              "Joints/Joint opening must be less than Plate/Thickness = " +
                rounded_text(t) + got(joint_opening) +
                ": the model puts both slabs' faces on the joint line and "
                "the opening into the bar's bending only, which holds for a "
                "gap narrow against the slab.");
      // K d is the support per length of bar [force/length^2], as E.
      require(dowel_support_modulus <= 1e6 * E / dowel_diameter,
              "Joints/Dowel support modulus must be at most 1e6 times "
              "Plate/Young's modulus / Joints/Dowel diameter = " +
                rounded_text(1e6 * E / dowel_diameter) +
                " for this plate and bar" + got(dowel_support_modulus) + rigid);
    }

    const std::vector<std::string> &
    entries_excluding_lower_bound()
    {
      // Each of them has a check "> bound" below, after its declaration.
      static const std::vector<std::string> names = {
        "Plate/Thickness",
        "Plate/Young's modulus",
        "Foundation/Young's modulus",
        "Contact/Tolerance"};
      return names;
    }

    const std::vector<std::string> &
    fibre_stress_names()
    {
      static const std::vector<std::string> names = {"sxx_bottom",
                                                     "syy_bottom",
                                                     "sxy_bottom",
                                                     "s1_bottom",
                                                     "sxx_top",
                                                     "syy_top",
                                                     "sxy_top",
                                                     "s1_top"};
      return names;
    }

    void
    Temperature::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Temperature");
      prm.declare_entry("Expansion coefficient",
                        "1e-5",
                        Patterns::Double(0),
                        "Coefficient of thermal expansion alpha of the plate "
                        "[1/K], >= 0.");
      prm.declare_entry("Difference",
                        "0",
                        Patterns::Double(),
                        "T_top - T_bottom [K], linear through the thickness: "
                        "> 0 a warmer top (day; the plate curls its edges "
                        "down), < 0 a cooler top (night; corners and edges "
                        "lift).");
      prm.declare_entry("Profile",
                        "",
                        Patterns::Anything(),
                        "Optional: temperatures [K] at equally spaced depths "
                        "from the top to the bottom face, at least two, "
                        "comma separated, linear between them; overrides "
                        "Difference. Its mean expands the plate freely, its "
                        "equivalent linear part curls it, its remainder "
                        "stresses the fibres only.");
      prm.leave_subsection();
    }

    void
    Temperature::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Temperature");
      expansion_coefficient = prm.get_double("Expansion coefficient");
      difference            = prm.get_double("Difference");
      const auto items      = parse_number_list(prm.get("Profile"),
                                           0,
                                           "Temperature/Profile",
                                           "temperatures top to bottom");
      prm.leave_subsection();
      require(std::isfinite(expansion_coefficient) &&
                expansion_coefficient >= 0,
              "Temperature/Expansion coefficient must be >= 0" +
                got(expansion_coefficient) + ".");
      require(std::isfinite(difference),
              "Temperature/Difference must be a finite number" +
                got(difference) + ".");
      require(items.size() <= 1,
              "Temperature/Profile takes one list of temperatures, top to "
              "bottom, separated by commas (not ';').");
      profile = items.empty() ? std::vector<double>() : items[0];
      require(profile.empty() || profile.size() >= 2,
              "Temperature/Profile needs at least two temperatures (top and "
              "bottom face), separated by commas; got " +
                std::to_string(profile.size()) + ".");
      // The plate's theory is one of small strains: a thermal strain of
      // 10 % is a units slip (doc/errors-and-limits.md, "Dense liquid and
      // temperature"); larger ones overflowed into the loads' checks.
      const auto strain_check = [&](const std::string &entry,
                                    const double       temperature) {
        const double strain = expansion_coefficient * std::abs(temperature);
        require(strain <= 0.1,
                entry +
                  ": the thermal strain (Temperature/Expansion "
                  "coefficient times the temperature difference " +
                  to_text(temperature) + ") reaches " + to_text(strain) +
                  ", beyond the 0.1 the plate's small strains allow; check "
                  "the units of the temperatures [K] and of the expansion "
                  "coefficient [1/K].");
      };
      // The profile's mean only expands the plate freely (absolute
      // temperatures in K are fine): its strains are the differences from
      // the mean, summed as T_i / n so that no sum overflows.
      if (profile.empty())
        strain_check("Temperature/Difference", difference);
      double mean = 0;
      for (const double temperature : profile)
        mean += temperature / profile.size();
      for (const double temperature : profile)
        strain_check("Temperature/Profile", temperature - mean);
    }

    void
    FoundationOperator::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Foundation operator");
      prm.declare_entry("Storage",
                        "auto",
                        Patterns::Selection("auto|dense|hierarchical|fft"),
                        "How the half-space block is stored: dense (LAPACK), "
                        "hierarchical (an H-matrix of hmat-oss, compressed "
                        "to Tolerance), fft (the kernel split into a sparse "
                        "near field and a smooth far field applied by the "
                        "FFT, accurate to Tolerance; the homogeneous "
                        "half-space only); hierarchical and fft need "
                        "Contact/Solver = iterative or "
                        "auto, Flexibility = galerkin and, on a tensionless "
                        "foundation, Contact/Method = active set; or auto: "
                        "in the cycles with at least Hierarchical from "
                        "foundation nodes where the scene allows it (the "
                        "conditions above, Contact/Solver not direct) fft "
                        "for the homogeneous half-space on a mesh of "
                        "cells of similar size (on any number of "
                        "processes), hierarchical for a layered soil, on "
                        "graded meshes or where fft does not fit the "
                        "memory; dense otherwise.");
      prm.declare_entry(
        "Tolerance",
        "1e-6",
        Patterns::Double(0, 1),
        "Relative accuracy of the compressed blocks "
        "(Storage = hierarchical), of the split kernel's "
        "far field and cutoff (Storage = fft), and of a goal estimate's "
        "compressed settlement on large meshes (any "
        "storage); the H-Cholesky factor, which only "
        "preconditions, is recompressed at the larger of "
        "this and 1e-3. With those storages the iterative "
        "contact solver's last solve stops at a hundredth "
        "of it (at 1e-10 if that is larger).");
      prm.declare_entry("Hierarchical from",
                        "3000",
                        Patterns::Integer(0),
                        "Storage = auto: the number of foundation nodes from "
                        "which a cycle uses a compressed operator, fft or "
                        "hierarchical (below it the dense one, exact and "
                        "fast enough; doc/performance.md has the "
                        "measurements).");
      prm.leave_subsection();
    }

    void
    FoundationOperator::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Foundation operator");
      const std::string name = prm.get("Storage");
      storage                = (name == "dense"        ? Storage::dense :
                                name == "hierarchical" ? Storage::hierarchical :
                                name == "fft"          ? Storage::fft :
                                                         Storage::automatic);
      tolerance              = prm.get_double("Tolerance");
      hierarchical_from      = prm.get_integer("Hierarchical from");
      prm.leave_subsection();
      // The compressed blocks are checked against the exactly integrated
      // ones in double precision, which resolves about 1e-16: a finer
      // tolerance can never pass that check (doc/errors-and-limits.md).
      require(tolerance >= 1e-14,
              "Foundation operator/Tolerance must lie in [1e-14, 1]" +
                got(tolerance) +
                ": double precision resolves no finer. For the exactly "
                "integrated flexibility use Foundation operator/Storage = "
                "dense.");
    }

    void
    Loads::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads");
      prm.declare_entry("Uniform pressure",
                        "0",
                        Patterns::Double(),
                        "Pressure on the whole plate, downward positive "
                        "[force/length^2].");
      prm.declare_entry("Rectangular patches",
                        "",
                        Patterns::Anything(),
                        "Rectangular pressure patches x1,y1,x2,y2,pressure ; "
                        "... (x1<x2, y1<y2; downward positive; integrated "
                        "exactly over the covered part of each cell).");
      prm.declare_entry("Circular patches",
                        "",
                        Patterns::Anything(),
                        "Circular pressure patches xc,yc,radius,pressure ; "
                        "... (radius > 0; downward positive).");
      prm.declare_entry("Point loads",
                        "",
                        Patterns::Anything(),
                        "Point loads x,y,force ; ... (downward positive, the "
                        "point must lie on the plate).");
      prm.declare_entry(
        "Axles",
        "",
        Patterns::Anything(),
        "Axle groups and aircraft main gears type,x,y,angle,load,tyre "
        "pressure ; ...: type one of " +
          boost::algorithm::join(AxleGroup::type_names(), " | ") +
          " (tyre layouts in metres, doc/parameters.md), (x,y) the group's "
          "centre, angle [degrees] from the x axis to the direction of "
          "travel, load the group's total load and the tyre pressure (both > "
          "0). Each tyre is a circular patch of area load/(tyres * "
          "pressure).");
      prm.declare_entry(
        "Sweep",
        "",
        Patterns::Anything(),
        "x1,y1,x2,y2,steps: after the last cycle, move every axle group by "
        "the offsets from (x1,y1) to (x2,y2) in steps >= 2 equal steps on "
        "the last mesh and report the envelope (sweep.csv, summary.json "
        "\"sweep\"); empty: no sweep. Needs Loads/Axles.");
      for (const LoadKind &kind : registered_load_kinds())
        kind.declare_parameters(prm);
      prm.leave_subsection();
    }

    Point<2>
    Loads::sweep_position(const unsigned int step) const
    {
      return sweep_start +
             (sweep_end - sweep_start) *
               (sweep_steps > 1 ? step / double(sweep_steps - 1) : 0.);
    }

    Loads
    Loads::with_axles_moved(const Tensor<1, 2> &offset) const
    {
      Loads        moved   = *this;
      unsigned int n_tyres = 0;
      for (const AxleGroup &group : axles)
        n_tyres += AxleGroup::tyre_layout(group.type).size();
      moved.circular_patches.resize(circular_patches.size() - n_tyres);
      for (unsigned int g = 0; g < axles.size(); ++g)
        {
          moved.axles[g].centre += offset;
          for (const CircularPatch &tyre : moved.axles[g].tyre_patches(g + 1))
            moved.circular_patches.push_back(tyre);
        }
      return moved;
    }

    void
    Loads::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Loads");
      uniform_pressure = prm.get_double("Uniform pressure");
      rectangular_patches.clear();
      for (const auto &v : parse_number_list(prm.get("Rectangular patches"),
                                             5,
                                             "Loads/Rectangular patches",
                                             "x1,y1,x2,y2,pressure"))
        {
          require(v[0] < v[2] && v[1] < v[3],
                  "Loads/Rectangular patches: each patch x1,y1,x2,y2,pressure "
                  "needs x1 < x2 and y1 < y2 (patch " +
                    std::to_string(rectangular_patches.size() + 1) + ").");
          rectangular_patches.push_back(
            {Point<2>(v[0], v[1]), Point<2>(v[2], v[3]), v[4]});
        }
      circular_patches.clear();
      for (const auto &v : parse_number_list(prm.get("Circular patches"),
                                             4,
                                             "Loads/Circular patches",
                                             "xc,yc,radius,pressure"))
        {
          require(v[2] > 0,
                  "Loads/Circular patches: the radius must be > 0" + got(v[2]) +
                    ".");
          circular_patches.push_back(
            {Point<2>(v[0], v[1]),
             v[2],
             v[3],
             "Loads/Circular patches: patch " +
               std::to_string(circular_patches.size() + 1)});
        }
      point_loads.clear();
      for (const auto &v : parse_number_list(
             prm.get("Point loads"), 3, "Loads/Point loads", "x,y,force"))
        point_loads.push_back({Point<2>(v[0], v[1]), v[2]});
      axles.clear();
      for (const std::string &item :
           list_items(prm.get("Axles"), "Loads/Axles"))
        {
          const std::vector<std::string> fields =
            item_fields(item, "Loads/Axles");
          require(fields.size() == 6,
                  "Entry <Loads/Axles>: the item <" + item +
                    "> must have 6 fields (type,x,y,angle,load,tyre "
                    "pressure).");
          const auto &names = AxleGroup::type_names();
          const auto  found = std::find(names.begin(), names.end(), fields[0]);
          require(found != names.end(),
                  "Loads/Axles: the type <" + fields[0] + "> must be one of " +
                    boost::algorithm::join(names, ", ") + ".");
          const std::vector<std::vector<double>> numbers = parse_number_list(
            boost::algorithm::join(
              std::vector<std::string>(fields.begin() + 1, fields.end()), ","),
            5,
            "Loads/Axles",
            "x,y,angle,load,tyre pressure");
          const std::vector<double> &v = numbers[0];
          AxleGroup                  group;
          group.type =
            static_cast<AxleGroup::Type>(std::distance(names.begin(), found));
          group.centre        = Point<2>(v[0], v[1]);
          group.angle         = v[2];
          group.load          = v[3];
          group.tyre_pressure = v[4];
          std::ostringstream values;
          values << " (got " << group.load << " and " << group.tyre_pressure
                 << ").";
          require(group.load > 0 && group.tyre_pressure > 0,
                  "Loads/Axles: the load and the tyre pressure of group " +
                    std::to_string(axles.size() + 1) + " must be > 0" +
                    values.str());
          axles.push_back(group);
          for (const CircularPatch &tyre : group.tyre_patches(axles.size()))
            circular_patches.push_back(tyre);
        }
      sweep_steps      = 0;
      const auto sweep = parse_number_list(prm.get("Sweep"),
                                           5,
                                           "Loads/Sweep",
                                           "x1,y1,x2,y2,steps");
      registered_kinds.clear();
      for (const LoadKind &kind : registered_load_kinds())
        for (auto &load : kind.parse_parameters(prm))
          registered_kinds.push_back(std::move(load));
      prm.leave_subsection();
      require(sweep.size() <= 1,
              "Loads/Sweep takes one path x1,y1,x2,y2,steps (got " +
                std::to_string(sweep.size()) + ").");
      if (sweep.size() == 1)
        {
          const std::vector<double> &v = sweep[0];
          require(v[4] == std::floor(v[4]) && v[4] >= 2 && v[4] <= 1000,
                  "Loads/Sweep: steps must be a whole number in [2, 1000]" +
                    got(v[4]) + ".");
          require(!axles.empty(),
                  "Loads/Sweep moves the axle groups: set Loads/Axles.");
          sweep_start = Point<2>(v[0], v[1]);
          sweep_end   = Point<2>(v[2], v[3]);
          sweep_steps = static_cast<unsigned int>(v[4]);
        }
    }

    void
    Discretization::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Discretization");
      prm.declare_entry("Element",
                        "heterosis",
                        Patterns::Selection("serendipity|heterosis|lagrange"),
                        "heterosis (default): w serendipity, rotations Q2, "
                        "free of shear locking; serendipity: the paper's "
                        "8-node element (Q2 with constrained centre), locks "
                        "when the cells are much larger than the thickness; "
                        "lagrange: all Q2.");
      prm.declare_entry("Shear integration",
                        "auto",
                        Patterns::Selection("auto|reduced|selective|full"),
                        "auto: follows the Element (serendipity: reduced, "
                        "heterosis and lagrange: selective); reduced: "
                        "bending and shear 2x2 Gauss (the paper's practice, "
                        "serendipity only); selective: bending 3x3, shear "
                        "2x2; full: both 3x3 (locks for thin plates).");
      prm.declare_entry("Subdivisions x",
                        "10",
                        Patterns::Integer(1, 1000),
                        "Shape = rectangle: initial cells along x; Shape = "
                        "slabs: along x in each slab.");
      prm.declare_entry("Subdivisions y",
                        "10",
                        Patterns::Integer(1, 1000),
                        "Shape = rectangle: initial cells along y; Shape = "
                        "slabs: along y in each slab.");
      prm.declare_entry("Initial refinements",
                        "0",
                        Patterns::Integer(0, 10),
                        "Global refinements of the initial mesh.");
      prm.declare_entry("Flexibility",
                        "galerkin",
                        Patterns::Selection("galerkin|collocation"),
                        "galerkin: symmetric Galerkin half-space operator "
                        "(default); collocation: the paper's nodal "
                        "flexibility matrix G (needs axis-aligned "
                        "rectangular cells).");
      prm.declare_entry("Symmetry",
                        "auto",
                        Patterns::Selection("auto|none|x|y|xy"),
                        "Mirror planes x = 0 and/or y = 0 to exploit: a "
                        "scene whose mesh and loads are mirror symmetric is "
                        "solved on the half or quarter plate, with the "
                        "mirror images in the half-space kernel (the same "
                        "answer, a 4x or 16x smaller dense block). auto: "
                        "the planes the scene has; x, y, xy: insist (an "
                        "error if the scene is not symmetric); none: the "
                        "whole plate.");
      prm.declare_entry("Singular quadrature order",
                        "8",
                        Patterns::Integer(4, 30),
                        "galerkin: Gauss points per direction of the Duffy "
                        "rules for coincident and touching cell pairs.");
      prm.leave_subsection();
    }

    Discretization::ShearIntegration
    Discretization::shear_integration_for(const Element element)
    {
      // doc/formulation.md, "Plate": serendipity keeps the paper's reduced
      // rule; heterosis and lagrange have spurious rotation modes with it,
      // and selective is their locking-free rule.
      return element == Element::serendipity ? ShearIntegration::reduced :
                                               ShearIntegration::selective;
    }

    void
    Discretization::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Discretization");
      const std::string e = prm.get("Element");
      element             = (e == "serendipity" ? Element::serendipity :
                             e == "heterosis"   ? Element::heterosis :
                                                  Element::lagrange);
      const std::string s = prm.get("Shear integration");
      shear_integration   = (s == "auto"      ? shear_integration_for(element) :
                             s == "reduced"   ? ShearIntegration::reduced :
                             s == "selective" ? ShearIntegration::selective :
                                                ShearIntegration::full);
      subdivisions_x      = prm.get_integer("Subdivisions x");
      subdivisions_y      = prm.get_integer("Subdivisions y");
      initial_refinements = prm.get_integer("Initial refinements");
      flexibility =
        (prm.get("Flexibility") == "galerkin" ? Flexibility::galerkin :
                                                Flexibility::collocation);
      symmetry = prm.get("Symmetry");
      // tests/unit/plate_zero_energy_modes.cc: these two choices have three
      // spurious pure-rotation modes that survive assembly and that the
      // foundation (acting on w only) cannot restrain.
      require(shear_integration != ShearIntegration::reduced ||
                element == Element::serendipity,
              "Discretization/Shear integration = reduced is only stable "
              "with Element = serendipity; heterosis and lagrange have "
              "spurious rotation modes with it (use selective or full).");
      singular_quadrature_order = prm.get_integer("Singular quadrature order");
      prm.leave_subsection();
    }

    void
    Contact::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      prm.declare_entry("Method",
                        "active set",
                        Patterns::Selection("active set|element exclusion"),
                        "Tensionless contact algorithm: active set (exact "
                        "discrete complementarity) or element exclusion (the "
                        "paper's heuristic).");
      prm.declare_entry("Max iterations",
                        "100",
                        Patterns::Integer(1, 100000),
                        "Maximum contact iterations per cycle.");
      prm.declare_entry("Tolerance",
                        "1e-8",
                        Patterns::Double(0, 1),
                        "element exclusion: relative change of the "
                        "displacement norm that ends the iteration.");
      prm.declare_entry(
        "Solver",
        "auto",
        Patterns::Selection("auto|direct|iterative"),
        "How each contact set is solved: auto (iterative with a "
        "compressed half-space operator, hierarchical or fft, direct with a dense one; with "
        "Foundation operator/Storage = auto also direct with a dense one "
        "for a plate so much more flexible than the soil that rounding "
        "would leave the iterated pressures less accurate than 1e-6, and "
        "where the iterations fail, from that cycle on), direct "
        "(the plate condensed onto "
        "the foundation nodes into a dense matrix, factorised by LAPACK) or "
        "iterative (conjugate gradients on the contact pressures with the "
        "sparse plate stiffness and the half-space preconditioned by its "
        "inverse; no dense coupled matrix; needs Discretization/Flexibility "
        "= galerkin and Contact/Method = active set; coupled_matrix_rcond "
        "is not estimated and reads 1; see Contact/Preconditioner).");
      prm.declare_entry(
        "Constrained start",
        "true",
        Patterns::Bool(),
        "Iterative solver, tensionless: start the active set from the "
        "contact set that constrained conjugate gradients estimate (the set "
        "changes inside one CG loop: tensile nodes leave, penetrating ones "
        "join), which the active set then checks and corrects; false: from "
        "the previous cycle's set (or all nodes), one solve per set. The "
        "answer is the same; the active-set steps and the time differ.");
      prm.declare_entry(
        "Nested start",
        "auto",
        Patterns::Selection("auto|true|false"),
        "Tensionless: seed the first cycle's contact set and pressure with "
        "the same scene solved first on the mesh one refinement coarser "
        "(every cell coarsened once, nested again while its mesh allows; "
        "needs Discretization/Initial refinements of at least 1, 2 with "
        "Adaptivity/Refinement = goal, and one process). The coarse solve "
        "finds where the plate lifts off for about a quarter of the cost, "
        "so the fine one only corrects its boundary. auto: from 20000 "
        "foundation nodes on. The answer is the same; the active-set "
        "steps and the time differ (doc/formulation.md, \"Nested "
        "start\").");
      prm.declare_entry(
        "Preconditioner",
        "auto",
        Patterns::Selection("auto|soil inverse|plate on springs"),
        "Iterative solver: the preconditioner of the conjugate gradients on "
        "the contact pressures. soil inverse: the half-space operator's "
        "approximate inverse (suits a plate stiffer than the soil over its "
        "size); plate on springs: the plate's sparse stiffness with the "
        "soil as independent springs, factorised once per contact set "
        "(suits a plate whose radius of relative stiffness is not much "
        "larger than the cells); auto: the one whose spectral estimate "
        "from the radius of relative stiffness, the smallest cell and the "
        "plate's diameter is smaller (doc/formulation.md, "
        "\"Preconditioning the contact pressures\"). The answer is the "
        "same; the iterations and the time differ.");
      prm.leave_subsection();
    }

    void
    Contact::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Contact");
      method         = (prm.get("Method") == "active set" ? Method::active_set :
                                                            Method::element_exclusion);
      max_iterations = prm.get_integer("Max iterations");
      tolerance      = prm.get_double("Tolerance");
      const std::string name   = prm.get("Solver");
      solver                   = (name == "iterative" ? Solver::iterative :
                                  name == "direct"    ? Solver::direct :
                                                        Solver::automatic);
      constrained_start        = prm.get_bool("Constrained start");
      const std::string nested = prm.get("Nested start");
      nested_start             = (nested == "true"  ? NestedStart::on :
                                  nested == "false" ? NestedStart::off :
                                                      NestedStart::automatic);
      const std::string p      = prm.get("Preconditioner");
      preconditioner =
        (p == "soil inverse"     ? Preconditioner::soil_inverse :
         p == "plate on springs" ? Preconditioner::plate_on_springs :
                                   Preconditioner::automatic);
      prm.leave_subsection();
      require(tolerance > 0,
              "Contact/Tolerance must lie in (0, 1]" + got(tolerance) + ".");
    }

    void
    Adaptivity::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptivity");
      prm.declare_entry("Cycles",
                        "1",
                        Patterns::Integer(1, 30),
                        "Number of solve/refine cycles; 1 solves once on the "
                        "initial mesh.");
      prm.declare_entry("Refinement",
                        "adaptive",
                        Patterns::Selection("global|adaptive|goal"),
                        "global: refine every cell; adaptive: Kelly "
                        "indicator plus plate edge and contact boundary; "
                        "goal: the cell-wise dual-weighted residual "
                        "estimate of the error in Goal.");
      prm.declare_entry("Goal",
                        "",
                        Patterns::Anything(),
                        "Quantity of interest whose error every cycle "
                        "estimates: w|Mx|My|Mxy|q at x,y ; peak Mx|My|M1 ; "
                        "contact area ; mean w ; w at x1,y1 minus x2,y2. "
                        "Empty: no estimate.");
      prm.declare_entry("Target error",
                        "0",
                        Patterns::Double(0),
                        "Relative error of Goal to reach: cycling stops "
                        "once the estimate over |value| is below it; 0: "
                        "run all Cycles.");
      prm.declare_entry("Refine fraction",
                        "0.3",
                        Patterns::Double(0, 1),
                        "Adaptive: fraction of cells refined per cycle.");
      prm.declare_entry("Coarsen fraction",
                        "0",
                        Patterns::Double(0, 1),
                        "Adaptive: fraction of cells coarsened per cycle.");
      prm.declare_entry("Max cells",
                        "20000",
                        Patterns::Integer(1),
                        "Refinement stops before the mesh exceeds this many "
                        "cells (the dense foundation block grows with the "
                        "square of the node count).");
      prm.leave_subsection();
    }

    void
    Adaptivity::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Adaptivity");
      cycles              = prm.get_integer("Cycles");
      const std::string r = prm.get("Refinement");
      refinement          = (r == "adaptive" ? Refinement::adaptive :
                             r == "goal"     ? Refinement::goal :
                                               Refinement::global);
      goal                = Goal::parse(prm.get("Goal"));
      target_error        = prm.get_double("Target error");
      refine_fraction     = prm.get_double("Refine fraction");
      coarsen_fraction    = prm.get_double("Coarsen fraction");
      max_cells           = prm.get_integer("Max cells");
      prm.leave_subsection();
      require(refine_fraction + coarsen_fraction <= 1,
              "Adaptivity/Refine fraction + Adaptivity/Coarsen fraction must "
              "not exceed 1.");
      require(goal.functional || refinement != Refinement::goal,
              "Adaptivity/Refinement = goal needs Adaptivity/Goal (the "
              "quantity whose error refinement reduces).");
      require(refinement != Refinement::goal || !goal.functional ||
                goal.functional->estimate() !=
                  GoalFunctional::Estimate::change_only,
              "Adaptivity/Refinement = goal cannot refine for Goal = " +
                goal.text + ": " +
                (goal.functional ? goal.functional->no_estimate_reason() :
                                   std::string()) +
                "; use Refinement = adaptive or global.");
      require(goal.functional || target_error == 0,
              "Adaptivity/Target error needs Adaptivity/Goal (the quantity "
              "the target refers to).");
      require(target_error < 1,
              "Adaptivity/Target error is relative and must lie in [0, 1)" +
                got(target_error) + ".");
      // met only once the changes are seen to shrink (add_goal_results())
      require(target_error == 0 || cycles >= 3,
              "Adaptivity/Target error needs Adaptivity/Cycles >= 3 (got " +
                std::to_string(cycles) +
                "): a target is met only once the changes of the goal "
                "between cycles are seen to shrink, which the third cycle "
                "shows first. Raise Cycles, or set Target error = 0 and read "
                "the reported error (summary.json's relative_error).");
    }

    Goal
    Goal::parse(const std::string &entry)
    {
      // The goal kinds parse their own syntax (refinement/goals/).
      Goal goal;
      goal.text       = Utilities::trim(entry);
      goal.functional = create_goal(entry);
      return goal;
    }

    void
    Output::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      prm.declare_entry("Probe points",
                        "",
                        Patterns::Anything(),
                        "Points x,y ; ... where w, q, Mx, My are reported in "
                        "summary.json (each must lie on the plate).");
      prm.declare_entry("Profile",
                        "",
                        Patterns::Anything(),
                        "Line x1,y1,x2,y2,points for profile-NN.csv; empty: "
                        "the centre line y = 0 across the plate with 241 "
                        "points.");
      prm.declare_entry("VTU",
                        "true",
                        Patterns::Bool(),
                        "Write solution-NN.vtu and solution.pvd.");
      prm.declare_entry("Verbosity",
                        "1",
                        Patterns::Integer(0, 2),
                        "0: only checks and errors; 1: a line per cycle and "
                        "contact iteration; 2: also timings (not for tests).");
      prm.leave_subsection();
    }

    void
    Output::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Output");
      probe_points.clear();
      for (const auto &v : parse_number_list(
             prm.get("Probe points"), 2, "Output/Probe points", "x,y"))
        probe_points.emplace_back(v[0], v[1]);
      const auto profile = parse_number_list(prm.get("Profile"),
                                             5,
                                             "Output/Profile",
                                             "x1,y1,x2,y2,points");
      require(profile.size() <= 1,
              "Output/Profile takes one line x1,y1,x2,y2,points.");
      default_profile = profile.empty();
      if (!default_profile)
        {
          const auto &v = profile[0];
          profile_start = Point<2>(v[0], v[1]);
          profile_end   = Point<2>(v[2], v[3]);
          require(v[4] >= 2 && v[4] <= 1e6 && v[4] == std::floor(v[4]),
                  "Output/Profile: the number of points must be an integer "
                  "in [2, 1e6].");
          profile_points = static_cast<unsigned int>(v[4]);
          require(profile_start.distance(profile_end) > 0,
                  "Output/Profile: the line must have two distinct end "
                  "points.");
        }
      else
        profile_points = 241;
      vtu       = prm.get_bool("VTU");
      verbosity = prm.get_integer("Verbosity");
      prm.leave_subsection();
    }

    void
    Verification::declare_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Verification");
      prm.declare_entry(
        "Checks",
        "",
        Patterns::Anything(),
        "Values the run must reproduce, checked after the last cycle: "
        "'quantity,x,y,reference,relative tolerance' for w|q|Mx|My|"
        "sxx_bottom|...|s1_top at a point, or 'key,reference,relative "
        "tolerance' for a number of the last cycle in summary.json (e.g. "
        "max_w, contact_force, n_dofs, goal.value: every number and count "
        "that plate-on-halfspace --print-results lists under cycles and "
        "cycles.goal); items separated by ';'. A failed check makes the "
        "program exit with status 1.");
      prm.leave_subsection();
    }

    void
    Verification::parse_parameters(ParameterHandler &prm)
    {
      prm.enter_subsection("Verification");
      const std::string text = prm.get("Checks");
      prm.leave_subsection();
      checks.clear();
      for (const std::string &item : list_items(text, "Verification/Checks"))
        {
          std::vector<std::string> fields =
            item_fields(item, "Verification/Checks");
          require(fields.size() == 5 || fields.size() == 3,
                  "Verification/Checks: <" + item +
                    "> must be 'quantity,x,y,reference,tolerance' or "
                    "'key,reference,tolerance'.");
          const std::string quantity = fields[0];
          fields.erase(fields.begin());
          std::string rest;
          for (const std::string &f : fields)
            rest += (rest.empty() ? "" : ",") + f;
          const auto  numbers = parse_number_list(rest,
                                                 fields.size(),
                                                 "Verification/Checks",
                                                 "numbers after the quantity");
          const auto &v       = numbers[0];
          Check       check;
          check.quantity = quantity;
          check.at_point = (v.size() == 4);
          if (check.at_point)
            {
              std::vector<std::string> names = {"w", "q", "Mx", "My"};
              names.insert(names.end(),
                           fibre_stress_names().begin(),
                           fibre_stress_names().end());
              require(std::find(names.begin(), names.end(), quantity) !=
                        names.end(),
                      "Verification/Checks: point quantity <" + quantity +
                        "> must be one of w, q, Mx, My, sxx_bottom, "
                        "syy_bottom, sxy_bottom, s1_bottom, sxx_top, syy_top, "
                        "sxy_top, s1_top.");
              check.location = Point<2>(v[0], v[1]);
            }
          else
            {
              const std::vector<std::string> keys = checkable_result_keys();
              require(std::find(keys.begin(), keys.end(), quantity) !=
                        keys.end(),
                      "Verification/Checks: summary key <" + quantity +
                        "> is not a number of a cycle in summary.json (e.g. "
                        "max_w, contact_force, n_dofs, goal.value; "
                        "plate-on-halfspace --print-results lists them).");
            }
          check.reference          = v[v.size() - 2];
          check.relative_tolerance = v[v.size() - 1];
          require(check.relative_tolerance > 0,
                  "Verification/Checks: the tolerance of <" + item +
                    "> must be > 0.");
          checks.push_back(check);
        }
    }
  } // namespace Parameters
} // namespace PlateOnHalfspace
