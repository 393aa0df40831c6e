/**
 * The scene: every entry of the parameter file (doc/parameters.md), one struct
 * per subsection, each with declare_parameters() and parse_parameters() (the
 * code-gallery step-44 pattern). Cross-entry checks happen in
 * parse_parameters() and throw an ExcMessage that names the entry and the
 * allowed range.
 *
 * Units: any consistent set (kN, m, kPa in the shipped scenes). Loads and
 * deflections are positive downward (doc/formulation.md, "Conventions").
 */
#ifndef plate_on_halfspace_scene_parameters_h
#define plate_on_halfspace_scene_parameters_h

#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/point.h>

#include <plate_on_halfspace/loads/load.h>
#include <plate_on_halfspace/scene/axles.h>

#include <memory>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  class GoalFunctional;

  using namespace dealii;

  namespace Parameters
  {
    /** subsection Plate: geometry and material of the plate. */
    struct Plate
    {
      enum class Shape
      {
        rectangle,
        disk,
        mesh_file,
        slabs
      };
      Shape  shape;
      double length_x, length_y; ///< rectangle spans [-L/2, L/2]
      /** Shape = slabs: the slab sizes along x and along y; the grid of
       *  slabs is centred at the origin, joints lie between them. */
      std::vector<double> slab_lengths_x, slab_lengths_y;
      double              radius;    ///< disk centred at the origin
      std::string         mesh_file; ///< Gmsh .msh with quadrilaterals
      double              thickness;
      double              youngs_modulus;
      double              poissons_ratio;
      double unit_weight; ///< self weight = unit weight * thickness

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);

      /** Flexural rigidity D = E t^3 / (12 (1 - nu^2)). */
      double
      flexural_rigidity() const;
    };

    /**
     * subsection Foundation: the soil under the plate, an elastic half-space
     * or a dense liquid (doc/formulation.md, "Dense-liquid foundation").
     */
    struct Foundation
    {
      enum class Model
      {
        half_space,   ///< Boussinesq: E0, nu0
        dense_liquid, ///< Winkler: q = k w where the soil carries the plate
        layered       ///< elastic layers over a half-space or a rigid base
      };
      /** One of Layers: thickness [length], E [force/length^2], nu. */
      struct Layer
      {
        double thickness, youngs_modulus, poissons_ratio;
      };
      Model  model;
      double youngs_modulus;     ///< half-space E0 (layered: under the layers)
      double poissons_ratio;     ///< half-space nu0
      double subgrade_modulus;   ///< dense liquid k [force/length^3]
      bool   tensionless;        ///< Contact = tensionless (true) or bonded
      std::vector<Layer> layers; ///< Model = layered: top down
      bool               rigid_base; ///< Base = rigid (layered)
      bool frictionless_interfaces;  ///< Interfaces = frictionless (layered)

      /** The checks of Layers with Model = layered. */
      void
      check_layers() const;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** subsection Foundation operator: how the half-space is stored. */
    struct FoundationOperator
    {
      enum class Storage
      {
        dense,        ///< every entry (LAPACK)
        hierarchical, ///< an H-matrix (hmat-oss)
        automatic,    ///< compressed from Hierarchical from nodes
        sparse,       ///< the dense liquid's mass matrix (never an entry)
        fft           ///< split kernel: sparse near field, FFT far field
      };
      /** Whether @p s compresses the flexibility (hierarchical, fft): no
       *  direct solver, and Contact/Solver = auto's flexible-plate
       *  fallbacks apply (doc/parameters.md). */
      static bool
      compressed(const Storage s)
      {
        return s == Storage::hierarchical || s == Storage::fft;
      }

      Storage storage;
      double  tolerance;
      /** Storage = auto: compressed from this many foundation nodes. */
      unsigned int hierarchical_from;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * subsection Temperature: the plate's temperature through its thickness
     * (doc/formulation.md, "Temperature"), linear (Difference) or a profile.
     */
    struct Temperature
    {
      double expansion_coefficient; ///< alpha [1/K]
      double difference;            ///< T_top - T_bottom [K], linear
      /** Temperatures [K] at equally spaced depths, top to bottom (at least
       *  two); empty: the linear Difference. */
      std::vector<double> profile;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * subsection Joints: the load transfer between the slabs of Plate/
     * Shape = slabs (doc/formulation.md, "Joints"). Transverse joints lie
     * across the direction of travel x (lines x = const), longitudinal
     * joints along it (lines y = const).
     */
    struct Joints
    {
      enum class LoadTransfer
      {
        free,                ///< no connection: two free edges
        aggregate_interlock, ///< distributed shear spring
        dowels,              ///< discrete shear springs (dowel bars)
        tied                 ///< continuous in w and the rotations
      };
      LoadTransfer transverse;      ///< Load transfer
      LoadTransfer longitudinal;    ///< Longitudinal load transfer, resolved
      double       shear_stiffness; ///< aggregate interlock [force/length^2]
      double       dowel_diameter, dowel_spacing, dowel_modulus, joint_opening;
      double dowel_support_modulus; ///< K of the concrete [force/length^3]

      /** The range checks of the entries the joints use, and their bounds
       *  against the slabs of @p plate (the scene checks them for Plate/
       *  Shape = slabs only). */
      void
      check(const Plate &plate) const;

      /** The entry's text of @p transfer ("aggregate interlock", ...). */
      static std::string
      name(LoadTransfer transfer);

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** A rectangular load patch [x1,x2] x [y1,y2] with a pressure. */
    struct RectangularPatch
    {
      Point<2> lower, upper;
      double   pressure;
    };

    /** A circular load patch. */
    struct CircularPatch
    {
      Point<2> centre;
      double   radius;
      double   pressure;
      /** How messages name it, e.g. "Loads/Circular patches: patch 2". */
      std::string label;
    };

    /** A point load (force, downward positive). */
    struct PointLoad
    {
      Point<2> location;
      double   force;
    };

    /** subsection Loads. */
    struct Loads
    {
      double                        uniform_pressure;
      std::vector<RectangularPatch> rectangular_patches;
      /** The entry's patches, then one per tyre of the axle groups. */
      std::vector<CircularPatch> circular_patches;
      /** Loads/Axles as written (their tyres are in circular_patches). */
      std::vector<AxleGroup> axles;
      std::vector<PointLoad> point_loads;
      /** The loads of the kinds that declare their own entries
       *  (LoadKind, e.g. Loads/Pressure function). */
      LoadList registered_kinds;
      /** Loads/Sweep: the axles move along [sweep_start, sweep_end] in
       *  sweep_steps positions (0: no sweep). */
      Point<2>     sweep_start, sweep_end;
      unsigned int sweep_steps = 0;

      /** Position @p step of the sweep, the offset added to every axle. */
      Point<2>
      sweep_position(const unsigned int step) const;

      /** These loads with every axle group moved by @p offset (the other
       *  patches, point loads and pressures stay). */
      Loads
      with_axles_moved(const Tensor<1, 2> &offset) const;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** subsection Discretization. */
    struct Discretization
    {
      /** The plate element (doc/formulation.md, "Plate"). */
      enum class Element
      {
        serendipity, ///< w and rotations serendipity (the paper's element)
        heterosis,   ///< w serendipity, rotations biquadratic (default)
        lagrange     ///< w and rotations biquadratic
      };
      /**
       * Gauss rules of the bending and the shear term. The entry's value
       * auto is not among them: parse_parameters() resolves it with
       * shear_integration_for().
       */
      enum class ShearIntegration
      {
        reduced,   ///< bending and shear 2x2
        selective, ///< bending 3x3, shear 2x2
        full       ///< bending and shear 3x3
      };

      /**
       * What Shear integration = auto means for @p element: reduced for
       * serendipity (the paper's practice), selective for heterosis and
       * lagrange (reduced is refused with those).
       */
      static ShearIntegration
      shear_integration_for(Element element);

      enum class Flexibility
      {
        galerkin,
        collocation
      };
      Element element;
      /** Never auto: the entry's auto is resolved when it is parsed. */
      ShearIntegration shear_integration;
      unsigned int     subdivisions_x, subdivisions_y;
      unsigned int     initial_refinements;
      Flexibility      flexibility;
      std::string      symmetry;
      unsigned int     singular_quadrature_order;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** subsection Contact: the contact algorithm (tensionless contact). */
    struct Contact
    {
      enum class Method
      {
        active_set,
        element_exclusion
      };
      /** How each contact set's coupled problem is solved. */
      enum class Solver
      {
        direct,    ///< DirectContactSolver: dense condensed plate + LAPACK
        iterative, ///< IterativeContactSolver: sparse plate + CG
        automatic  ///< iterative with hierarchical storage, else direct
      };
      Method       method;
      unsigned int max_iterations;
      double       tolerance;
      Solver       solver;
      /** IterativeContactSolver: start from predict_contact_set(). */
      bool constrained_start = true;
      /** A tensionless first cycle seeded by the same scene solved on
       *  the mesh one refinement coarser (doc/formulation.md,
       *  "Nested start"). */
      enum class NestedStart
      {
        automatic, ///< from nested_start_nodes foundation nodes on
        on,
        off
      };
      NestedStart nested_start = NestedStart::automatic;
      /** Foundation nodes from which NestedStart::automatic applies. */
      static constexpr unsigned int nested_start_nodes = 20000;
      /** IterativeContactSolver: how the pressures are preconditioned
       *  (contact/pressure_preconditioner.h). */
      enum class Preconditioner
      {
        automatic,       ///< the smaller estimated condition number
        soil_inverse,    ///< the soil's approximate inverse
        plate_on_springs ///< the plate with the soil as springs
      };
      Preconditioner preconditioner = Preconditioner::automatic;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * The quantity of interest of Adaptivity/Goal (doc/formulation.md,
     * "Goal-oriented refinement"), e.g. "Mx at 0,0", "peak Mx",
     * "stress_bottom at 0,1.8", "peak stress_top",
     * "contact area", "mean w", "w at 0,0 minus 3,0".
     */
    struct Goal
    {
      std::string text; ///< the entry as written, for the outputs
      /** The goal it names (refinement/goal.h); null for none. */
      std::shared_ptr<const GoalFunctional> functional;

      /** Parse @p text; throws ExcMessage naming Adaptivity/Goal. */
      static Goal
      parse(const std::string &text);
    };

    /** subsection Adaptivity. */
    struct Adaptivity
    {
      /** How the mesh of the next cycle is made (refinement/interface.h). */
      enum class Refinement
      {
        global,   ///< every cell
        adaptive, ///< Kelly with the contact and load indicators
        goal      ///< the cell-wise dual-weighted residual of the Goal
      };
      unsigned int cycles;
      Refinement   refinement;
      Goal         goal;
      /** Relative target of the goal's error estimate; 0: none. */
      double       target_error;
      double       refine_fraction;
      double       coarsen_fraction;
      unsigned int max_cells;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /** subsection Output. */
    struct Output
    {
      std::vector<Point<2>> probe_points;
      bool                  default_profile;
      Point<2>              profile_start, profile_end;
      unsigned int          profile_points;
      bool                  vtu;
      unsigned int          verbosity;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    /**
     * The names of the fibre stresses at a point, as checks, VTU fields and
     * profile columns call them: sxx, syy, sxy and s1 (the largest
     * principal stress) of the bottom, then the same of the top
     * (doc/formulation.md, "Stresses").
     */
    const std::vector<std::string> &
    fibre_stress_names();

    /**
     * The entries (Section/Name) whose checks exclude their pattern's
     * lower bound: deal.II's patterns have inclusive bounds only, so
     * Plate/Thickness is declared >= 0 and checked > 0. Messages about
     * such an entry's pattern name the open bound (describe_pattern()).
     */
    const std::vector<std::string> &
    entries_excluding_lower_bound();

    /**
     * A value the run must reproduce: quantity at a probe point or a summary
     * value, a reference value and a relative tolerance. The program prints
     * the comparison and fails (non-zero exit) if it does not hold, so that a
     * scene file can serve as a verification test.
     */
    struct Check
    {
      std::string quantity; ///< w | q | Mx | My (at x,y) or a summary key
      Point<2>    location;
      bool        at_point;
      double      reference;
      double      relative_tolerance;
    };

    /** subsection Verification. */
    struct Verification
    {
      std::vector<Check> checks;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };
  } // namespace Parameters

  /**
   * The whole scene, as read from one parameter file.
   */
  struct SceneParameters
  {
    std::string output_directory;

    Parameters::Plate              plate;
    Parameters::Joints             joints;
    Parameters::Foundation         foundation;
    Parameters::FoundationOperator foundation_operator;
    Parameters::Temperature        temperature;
    Parameters::Loads              loads;
    Parameters::Discretization     discretization;
    Parameters::Contact            contact;
    Parameters::Adaptivity         adaptivity;
    Parameters::Output             output;
    Parameters::Verification       verification;

    /** What parse_parameters() chose for an entry the user left alone,
     *  for the log; empty if nothing. */
    std::string refinement_note;

    static void
    declare_parameters(ParameterHandler &prm);
    void
    parse_parameters(ParameterHandler &prm);

    /**
     * The storage of the foundation operator in a cycle with
     * @p n_foundation_nodes nodes: dense, hierarchical or fft for an
     * elastic soil (Foundation operator/Storage, with auto resolved: dense
     * below Hierarchical from, above it fft for the homogeneous
     * half-space, hierarchical otherwise), sparse for the dense liquid.
     * The same on any number of MPI processes.
     */
    Parameters::FoundationOperator::Storage
    foundation_storage(const unsigned int n_foundation_nodes) const;

    /** The contact solver of such a cycle: direct or iterative
     *  (Contact/Solver, with auto resolved; iterative unless the
     *  storage is dense). */
    Parameters::Contact::Solver
    contact_solver(const unsigned int n_foundation_nodes) const;


    /** Declare, read @p filename, parse and check. Throws on bad input. */
    void
    read(const std::string &filename);

    /** Declare, read the parameter text @p text, parse and check. */
    void
    read_from_string(const std::string &text);
  };
  /**
   * The loads of the scene's subsection Loads: Uniform pressure, the
   * patches, the axles' tyres, the point loads and the loads of the
   * registered kinds, and the plate's own weight as a uniform pressure
   * @p self_weight_pressure (none if zero).
   */
  LoadList
  make_loads(const Parameters::Loads &loads, const double self_weight_pressure);
} // namespace PlateOnHalfspace

#endif
