#include <deal.II/base/timer.h>

#include <deal.II/grid/grid_tools.h>

#include <deal.II/numerics/solution_transfer.h>

#include <plate_on_halfspace/base/error_on_every_rank.h>
#include <plate_on_halfspace/base/interruption.h>
#include <plate_on_halfspace/base/progress.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/base/tasks.h>
#include <plate_on_halfspace/contact/active_set.h>
#include <plate_on_halfspace/contact/iterative_solver.h>
#include <plate_on_halfspace/contact/pressure_preconditioner.h>
#include <plate_on_halfspace/halfspace/memory_guard.h>
#include <plate_on_halfspace/halfspace/split_kernel_operator.h>
#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/plate/load_checks.h>
#include <plate_on_halfspace/plate/plate_mesh.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>
#include <plate_on_halfspace/refinement/interface.h>
#include <plate_on_halfspace/scene/input_checks.h>

#ifdef __GLIBC__
#  include <malloc.h>
#endif

#include <cfloat>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <limits>
#include <map>
#include <new>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

namespace PlateOnHalfspace
{
  namespace
  {
    /** @p message without its final full stop, to stand in parentheses. */
    std::string
    without_final_period(std::string message)
    {
      if (!message.empty() && message.back() == '.')
        message.pop_back();
      return message;
    }

    /** A convergence.txt column of a count or a time of the record. */
    ConvergenceColumn
    column(const std::string &name,
           const std::string &key,
           const unsigned int precision,
           const std::string &meaning = "")
    {
      return {name,
              meaning.empty() ? "`" + key + "`" : meaning,
              [key](const ResultRecord &r, double &v) {
                v = r.number(key);
                return true;
              },
              precision};
    }

    // The driver's results: the mesh, the loads, the time split and the
    // foundation operator of each cycle (doc/outputs.md).
    const bool declared_mesh = declare_results(
      "cycles",
      10,
      {{{"cycle"}, "–", "0, 1, …", ResultKind::count},
       {{"n_cells"},
        "–",
        "active cells of the computed part",
        ResultKind::count},
       {{"n_dofs"},
        "–",
        "unconstrained degrees of freedom of the plate (w, β_x, β_y) on the "
        "computed part",
        ResultKind::count},
       {{"n_foundation_dofs"},
        "–",
        "foundation nodes (unconstrained w-DOFs) of the computed part: the "
        "size n of the half-space block",
        ResultKind::count}},
      {column("cycle", "cycle", 0),
       column("cells", "n_cells", 0),
       column("dofs", "n_dofs", 0),
       column("foundation dofs", "n_foundation_dofs", 0)});

    const bool declared_loads = declare_results(
      "cycles",
      20,
      {{{"applied_load"},
        "force",
        "total applied load of the whole plate (downward positive), the part "
        "of patches on the plate"},
       {{"load_integration_error"},
        "–",
        "the largest difference, over the loads, between a load integrated "
        "by its own rule and by 3 more Gauss points per direction on each "
        "quarter of each cell, relative to the integral of its \\|p\\| "
        "([loads.md](loads.md#pressure-function)); 0 without a `Pressure "
        "function` (the other loads are integrated exactly), rounding "
        "(≈ 1e-15) for a polynomial one"}});

    const bool declared_timing = declare_results(
      "cycles",
      50,
      {{{"wall_time_s"},
        "s",
        "wall time of the cycle (plate setup and nested start included)"},
       {{"nested_start_time_s"},
        "s",
        "the first cycle's nested start: the scene solved on the mesh one "
        "refinement coarser, and the refinement back with the plate's "
        "stiffness on the first mesh "
        "([formulation.md](formulation.md#nested-start)); 0 without it"},
       {{"assembly_time_s"},
        "s",
        "plate setup (DoFs, constraints, stiffness: with a nested start, "
        "the stiffness is in nested_start_time_s) and loads"},
       {{"foundation_time_s"},
        "s",
        "building the foundation operator; the sum of the next three"},
       {{"foundation_integration_time_s"}, "s", "integrating its entries"},
       {{"foundation_compression_time_s"},
        "s",
        "hierarchical storage: ACA+'s own algebra (0 for dense)"},
       {{"foundation_factorization_time_s"},
        "s",
        "the contact solver's factorisation of the flexibility: the "
        "iterative solver's preconditioner (`Contact/Preconditioner`: the "
        "H-Cholesky or dense Cholesky factor of the soil inverse or the "
        "fractional soil inverse's sparse factors, or every factorisation "
        "of the plate on springs), or the direct solver's "
        "first contact block F_CC"},
       {{"solve_time_s"},
        "s",
        "the contact solve without that factorisation: the plate's "
        "condensation (direct) or generalised inverse (iterative) and all "
        "contact iterations"},
       {{"output_time_s"}, "s", "evaluating and writing the results"}},
      {column("assembly [s]", "assembly_time_s", 3),
       column("foundation [s]", "foundation_time_s", 3),
       column("solve [s]", "solve_time_s", 3),
       column("output [s]", "output_time_s", 3),
       column("total [s]",
              "wall_time_s",
              3,
              "`wall_time_s`, the cycle's wall time")});

    const bool declared_foundation = declare_results(
      "cycles",
      60,
      {{{"foundation_storage"},
        "–",
        "`dense`, `hierarchical` or `fft` for the half-space (with "
        "`Storage = auto`, decided per cycle), `sparse` for the dense "
        "liquid",
        ResultKind::text},
       {{"foundation_memory_bytes"},
        "bytes",
        "memory held by the half-space operator's matrices and by the "
        "contact solver's factor of the flexibility, or of the plate on "
        "springs, with the iterative solver's recorded directions (on "
        "several processes: rank 0's share)",
        ResultKind::count},
       {{"foundation_nodes_per_rank"},
        "–",
        "the foundation nodes each MPI process owns, one entry per process "
        "([parallel.md](parallel.md))",
        ResultKind::list}});

    /**
     * The warning with which auto's own fft choice gives way to the
     * hierarchical storage after @p shortfall in @p part ("" where the
     * storage was requested or is not fft: then the shortfall stops the
     * run, doc/errors-and-limits.md, "Memory guard").
     */
    std::string
    fft_fallback_warning(const SceneParameters &parameters,
                         const Parameters::FoundationOperator::Storage storage,
                         const unsigned int                            n,
                         const std::string                            &part,
                         const StorageDoesNotFit &shortfall)
    {
      using Storage = Parameters::FoundationOperator::Storage;
      if (parameters.foundation_operator.storage != Storage::automatic ||
          storage != Storage::fft)
        return "";
      return "Foundation operator/Storage = auto: " + part +
             " does not fit on " + std::to_string(n) +
             " foundation nodes, so this cycle and the later ones use the "
             "hierarchical storage. " +
             shortfall.shortfall;
    }
  } // namespace

  PlateOnHalfspaceProblem::PlateOnHalfspaceProblem(
    const SceneParameters &parameters,
    std::ostream          &log)
    : parameters(parameters)
    , log(log)
    , communicator(Utilities::MPI::job_supports_mpi() ? MPI_COMM_WORLD :
                                                        MPI_COMM_SELF)
    , soil(create_soil_model(parameters))
    , timer_output(log, TimerOutput::never, TimerOutput::wall_times)
  {
    (void)declared_mesh;
    (void)declared_loads;
    (void)declared_timing;
    (void)declared_foundation;
  }

  bool
  PlateOnHalfspaceProblem::run()
  {
    // Long phases report their progress on a terminal (base/progress.h).
    ProgressReport::enable(parameters.output.verbosity > 0 &&
                           rank_in(communicator) == 0);
    // SIGINT and SIGTERM end the run at the next safe point, agreed over
    // the ranks (base/interruption.h); a signal that came before touches
    // nothing.
    Interruption::set_communicator(communicator);
    struct Unregister
    {
      ~Unregister()
      {
        Interruption::set_communicator(MPI_COMM_NULL);
      }
    } unregister;
    Interruption::check();
    output = std::make_unique<ResultsOutput>(parameters.output_directory,
                                             communicator);
    if (!output->recovery_note().empty() && parameters.output.verbosity > 0)
      log << output->recovery_note() << std::endl;
    // A run that fails (a failed check included) or is interrupted keeps
    // the earlier run's results (results_output.h): its files go to
    // failed-run/, and the log says where each went. After that only the
    // teardown is left, which has no safe point: signals act at once
    // (the exception in flight, if any, says why the run ended).
    const auto abandon_run = [&]() {
      std::string note;
      try
        {
          note = output->abandon();
        }
      catch (const std::exception &e)
        {
          note =
            "Restoring the earlier results failed: " + one_line_message(e) +
            " They are in <" + parameters.output_directory + "/previous-run>.";
        }
      if (!note.empty())
        log << note << std::endl;
      Interruption::release_signals();
    };
    bool checks_passed = true;
    try
      {
        make_mesh();
        setup_plate(stiffness_unless_coarsened());
        check_sweep_positions();
        for (unsigned int cycle = 0; cycle < parameters.adaptivity.cycles;
             ++cycle)
          {
            Interruption::check();
            if (cycle > 0 && !refine_mesh())
              break;
            nested_start_time_s = cycle == 0 ? solve_on_coarser_mesh() : 0.;
            // made already, as the mesh was left or refined back
            mindlin_plate->complete_setup();
            assemble_loads(cycle);
            build_foundation_operator();
            Interruption::check();
            solve_contact();
            if (!nested_start_note.empty())
              warn(std::exchange(nested_start_note, std::string()));
            Interruption::check();
            if (contact.converged)
              estimate_goal_error();
            Interruption::check();
            postprocess();
            unmet_contact_conditions = goal_estimate_beside_tensile_nodes();
            write_output();
            AssertThrow(contact.converged,
                        ExcMessage(
                          "Contact/Max iterations (" +
                          std::to_string(parameters.contact.max_iterations) +
                          ") reached before the contact set settled."));
            if (summary.has("goal") &&
                summary.object("goal").flag("target_met"))
              {
                log << "Adaptivity/Target error met: estimated relative "
                       "error of <"
                    << goal->name() << "> " << std::scientific
                    << std::setprecision(2)
                    << summary.object("goal").number("relative_error")
                    << " <= " << parameters.adaptivity.target_error
                    << std::defaultfloat << "." << std::endl;
                break;
              }
          }
        // Said of the last cycle's mesh, whose results the run reports.
        if (!unresolved_deflection_length.empty())
          warn(unresolved_deflection_length);
        if (!unmet_contact_conditions.empty())
          warn(unmet_contact_conditions);
        if (parameters.loads.sweep_steps > 0)
          run_sweep();
        // A run whose checks fail is a failed run: its files go to
        // failed-run/ and the earlier results stay (doc/outputs.md).
        checks_passed = run_checks();
        // the last moment to give up: after it the results are committed
        Interruption::check();
      }
    catch (...)
      {
        abandon_run();
        throw;
      }
    if (!checks_passed)
      {
        abandon_run();
        return false;
      }
    output->commit();
    if (parameters.output.verbosity > 1)
      timer_output.print_summary();
    // A signal during the last writes: the results are whole, but whoever
    // sent it asked the run to stop, and a script must learn that it did
    // not end normally. The ranks agree on it; one that comes after the
    // agreement and before the release is this rank's alone.
    int signal_number = 0;
    try
      {
        Interruption::check();
      }
    catch (const Interrupted &e)
      {
        signal_number = e.signal_number();
      }
    const int late_signal = Interruption::release_signals();
    if (signal_number == 0)
      signal_number = late_signal;
    if (signal_number != 0)
      throw Interrupted(signal_number, true);
    return true;
  }

  void
  PlateOnHalfspaceProblem::make_mesh()
  {
    // The goal's error estimate reconstructs on patches of 2 x 2 cells
    // (refinement/dual_weighted_residual.h): keep every cell's siblings.
    if (parameters.adaptivity.goal.functional)
      triangulation.set_mesh_smoothing(Triangulation<2>::patch_level_1);
    // A symmetric scene is solved on the part x >= 0 and/or y >= 0 of the
    // plate (mirror_symmetry.h), cut from the coarse mesh so that its
    // refinements are those of the whole plate's mesh.
    make_coarse_plate_mesh(parameters.plate,
                           parameters.discretization,
                           triangulation);
    // The plate's narrowest extent, or its narrowest slab's: a plate
    // rigid for the soil across it loses its moments' digits there.
    double plate_width;
    if (parameters.plate.shape == Parameters::Plate::Shape::slabs)
      plate_width =
        std::min(*std::min_element(parameters.plate.slab_lengths_x.begin(),
                                   parameters.plate.slab_lengths_x.end()),
                 *std::min_element(parameters.plate.slab_lengths_y.begin(),
                                   parameters.plate.slab_lengths_y.end()));
    else
      {
        const auto corners =
          GridTools::compute_bounding_box(triangulation).get_boundary_points();
        plate_width = std::min(corners.second[0] - corners.first[0],
                               corners.second[1] - corners.first[1]);
      }
    // the plate's weight is uniform: symmetric about both planes
    symmetry = choose_mirror_symmetry(
      parameters,
      triangulation,
      [this](const unsigned int axis, const double tolerance) {
        return reason_loads_not_symmetric(make_loads(parameters.loads, 0.),
                                          axis,
                                          tolerance);
      });
    computed_loads = loads_at(Tensor<1, 2>(), true);
    cut_to_computed_part(symmetry, triangulation);
    slab_grid = std::make_unique<SlabGrid>(parameters.plate, parameters.joints);
    slab_grid->mark_joint_faces(triangulation);
    if (parameters.output.verbosity > 0 && !parameters.refinement_note.empty())
      log << parameters.refinement_note << std::endl;
    triangulation.refine_global(parameters.discretization.initial_refinements);
    if (parameters.output.verbosity > 0 && symmetry.n_copies() > 1)
      log << "symmetry " << symmetry.name() << ": computing "
          << (symmetry.n_copies() == 2 ? "half" : "a quarter")
          << " of the plate" << std::endl;
    {
      // Computed at every verbosity, so that a soil whose compliance cannot
      // be evaluated stops the run alike, and before the line is begun, so
      // that a failure leaves no half-written line in the log.
      const double l = soil->radius_of_relative_stiffness(
        parameters.plate.flexural_rigidity());
      relative_stiffness_radius = l;
      check_plate_against_soil(plate_width);
      if (parameters.output.verbosity > 0)
        log << "radius of relative stiffness on the " << soil->name()
            << " soil: l = " << l
            << " for the plate's D = " << parameters.plate.flexural_rigidity()
            << " (doc/soil-models.md)" << std::endl;
    }
    mindlin_plate = std::make_unique<MindlinPlate>(parameters.plate,
                                                   parameters.discretization);
    mindlin_plate->set_mirror_symmetry(symmetry);
    mindlin_plate->set_communicator(communicator);
    mindlin_plate->set_slab_grid(*slab_grid);
    mindlin_plate->set_thermal_load(
      thermal_load(parameters.plate, parameters.temperature));
    goal = parameters.adaptivity.goal.functional;
  }

  void
  PlateOnHalfspaceProblem::check_plate_against_soil(
    const double plate_width) const
  {
    // The plate's bending is a small fraction, about 1/R, of its rigid-body
    // motion, and the moments and stresses are what rounding leaves of it:
    // one solution vector holds both, so they keep about 12 - log10(R)
    // digits on a dense liquid and 14 - log10(R) on a half-space
    // (doc/errors-and-limits.md, "Stiffness ratio"). A plate beyond the
    // bound is rigid for the soil, and a softer one as rigid keeps the
    // digits. D and the ratio are linear in E: per unit of E the ratio
    // stays finite for a modulus that would overflow it (E = 1e308).
    const auto  &plate             = parameters.plate;
    const double modulus           = plate.youngs_modulus;
    const double ratio_per_modulus = soil->relative_stiffness(
      std::pow(plate.thickness, 3) /
        (12. * (1. - plate.poissons_ratio * plate.poissons_ratio)),
      plate_width);
    const double ratio = ratio_per_modulus * modulus;
    if (!(ratio > largest_relative_stiffness))
      return;
    // Three digits, the ratio rounded up and the modulus down, so that the
    // ratio printed is above the bound and the modulus is accepted.
    const auto three_digits = [](const double value, const bool up) {
      const double unit = std::pow(10., std::floor(std::log10(value)) - 2);
      return (up ? std::ceil(value / unit) : std::floor(value / unit)) * unit;
    };
    const auto  model = parameters.foundation.model;
    const char *soil_entries =
      model == Parameters::Foundation::Model::dense_liquid ?
        "Foundation/Modulus of subgrade reaction" :
      model == Parameters::Foundation::Model::layered ?
        "Foundation/Layers (and Foundation/Young's modulus of a half-space "
        "under them)" :
        "Foundation/Young's modulus";
    std::ostringstream message;
    message << std::setprecision(3) << "The plate is ";
    if (std::isfinite(ratio))
      message << three_digits(ratio, true);
    else
      message << "more than 1e308";
    message << " times stiffer than the " << soil->name()
            << " soil across it (D k^4 G(k) at k = 1/L, L = " << plate_width
            << ", the plate's narrowest extent or its narrowest slab's; "
               "doc/soil-models.md, \"Radius of relative stiffness\"), "
               "above the 1e6 up to which rounding leaves its moments and "
               "stresses 6 digits. For the soil such a plate is rigid: one "
               "with Plate/Young's modulus at most "
            << three_digits(largest_relative_stiffness / ratio_per_modulus,
                            false)
            << " (now " << modulus
            << ") settles and presses the soil the same to about 1e-7 and "
               "keeps the digits. Compare Plate/Young's modulus and "
               "Plate/Thickness with "
            << soil_entries << ", and check their units.";
    AssertThrow(false, ExcMessage(message.str()));
  }

  void
  PlateOnHalfspaceProblem::setup_plate(
    const std::function<bool()> &stiffness_needed)
  {
    std::optional<TimerOutput::Scope> scope;
    if (!timing_nested_start)
      scope.emplace(timer_output, "plate setup");
    Timer setup_timer;
    // an analysis of the plate as it was
    plate_inverse.reset();
    partition_plate_mesh(triangulation, communicator);
    mindlin_plate->setup_dofs(triangulation);
    if (!stiffness_needed || stiffness_needed())
      mindlin_plate->complete_setup();
    if (n_ranks(communicator) > 1)
      {
        // A rank with cells may still own no foundation node (the nodes
        // on its cells' edges may all belong to its neighbours); decided
        // by all ranks together, so that all stop alike (doc/parallel.md).
        const unsigned int own_nodes =
          mindlin_plate->get_foundation_space().owned_nodes.n_elements();
        if (Utilities::MPI::min(own_nodes, communicator) == 0)
          throw ErrorOnEveryRank(
            too_many_ranks_message(n_ranks(communicator),
                                   triangulation.n_active_cells()));
      }
    setup_time_s = setup_timer.wall_time();
  }

  void
  PlateOnHalfspaceProblem::check_sweep_positions()
  {
    // Every position's loads must lie on the plate: found before the
    // first cycle writes anything.
    const Parameters::Loads &loads = parameters.loads;
    for (unsigned int step = 0; step < loads.sweep_steps; ++step)
      {
        const Point<2> offset = loads.sweep_position(step);
        try
          {
            mindlin_plate->load_vector(loads_at(offset, true));
          }
        catch (const ExceptionBase &e)
          {
            std::ostringstream where;
            where << "Loads/Sweep: at position " << step << " (offset "
                  << offset[0] << ", " << offset[1] << "): ";
            AssertThrow(false, ExcMessage(where.str() + one_line_message(e)));
          }
        std::ostringstream where;
        where << "Loads/Sweep: at position " << step << " (offset " << offset[0]
              << ", " << offset[1] << "): ";
        check_loads_on_plate(loads_at(offset, false), where.str(), true, false);
      }
  }

  LoadList
  PlateOnHalfspaceProblem::loads_at(const Tensor<1, 2> &offset,
                                    const bool          computed_part) const
  {
    const LoadList whole =
      make_loads(parameters.loads.with_axles_moved(offset),
                 parameters.plate.unit_weight * parameters.plate.thickness);
    return computed_part ? loads_on_computed_part(whole,
                                                  {{symmetry.x, symmetry.y}},
                                                  symmetry.tolerance) :
                           whole;
  }

  void
  PlateOnHalfspaceProblem::check_loads_on_plate(const LoadList    &loads,
                                                const std::string &where,
                                                const bool warn_off_plate,
                                                const bool warn_resultant)
  {
    // Every patch and tyre on the whole plate's mesh, so that every
    // Plate/Shape (a Gmsh mesh too) warns alike (doc/errors-and-limits.md).
    if (warn_off_plate)
      for (const std::string &w : partly_off_plate_warnings(
             loads_on_plate(mindlin_plate->get_foundation_space(), loads),
             where))
        warn(w);
    if (!parameters.foundation.tensionless)
      return;
    const ResultantVerdict verdict =
      check_load_resultant(*mindlin_plate,
                           loads,
                           parameters.plate.unit_weight > 0,
                           parameters.foundation.model !=
                             Parameters::Foundation::Model::dense_liquid);
    AssertThrow(verdict.error.empty(), ExcMessage(where + verdict.error));
    if (warn_resultant && !verdict.warning.empty())
      warn(where + verdict.warning);
  }

  void
  PlateOnHalfspaceProblem::warn(const std::string &text)
  {
    if (coarse_solve_running)
      return;
    run_warnings.push_back(text);
    if (rank_in(communicator) == 0)
      std::cerr << "Warning: " << text << std::endl;
  }

  void
  PlateOnHalfspaceProblem::check_points_on_plate() const
  {
    std::vector<std::pair<std::string, Point<2>>> points;
    for (const Point<2> &x : parameters.output.probe_points)
      points.emplace_back("Output/Probe points", x);
    for (const Parameters::Check &check : parameters.verification.checks)
      if (check.at_point)
        points.emplace_back("Verification/Checks", check.location);
    // On the first mesh, which the later ones contain: a disk's refined
    // polygons only grow towards its circle.
    const FoundationSpace &space = mindlin_plate->get_foundation_space();
    const bool disk = parameters.plate.shape == Parameters::Plate::Shape::disk;
    for (const auto &[entry, x] : points)
      {
        bool on_plate = true;
        try
          {
            mindlin_plate->locate(space.symmetry.to_computed_part(x));
          }
        catch (...)
          {
            on_plate = false;
          }
        std::ostringstream message;
        message << entry << ": the point (" << x[0] << ", " << x[1]
                << ") is not on the plate"
                << (disk && x.norm() <= parameters.plate.radius ?
                      ": it lies between the disk's circle and the polygon "
                      "of the first mesh's boundary; move it inward or "
                      "refine the mesh (Discretization/Initial "
                      "refinements)." :
                      ".");
        AssertThrow(on_plate, ExcMessage(message.str()));
      }
    // a profile that meets no cell would write empty profiles
    if (!parameters.output.default_profile)
      {
        const Point<2> &start = parameters.output.profile_start,
                       &end   = parameters.output.profile_end;
        const double                       length    = start.distance(end);
        const Tensor<1, 2>                 direction = (end - start) / length;
        std::vector<std::array<double, 2>> images    = {{{1., 1.}}};
        for (const auto &signs : space.symmetry.reflections())
          images.push_back(signs);
        bool met = false;
        for (const auto &cell : space.cells)
          for (const auto &signs : images)
            {
              // the cell's image on the whole plate against the segment
              const Point<2> c = cell.geometry.map(Point<2>(0.5, 0.5));
              const Point<2> y(signs[0] * c[0], signs[1] * c[1]);
              const double   along =
                std::min(length, std::max(0., (y - start) * direction));
              met = met || y.distance(start + along * direction) <=
                             0.5 * cell.geometry.diameter();
            }
        std::ostringstream message;
        message << "Output/Profile: the line from (" << start[0] << ", "
                << start[1] << ") to (" << end[0] << ", " << end[1]
                << ") does not meet the plate.";
        AssertThrow(met, ExcMessage(message.str()));
      }
  }

  void
  PlateOnHalfspaceProblem::check_result_magnitudes() const
  {
    // Rough scales of the results the loads give, from the assembled
    // load's total magnitude F over the plate's area A: pressures F/A,
    // moments F, fibre stresses 6 F/t^2, and deflections F L^2/D (the
    // plate's own bending over its size L) or the soil's settlement.
    // Peaks under point loads and at edges exceed them many times, so the
    // limit keeps eight decades below the largest 32-bit float (3.4e38)
    // that the VTU files hold; the double arithmetic of the solvers (whose
    // norms square the values) is safe there as well.
    const FoundationSpace &space  = mindlin_plate->get_foundation_space();
    const double           copies = symmetry.n_copies();
    double                 force  = 0;
    for (const auto dof : mindlin_plate->get_foundation_dofs())
      force += copies * std::abs(mindlin_plate->get_load_vector()[dof]);
    const double area    = copies * space.area();
    const auto  &plate   = parameters.plate;
    double       patches = 0;
    for (const auto &load : computed_loads)
      {
        double peak = 0;
        for (const auto &cell : space.cells)
          for (const double p : load->on_cell(cell.geometry).pressure)
            peak = std::max(peak, std::abs(p));
        // the entries take decimal numbers from 1e-307: a function may
        // give less, where the solvers' arithmetic loses its digits
        if (peak > 0 && peak < 1e-307)
          {
            std::ostringstream message;
            message << load->label() << ": the largest pressure on the plate "
                    << "is " << peak
                    << ", below 1e-307, where the arithmetic loses its "
                       "digits; scale the scene's units.";
            AssertThrow(false, ExcMessage(message.str()));
          }
        patches = std::max(patches, peak);
      }
    const double thermal = std::abs(mindlin_plate->get_thermal_load().moment);
    const double settlement = soil->typical_settlement(force, area);
    const std::vector<std::pair<std::string, double>> scales = {
      {"the total load", force},
      {"the pressure (a load's pressure, or the total load over the "
       "plate's area)",
       std::max(patches, force / area)},
      {"the moment (the total load, or the thermal moment)",
       std::max(force, thermal)},
      {"the fibre stress 6 M/t^2",
       6 * std::max(force, thermal) / (plate.thickness * plate.thickness)},
      {"the deflection (F L^2/D of the plate, or the soil's settlement)",
       std::max(force * area / plate.flexural_rigidity(), settlement)}};
    const double limit = 1e30;
    for (const auto &[name, value] : scales)
      if (!std::isfinite(value))
        {
          AssertThrow(false,
                      ExcMessage(
                        "Loads: " + name +
                        " of this scene overflows the arithmetic (it is not "
                        "a finite number): the plate's size, thickness, "
                        "moduli or loads lie beyond what double precision "
                        "holds. Express the scene in other units (e.g. MN "
                        "and MPa instead of kN and kPa) or check these "
                        "entries (doc/errors-and-limits.md, \"Finite "
                        "results\")."));
        }
      else if (!(value <= limit))
        {
          std::ostringstream message;
          message << "Loads: the results of this scene would reach about "
                  << std::setprecision(3) << value << " (" << name
                  << "), beyond the " << limit
                  << " the program accepts: the VTU files hold 32-bit "
                     "floats (up to 3.4e38), and the peaks under point "
                     "loads and at edges exceed these scales many times. "
                     "Express the scene in larger units (e.g. MN and MPa "
                     "instead of kN and kPa) or check the loads and moduli "
                     "(doc/errors-and-limits.md, \"Finite results\").";
          AssertThrow(false, ExcMessage(message.str()));
        }
  }

  void
  PlateOnHalfspaceProblem::check_results_are_finite() const
  {
    // A last guard: whatever the scene, no NaN, infinity or value the VTU
    // files cannot hold reaches a result file (doc/errors-and-limits.md,
    // "Finite results"). The same bound without VTU files: no physical
    // scene in consistent units comes near it, so a value beyond it is
    // round-off grown out of bounds (an absurd stiffness ratio, say).
    const double limit = 0.1 * FLT_MAX;
    const auto   check = [&](const std::string &name, const double value) {
      if (std::isfinite(value) && std::abs(value) <= limit)
        return;
      std::ostringstream message;
      message << "The " << name << " of cycle " << summary.count("cycle")
              << " is " << (std::isfinite(value) ? "" : "not a finite number, ")
              << value;
      if (std::isfinite(value))
        message << ", beyond the 3.4e37 the results may reach (the VTU files "
                     "hold 32-bit floats, up to 3.4e38): express the scene in "
                     "larger units (e.g. MN and MPa instead of kN and kPa), "
                     "or check the loads and moduli (doc/errors-and-limits.md, "
                     "\"Finite results\").";
      else
        message << ": the scene has no finite answer on this mesh; check the "
                     "loads, moduli and mesh (doc/errors-and-limits.md, "
                     "\"Finite results\").";
      AssertThrow(false, ExcMessage(message.str()));
    };
    const auto check_vector = [&](const std::string    &name,
                                  const Vector<double> &v) {
      for (const double value : v)
        check(name, value);
    };
    check_vector("plate solution (deflection and rotations)",
                 contact.plate_solution);
    check_vector("contact pressure", contact.q);
    check_vector("gap", contact.gap);
    // every number of the cycle's record (doc/outputs.md)
    summary.for_each_number([&](const std::string &key, const double value) {
      check(key + " (summary.json)", value);
    });
  }

  bool
  PlateOnHalfspaceProblem::refine_mesh()
  {
    const bool refined = refine_and_carry_seed([this]() {
      if (!create_refinement_strategy(parameters)
             ->mark(*mindlin_plate, contact, goal_estimate, triangulation))
        return false;
      // the faces of each joint keep facing each other
      slab_grid->match_refinement(triangulation);
      return true;
    });
    if (!refined)
      log << "Adaptivity/Max cells reached: no further cycles." << std::endl;
    return refined;
  }

  bool
  PlateOnHalfspaceProblem::refine_and_carry_seed(
    const std::function<bool()> &mark)
  {
    // the active set (not the wider set where q > 0) seeds the next cycle,
    // and the nodal pressure starts the next constrained start
    // (IterativeContactSolver::predict_contact_set())
    Vector<double> indicator(contact.active_set.size());
    for (unsigned int i = 0; i < indicator.size(); ++i)
      indicator[i] = contact.active_set[i] ? 1. : 0.;
    const std::vector<Vector<double>> old_fields = {
      mindlin_plate->foundation_field_to_solution(indicator),
      mindlin_plate->foundation_field_to_solution(contact.q)};
    if (!mark())
      return false;
    SolutionTransfer<2> transfer(mindlin_plate->get_dof_handler());
    triangulation.prepare_coarsening_and_refinement();
    transfer.prepare_for_coarsening_and_refinement(old_fields);
    triangulation.execute_coarsening_and_refinement();
    setup_plate();

    std::vector<Vector<double>> new_fields(
      2, Vector<double>(mindlin_plate->get_dof_handler().n_dofs()));
    transfer.interpolate(old_fields, new_fields);
    const Vector<double> nodal =
      mindlin_plate->restrict_to_foundation(new_fields[0]);
    seed.contact_set.resize(nodal.size());
    for (unsigned int i = 0; i < nodal.size(); ++i)
      seed.contact_set[i] = nodal[i] > 0.5;
    seed.pressure = mindlin_plate->restrict_to_foundation(new_fields[1]);
    return true;
  }

  std::function<bool()>
  PlateOnHalfspaceProblem::stiffness_unless_coarsened() const
  {
    // A mesh that the nested start coarsens is set up again once refined
    // back: its stiffness would be assembled twice. Nothing before the
    // nested start reads it (the sweep's checks read loads and nodes).
    return [this]() { return nested_start_obstacle().has_value(); };
  }

  std::optional<std::string>
  PlateOnHalfspaceProblem::nested_start_obstacle() const
  {
    using NestedStart         = Parameters::Contact::NestedStart;
    const NestedStart  choice = parameters.contact.nested_start;
    const unsigned int n      = mindlin_plate->get_foundation_dofs().size();
    if (choice == NestedStart::off ||
        (choice == NestedStart::automatic &&
         n < Parameters::Contact::nested_start_nodes))
      return std::string();
    // The coarser mesh is the initial refinements' last but one: every
    // cell one level up.
    const int level = nested_start_level();
    // Adaptivity/Refinement = goal keeps every cell's siblings as a patch
    // (make_mesh()): deal.II then coarsens no cell to the coarse mesh's
    // level.
    const bool patches =
      triangulation.get_mesh_smoothing() & Triangulation<2>::patch_level_1;
    if (!parameters.foundation.tensionless)
      return std::string("a bonded foundation has no contact set to seed");
    if (parameters.contact.method != Parameters::Contact::Method::active_set)
      return std::string("Contact/Method = element exclusion does not start "
                         "from a seed");
    if (level < 1)
      return std::string("the first mesh has no coarser level (it needs "
                         "Discretization/Initial refinements of at least 1)");
    if (patches && level < 2)
      return std::string("Adaptivity/Refinement = goal keeps the cells in "
                         "patches that the coarse mesh's cells cannot form");
    return std::nullopt;
  }

  int
  PlateOnHalfspaceProblem::nested_start_level() const
  {
    const int level = static_cast<int>(triangulation.n_levels()) - 1;
    for (const auto &cell : triangulation.active_cell_iterators())
      if (cell->level() != level)
        return -1;
    return level;
  }

  double
  PlateOnHalfspaceProblem::solve_on_coarser_mesh(const bool within_nested)
  {
    using NestedStart             = Parameters::Contact::NestedStart;
    const NestedStart choice      = parameters.contact.nested_start;
    const auto        not_applied = [&](const std::string &reason,
                                 const bool         after_first_solve = false) {
      if (choice != NestedStart::on || within_nested)
        return 0.;
      const std::string text = "Contact/Nested start = true: " + reason +
                               "; the first cycle starts without it.";
      if (after_first_solve)
        nested_start_note = text;
      else
        warn(text);
      return 0.;
    };
    if (const std::optional<std::string> obstacle = nested_start_obstacle())
      return obstacle->empty() ? 0. : not_applied(*obstacle);
    const int level = nested_start_level();
    // The nested start's time holds the coarse solves, the refinement
    // back and its plate setup (the stiffness of the mesh as given among
    // it); the cycle's assembly_time_s keeps the setup of the mesh as
    // given before the run's loop: its DoFs and foundation nodes.
    // The whole nested start in one section of the timings: the phases
    // on the coarser meshes and the refinement back (timing_nested_start).
    struct NestedStartSection
    {
      NestedStartSection(PlateOnHalfspaceProblem &problem, const bool nested)
        : flag(problem.timing_nested_start)
      {
        if (!nested)
          scope.emplace(problem.timer_output, "nested start");
        flag = true;
      }
      ~NestedStartSection()
      {
        if (scope)
          flag = false;
      }
      bool                             &flag;
      std::optional<TimerOutput::Scope> scope;
    } section(*this, within_nested);
    Timer        timer;
    const double given_setup_s = setup_time_s;
    // Back to the mesh as given, the cells coarsened refined again
    // (refine_global()'s cells, vertices and order), and the cycle starts
    // without a seed for @p reason.
    const auto start_without = [&](const std::string &reason,
                                   const bool after_first_solve = false) {
      for (const auto &cell : triangulation.active_cell_iterators())
        if (cell->level() < level)
          cell->set_refine_flag();
      triangulation.execute_coarsening_and_refinement();
      AssertThrow(nested_start_level() == level,
                  ExcInternalError("Contact/Nested start: the mesh was not "
                                   "restored."));
      setup_plate();
      seed = ContactSeed();
      not_applied(reason, after_first_solve);
      setup_time_s = given_setup_s;
      return timer.wall_time();
    };
    for (const auto &cell : triangulation.active_cell_iterators())
      cell->set_coarsen_flag();
    triangulation.execute_coarsening_and_refinement();
    // not every cell coarsened: the mesh smoothing refused some
    if (nested_start_level() != level - 1)
      return start_without("deal.II's mesh smoothing kept cells from being "
                           "coarsened");
    // On several processes the coarser mesh may have too few cells for
    // them, which every rank finds alike (setup_plate()).
    try
      {
        setup_plate(stiffness_unless_coarsened());
      }
    catch (const ErrorOnEveryRank &)
      {
        return start_without("the mesh one refinement coarser has too few "
                             "cells for the processes",
                             true);
      }
    // the coarser mesh's own solve seeded from one coarser still, where
    // that applies in turn
    solve_on_coarser_mesh(true);
    // The coarse solve writes nothing: its log lines and warnings would
    // describe a mesh the run does not solve, and the first cycle checks
    // its own. What it decides for later cycles (a storage or solver
    // after a failure, a warning given once) is the first cycle's to
    // decide again.
    // (the copy first: nothing may throw between muting and the try)
    const auto            decided    = std::make_tuple(integration_error_warned,
                                         coarse_cell_warned,
                                         last_kernel_report,
                                         direct_after_failed_iterations,
                                         hierarchical_after_fft_did_not_fit);
    std::streambuf *const log_buffer = log.rdbuf(nullptr);
    coarse_solve_running             = true;
    const auto restore               = [&]() {
      log.rdbuf(log_buffer);
      coarse_solve_running                         = false;
      std::tie(integration_error_warned,
               coarse_cell_warned,
               last_kernel_report,
               direct_after_failed_iterations,
               hierarchical_after_fft_did_not_fit) = decided;
    };
    try
      {
        assemble_loads(0);
        build_foundation_operator();
        solve_contact();
      }
    catch (const Interrupted &)
      {
        restore();
        throw;
      }
    catch (const std::exception &error)
      {
        // On several processes one rank may fail while the others wait in
        // a collective step: it cannot start again without them, so it
        // stops the run as in any solve (doc/parallel.md), naming the
        // coarse solve and the way around it. An error that every rank
        // meets alike (most are: they are decided from what all ranks hold
        // the same) falls back as on one process; not so memory, which
        // may run out anywhere and on some ranks only.
        if (n_ranks(communicator) > 1 &&
            (dynamic_cast<const std::bad_alloc *>(&error) != nullptr ||
             !every_rank_fails_alike(error, FailureSite::coarse_solve)))
          {
            restore();
            throw std::runtime_error(
              "Contact/Nested start: the solve on the mesh one refinement "
              "coarser stopped on this process alone (" +
              without_final_period(one_line_message(error)) +
              "), and the run cannot go on without it. Set Contact/Nested "
              "start = false.");
          }
        // The coarse mesh is not the scene's: a load in the sliver its
        // chords cut off a disk, or a layer too thin for its wider cells,
        // may fail there and not on the mesh as given, which decides.
        // Said once the first cycle has solved: a scene refused on the
        // mesh as given too gets its refusal alone.
        restore();
        return start_without(
          "the solve on the mesh one refinement coarser stopped (" +
            without_final_period(one_line_message(error)) + ")",
          true);
      }
    restore();
    const unsigned int coarse_nodes     = contact.q.size();
    const bool         used_seed        = !seed.contact_set.empty();
    const unsigned int coarse_steps     = contact.iterations;
    const bool         coarse_converged = contact.converged;
    refine_and_carry_seed([this]() {
      for (const auto &cell : triangulation.active_cell_iterators())
        cell->set_refine_flag();
      return true;
    });
    // an unsettled coarse set would seed the cycle with a guess no better
    // than its default
    if (!coarse_converged)
      seed = ContactSeed();
    setup_time_s = given_setup_s;
    if (parameters.output.verbosity > 0)
      log << "Contact/Nested start: " << coarse_nodes
          << " foundation nodes one refinement coarser"
          << (used_seed ? " (seeded in turn)" : "") << ", " << coarse_steps
          << " active-set steps; "
          << (coarse_converged ? "its contact set and pressure seed the " :
                                 "not settled, so it seeds nothing on the ")
          << mindlin_plate->get_foundation_dofs().size() << " nodes"
          << std::endl;
    return timer.wall_time();
  }

  void
  PlateOnHalfspaceProblem::assemble_loads(const unsigned int cycle)
  {
    cycle_timer.restart();
    Timer phase;
    mindlin_plate->assemble_loads(computed_loads);
    // Sums over the computed part times the copies that make the plate.
    summary = ResultRecord("cycles");
    summary.set_count("cycle", cycle);
    summary.set_count("n_cells", triangulation.n_active_cells());
    summary.set_count("n_dofs", mindlin_plate->n_unconstrained_dofs());
    summary.set_count("n_foundation_dofs",
                      mindlin_plate->get_foundation_dofs().size());
    summary.set("applied_load",
                symmetry.n_copies() * mindlin_plate->applied_load());
    // before anything is computed on these loads: what they put on the
    // plate, whether it has an answer, and whether that fits the files
    check_loads_on_plate(loads_at(Tensor<1, 2>(), false),
                         "",
                         cycle == 0,
                         cycle == 0);
    if (cycle == 0)
      {
        check_result_magnitudes();
        check_points_on_plate();
      }
    const double integration_error =
      load_integration_error(mindlin_plate->get_foundation_space(),
                             computed_loads);
    summary.set("load_integration_error", integration_error);
    // said once: a later cycle's finer mesh usually brings it down
    if (integration_error > 1e-4 && !integration_error_warned)
      {
        std::ostringstream w;
        w << "Loads: the applied load of cycle " << cycle
          << " is integrated to a relative error of about "
          << std::setprecision(2) << integration_error
          << " (load_integration_error in summary.json): a pressure with a "
             "jump, a peak or a pole inside the cells. Raise Loads/Pressure "
             "function points, refine, or give a jump as a region "
             "(doc/loads.md).";
        warn(w.str());
        integration_error_warned = true;
      }
    const unsigned int owned_nodes = static_cast<unsigned int>(
      mindlin_plate->get_foundation_space().owned_nodes.n_elements());
    const std::vector<unsigned int> nodes_per_rank =
      n_ranks(communicator) > 1 ?
        Utilities::MPI::all_gather(communicator, owned_nodes) :
        std::vector<unsigned int>{owned_nodes};
    summary.set("foundation_nodes_per_rank",
                ResultRecord::Counts(nodes_per_rank.begin(),
                                     nodes_per_rank.end()));
    summary.set("assembly_time_s", setup_time_s + phase.wall_time());
    summary.set("nested_start_time_s", nested_start_time_s);
    if (parameters.output.verbosity > 0)
      log << "cycle " << cycle << ": " << summary.count("n_cells") << " cells, "
          << summary.count("n_dofs") << " dofs, "
          << summary.count("n_foundation_dofs") << " foundation nodes"
          << std::endl;
    if (parameters.output.verbosity > 0 && nodes_per_rank.size() > 1)
      {
        log << "   foundation nodes per rank (METIS):";
        for (const unsigned int n : nodes_per_rank)
          log << ' ' << n;
        log << std::endl;
      }
  }

  void
  PlateOnHalfspaceProblem::build_foundation_operator()
  {
    std::optional<TimerOutput::Scope> scope;
    if (!timing_nested_start)
      scope.emplace(timer_output, "build foundation operator");
    Timer phase;
    // Storage = auto and Solver = auto are decided for this cycle's mesh.
    const unsigned int n = summary.count("n_foundation_dofs");
    // Decided once for the cycle, and by all ranks alike (the free memory
    // differs between them and between calls).
    direct_for_flexible_plate_cycle =
      !direct_after_failed_iterations &&
      Utilities::MPI::min(direct_for_flexible_plate(n) ? 1u : 0u,
                          communicator) == 1u;
    using Storage      = Parameters::FoundationOperator::Storage;
    fft_unsuited_cycle = false;
    if (parameters.foundation_operator.storage == Storage::automatic &&
        parameters.foundation_storage(n) == Storage::fft)
      {
        const std::string obstacle =
          split_kernel_mesh_obstacle(mindlin_plate->get_foundation_space());
        fft_unsuited_cycle = !obstacle.empty();
        if (fft_unsuited_cycle && parameters.output.verbosity > 0)
          log << "Foundation operator/Storage = auto: hierarchical, not fft: "
              << obstacle << std::endl;
      }
    const auto storage = cycle_storage(n);
    if (parameters.output.verbosity > 0 && direct_for_flexible_plate_cycle)
      log << "Contact/Solver = auto: direct with dense storage, the plate is "
             "so much more flexible than the soil that rounding would leave "
             "the iterative solver's pressures about "
          << std::setprecision(1)
          << estimate_preconditioners(*mindlin_plate, *soil).rounding_floor
          << std::setprecision(6)
          << " of the settlement (doc/errors-and-limits.md, \"Stiffness "
             "ratio\")"
          << std::endl;
    if (storage == Storage::dense)
      check_dense_foundation_memory(n,
                                    cycle_solver(n) ==
                                      Parameters::Contact::Solver::iterative,
                                    !direct_after_failed_iterations);
    if (!foundation_operator || operator_storage != storage)
      {
        foundation_operator =
          create_foundation_operator(parameters, soil, storage);
        operator_storage = storage;
      }
    // The iterative solver's K^+ needs the plate alone, and its symbolic
    // stage (the ordering) runs on one core: beside the operator's build,
    // which leaves the second core idle for much of its time
    // (doc/performance.md, "The plate's ordering beside the operator's
    // build"). A failure there is left to the solver, which makes its own
    // K^+ and reports it where it always has. Only beside the fft build:
    // METIS draws from the C library's rand(), and hmat-oss's compression
    // draws from it too, so that beside a hierarchical build both would
    // depend on the timing.
    plate_inverse.reset();
    const bool analyse_plate =
      n_ranks(communicator) == 1 && storage == Storage::fft &&
      cycle_solver(n) == Parameters::Contact::Solver::iterative;
    try
      {
        run_tasks(analyse_plate ? 2 : 1, [&](const unsigned int part) {
          if (part == 0)
            foundation_operator->build(mindlin_plate->get_foundation_space(),
                                       {});
          else
            try
              {
                plate_inverse =
                  std::make_unique<PlateGeneralizedInverse>(*mindlin_plate);
              }
            catch (...)
              {
                plate_inverse.reset();
              }
        });
#ifdef __GLIBC__
        // The analysis's blocks, freed on its thread, stay in that
        // thread's heap, where the main thread's later factors do not
        // reuse them: given back, the run's peak is what it was without
        // the analysis beside the build (doc/performance.md, "The plate's
        // ordering beside the operator's build").
        if (analyse_plate)
          malloc_trim(0);
#endif
      }
    catch (const StorageDoesNotFit &shortfall)
      {
        const std::string warning = fft_fallback_warning(
          parameters, storage, n, "the split kernel (fft)", shortfall);
        if (warning.empty())
          throw;
        warn(warning);
        hierarchical_after_fft_did_not_fit = true;
        foundation_operator =
          create_foundation_operator(parameters, soil, Storage::hierarchical);
        operator_storage = Storage::hierarchical;
        foundation_operator->build(mindlin_plate->get_foundation_space(), {});
      }
    if (parameters.output.verbosity > 0 &&
        !foundation_operator->build_report().empty())
      log << foundation_operator->build_report() << std::endl;
    const std::string kernel_report = soil->kernel_report();
    if (!kernel_report.empty() && kernel_report != last_kernel_report)
      log << kernel_report << std::endl;
    last_kernel_report = kernel_report;
    // A smooth remainder's rules are sized for cells up to about 3 l wide:
    // separated pairs take 3 or 5 Gauss points per direction, the
    // settlement between nodes at most 12, touching pairs at most 96
    // (cell_pair_quadrature.h, surface_settlement.h).
    if (const auto *elastic = dynamic_cast<const ElasticSoil *>(soil.get()))
      {
        const FoundationSpace &space = mindlin_plate->get_foundation_space();
        const SurfaceKernel kernel   = elastic->kernel(maximal_distance(space));
        double              largest  = 0;
        for (const auto &cell : space.cells)
          largest = std::max(largest, cell.geometry.diameter());
        if (kernel.remainder &&
            largest > 3. * kernel.remainder->length_scale() &&
            !coarse_cell_warned)
          {
            std::ostringstream text;
            text << "Foundation/Layers: the plate's cells (up to " << largest
                 << ") are more than 3 times as wide as the top layer ("
                 << kernel.remainder->length_scale()
                 << " thick); the layered kernel's quadrature rules are sized "
                    "for cells up to about 3 times its thickness, and its "
                    "error may exceed the stated tolerance. Refine the mesh "
                    "(Discretization/Initial refinements), or merge the top "
                    "layer into the one below.";
            warn(text.str());
            coarse_cell_warned = true;
          }
      }
    foundation_time_s = phase.wall_time();
  }

  void
  PlateOnHalfspaceProblem::solve_contact()
  {
    std::optional<TimerOutput::Scope> scope;
    if (!timing_nested_start)
      scope.emplace(timer_output, "contact solve");
    Timer              phase;
    const unsigned int n          = summary.count("n_foundation_dofs");
    const auto         solve_with = [&](const Parameters::Contact::Solver s) {
      contact_solver = create_contact_solver(
        parameters, s, parameters.output.verbosity, log, coarse_solve_running);
      if (auto *iterative =
            dynamic_cast<IterativeContactSolver *>(contact_solver.get()))
        iterative->use_plate_inverse(std::move(plate_inverse));
      plate_inverse.reset();
      contact = contact_solver->solve(*mindlin_plate,
                                      *foundation_operator,
                                      mindlin_plate->get_load_vector(),
                                      seed);
    };
    double     rebuild_time      = 0;
    const auto rebuild_and_solve = [&](const Parameters::Contact::Solver s) {
      // The iterative solver refers to the operator about to be replaced.
      contact_solver.reset();
      const double first_build = foundation_time_s;
      Timer        rebuild;
      build_foundation_operator();
      rebuild_time = rebuild.wall_time();
      foundation_time_s += first_build;
      solve_with(s);
    };
    try
      {
        solve_with(cycle_solver(n));
      }
    catch (const ConjugateGradientsFailed &failure)
      {
        using Storage         = Parameters::FoundationOperator::Storage;
        const Storage storage = cycle_storage(n);
        const bool    own =
          parameters.contact.solver == Parameters::Contact::Solver::automatic &&
          parameters.foundation_operator.storage == Storage::automatic &&
          Parameters::FoundationOperator::compressed(storage);
        if (!own)
          throw;
        // The dense block's memory, checked here so that a failure says
        // both why the iterations stopped and why the fallback cannot run.
        const std::string shortfall =
          dense_foundation_memory_shortfall(n, false, false);
        if (!shortfall.empty())
          throw ConjugateGradientsFailed(
            "Contact/Solver = auto: the conjugate gradients on the contact "
            "pressures failed on " +
            std::to_string(n) +
            " foundation nodes (the plate is far more flexible than the "
            "soil), and the direct solver does not fit: " +
            shortfall + " The iterations stopped with: " + failure.what());
        warn("Contact/Solver = auto: the conjugate gradients failed on " +
             std::to_string(n) +
             " foundation nodes (the plate is far more flexible than the "
             "soil); this cycle and the later ones use the direct solver "
             "with dense storage (doc/errors-and-limits.md, \"Stiffness "
             "ratio\").");
        direct_after_failed_iterations = true;
        rebuild_and_solve(Parameters::Contact::Solver::direct);
      }
    catch (const StorageDoesNotFit &shortfall)
      {
        // The fft soil inverse checks its factors against the memory left
        // when it makes them (the plate's factor came after the build's
        // check): auto's own fft choice is replaced, as at the build.
        const std::string warning =
          fft_fallback_warning(parameters,
                               operator_storage,
                               n,
                               "the split kernel's (fft) soil inverse",
                               shortfall);
        if (warning.empty())
          throw;
        warn(warning);
        hierarchical_after_fft_did_not_fit = true;
        rebuild_and_solve(cycle_solver(n));
      }
    pressure_field = mindlin_plate->foundation_field_to_solution(contact.q);
    warn_rounding_floor(contact.rounding_limited_residual,
                        "on " + std::to_string(n) + " foundation nodes");
    warn_unresolved_contact_region();
    warn_knife_edge();
    if (!coarse_solve_running)
      unresolved_deflection_length =
        cells_larger_than_deflection_length(
          computed_loads,
          contact,
          false,
          "the last cycle's mesh (cycle " +
            std::to_string(summary.count("cycle")) + ")")
          .warning;
    // The solver's factorisation of the flexibility belongs to the
    // foundation's time (doc/outputs.md, the time split); so does a
    // rebuild after failed iterations, whose time the solve had.
    const double factorization = contact.factorization_time_s;
    const double compression   = foundation_operator->build_times().compression;
    summary.set("foundation_time_s", foundation_time_s + factorization);
    summary.set("foundation_integration_time_s",
                std::max(0., foundation_time_s - compression));
    summary.set("foundation_compression_time_s", compression);
    summary.set("foundation_factorization_time_s", factorization);
    summary.set("solve_time_s",
                std::max(0., phase.wall_time() - factorization - rebuild_time));
  }

  Parameters::FoundationOperator::Storage
  PlateOnHalfspaceProblem::cycle_storage(
    const unsigned int n_foundation_nodes) const
  {
    using Storage = Parameters::FoundationOperator::Storage;
    if (direct_after_failed_iterations || direct_for_flexible_plate_cycle)
      return Storage::dense;
    const Storage storage = parameters.foundation_storage(n_foundation_nodes);
    return storage == Storage::fft &&
               (hierarchical_after_fft_did_not_fit || fft_unsuited_cycle) ?
             Storage::hierarchical :
             storage;
  }

  void
  PlateOnHalfspaceProblem::warn_unresolved_contact_region()
  {
    if (coarse_solve_running || unresolved_contact_warned ||
        !parameters.foundation.tensionless || !contact.converged)
      return;
    const FoundationSpace &space    = mindlin_plate->get_foundation_space();
    double                 smallest = std::numeric_limits<double>::max();
    for (const auto &cell : space.cells)
      for (const unsigned int i : cell.nodes())
        if (contact.in_contact[i])
          {
            smallest = std::min(smallest, cell.geometry.area());
            break;
          }
    const double located = contact_area(contact);
    if (smallest == std::numeric_limits<double>::max() || located >= smallest)
      return;
    unresolved_contact_warned = true;
    std::ostringstream text;
    text << "cycle " << summary.count("cycle")
         << ": the plate bears on a contact region smaller than one of the "
            "cells that carry it (contact_area_fraction "
         << std::setprecision(3) << located / space.area() << ", the region "
         << located << " against a cell of " << smallest
         << "): its extent and the pressure under it are not resolved on "
            "this mesh. Refine there (Adaptivity/Refinement = adaptive, or "
            "goal with Adaptivity/Goal = contact area).";
    warn(text.str());
  }

  std::string
  PlateOnHalfspaceProblem::goal_estimate_beside_tensile_nodes() const
  {
    if (parameters.contact.method !=
          Parameters::Contact::Method::element_exclusion ||
        !parameters.foundation.tensionless || !summary.has("goal") ||
        !summary.has("tensile_nodes") || summary.count("tensile_nodes") == 0)
      return "";
    std::ostringstream text;
    text << "Adaptivity/Goal with Contact/Method = element exclusion: cycle "
         << summary.count("cycle") << " leaves "
         << summary.count("tensile_nodes")
         << " nodes in tension (complementarity violation "
         << std::setprecision(2) << summary.number("complementarity_violation")
         << "). The goal's estimated_error covers the discretisation on "
            "that contact set, not the error of the contact conditions it "
            "leaves unmet, which can be larger (doc/errors-and-limits.md, "
            "\"Goal error estimates\"). Contact/Method = active set meets "
            "them.";
    return text.str();
  }

  PlateOnHalfspaceProblem::UnresolvedCells
  PlateOnHalfspaceProblem::cells_larger_than_deflection_length(
    const LoadList     &loads,
    const ContactState &state,
    const bool          moving_features_only,
    const std::string  &mesh) const
  {
    const double l = relative_stiffness_radius;
    if (!(l > 0) || !std::isfinite(l))
      return {};
    const FoundationSpace &space    = mindlin_plate->get_foundation_space();
    const bool             lift_off = parameters.foundation.tensionless &&
                          state.converged &&
                          state.in_contact.size() == space.n_nodes();
    // How many times the length the cells may be before the results near
    // each feature are off by more than a few percent, measured in
    // doc/errors-and-limits.md, "Cells larger than l": a load's edge
    // (6 % to 22 % at 1.67), a curled free edge (2 % at 1.5, 26 % at 3),
    // a lift-off line (3 % at 2.8, 60 % at 16).
    constexpr double load_edge_ratio = 1.5, curled_edge_ratio = 2,
                     lift_off_ratio = 4;
    // A thermal moment bends the plate only within about l of its free
    // edges: every boundary face but a mirror plane's and a tied joint's
    // (a mesh file's outline keeps its own boundary ids).
    std::vector<bool> on_free_edge(space.cells.size(), false);
    if (mindlin_plate->get_thermal_load().moment != 0 && !moving_features_only)
      {
        const auto &joints    = slab_grid->get_joints();
        const auto  free_edge = [&](const auto &face) {
          const types::boundary_id id = face->boundary_id();
          if ((symmetry.x && id == mirror_plane_x_boundary_id) ||
              (symmetry.y && id == mirror_plane_y_boundary_id))
            return false;
          if (id != joint_boundary_id || joints.empty())
            return true;
          const unsigned int joint = slab_grid->joint_at(face->center());
          return joint == joints.size() ||
                 joints[joint].transfer !=
                   Parameters::Joints::LoadTransfer::tied;
        };
        unsigned int k = 0;
        for (const auto &cell :
             mindlin_plate->get_dof_handler().active_cell_iterators())
          {
            for (const unsigned int f : cell->face_indices())
              if (cell->at_boundary(f) && free_edge(cell->face(f)))
                on_free_edge[k] = true;
            ++k;
          }
      }
    // The worst cell: how far it exceeds its feature's ratio.
    double      worst = 1, worst_size = 0, worst_length = 0, worst_ratio = 0;
    std::string worst_what, worst_length_name;
    const std::string l_name = "the plate's radius of relative stiffness l";
    for (unsigned int k = 0; k < space.cells.size(); ++k)
      {
        const auto &cell = space.cells[k];
        // a square cell's side; every length below is at least l
        const double size = cell.geometry.diameter() / std::sqrt(2.);
        if (size <= worst * load_edge_ratio * l)
          continue;
        const auto consider = [&](const double       length,
                                  const double       ratio,
                                  const std::string &what,
                                  const std::string &length_name) {
          if (size > worst * ratio * length)
            {
              worst             = size / (ratio * length);
              worst_size        = size;
              worst_length      = length;
              worst_ratio       = ratio;
              worst_what        = what;
              worst_length_name = length_name;
            }
        };
        for (const auto &load : loads)
          if (load->jump_on(cell.geometry.get_vertices(),
                            cell.geometry.area()) > 0)
            {
              const std::optional<double> width = load->region_width();
              if (width && *width > l)
                consider(*width,
                         load_edge_ratio,
                         "the edge of " + load->label(),
                         "the load's width");
              else
                consider(l,
                         load_edge_ratio,
                         (load->concentrated_force() ? "" : "the edge of ") +
                           load->label(),
                         l_name);
            }
        if (on_free_edge[k])
          consider(l,
                   curled_edge_ratio,
                   "the edge of the plate that the temperature difference "
                   "curls",
                   l_name);
        if (lift_off)
          {
            bool touching = false, lifted = false;
            for (const unsigned int i : cell.nodes())
              (state.in_contact[i] ? touching : lifted) = true;
            if (touching && lifted)
              consider(l,
                       lift_off_ratio,
                       "the line where the plate lifts off",
                       l_name);
          }
      }
    if (worst_what.empty())
      return {};
    std::ostringstream text;
    text << std::setprecision(3) << mesh << ": cells of " << worst_size
         << " carry " << worst_what << ", " << worst_size / worst_length
         << " times the length over which the deflection varies there ("
         << worst_length_name << ", " << worst_length << "; more than "
         << worst_ratio
         << " times is not resolved): w, q, the moments and the contact area "
            "near it are not converged (off by 6 % to 60 % in "
            "doc/errors-and-limits.md, \"Cells larger than l\"). "
         << (moving_features_only ?
               // the cycles refine for the loads without an offset
               "Refine along the loads' path (Discretization/Initial "
               "refinements, or Subdivisions x and y)." :
               "Refine there (Discretization/Initial refinements, or "
               "Adaptivity/Refinement = adaptive with more Cycles).");
    return {worst, text.str()};
  }

  void
  PlateOnHalfspaceProblem::warn_knife_edge()
  {
    if (coarse_solve_running || knife_edge_warned ||
        !parameters.foundation.tensionless || !contact.converged ||
        !carried_on_knife_edge(mindlin_plate->get_foundation_space(), contact))
      return;
    knife_edge_warned = true;
    warn("cycle " + std::to_string(summary.count("cycle")) +
         ": the plate balances on a line of contact nodes (a knife edge): "
         "the nodes that hold its tilt about that line carry no pressure "
         "(less than 1e-6 of the largest), so the contact conditions hold "
         "for a range of tilts, and the deflections away from the line are "
         "those of the tilt the solver stopped at (for a scene symmetric "
         "about the line, its mirror image is as valid). Use "
         "Discretization/Symmetry for such a scene, or refine the mesh "
         "there.");
  }

  void
  PlateOnHalfspaceProblem::warn_rounding_floor(const double       residual,
                                               const std::string &what)
  {
    if (!(residual > 0))
      return;
    std::ostringstream w;
    w << "Contact/Solver = iterative: " << what
      << " the gap on the contact set is solved to " << std::setprecision(2)
      << residual << " of the soil's settlement, not to the tolerance "
      << last_solve_tolerance(ConjugateGradientControl().tolerance,
                              *foundation_operator)
      << ": the "
         "plate's deflections exceed the settlement so far that rounding "
         "sets that floor (a plate far more flexible than the soil; "
         "doc/errors-and-limits.md, \"Stiffness ratio\").";
    if (foundation_operator->storage_name() != "sparse")
      w << " Contact/Solver = direct with Foundation operator/Storage = "
           "dense reaches the tolerance.";
    warn(w.str());
  }

  bool
  PlateOnHalfspaceProblem::direct_for_flexible_plate(
    const unsigned int n_foundation_nodes) const
  {
    using Storage = Parameters::FoundationOperator::Storage;
    if (parameters.contact.solver != Parameters::Contact::Solver::automatic ||
        parameters.foundation_operator.storage != Storage::automatic)
      return false;
    const Storage storage = parameters.foundation_storage(n_foundation_nodes);
    if (!Parameters::FoundationOperator::compressed(storage))
      return false;
    // a tenth of the accepted floor: the estimate is good to a factor ten
    const PreconditionerEstimate estimate =
      estimate_preconditioners(*mindlin_plate, *soil);
    return estimate.rounding_floor > 0.1 * accepted_rounding_floor &&
           dense_foundation_memory_shortfall(n_foundation_nodes, false, false)
             .empty();
  }

  Parameters::Contact::Solver
  PlateOnHalfspaceProblem::cycle_solver(
    const unsigned int n_foundation_nodes) const
  {
    return direct_after_failed_iterations || direct_for_flexible_plate_cycle ?
             Parameters::Contact::Solver::direct :
             parameters.contact_solver(n_foundation_nodes);
  }

  void
  PlateOnHalfspaceProblem::estimate_goal_error()
  {
    goal_estimate = GoalErrorEstimate();
    if (!goal)
      return;
    TimerOutput::Scope               scope(timer_output, "goal error estimate");
    Timer                            phase;
    const GoalFunctional::Evaluation value = goal->evaluate(
      *mindlin_plate, contact.plate_solution, pressure_field, contact);
    goal_estimate = PlateOnHalfspace::estimate_goal_error(
      *goal,
      value,
      *mindlin_plate,
      contact,
      pressure_field,
      *contact_solver,
      GoalEstimateScene{computed_loads, *foundation_operator});
    warn_rounding_floor(goal_estimate.adjoint_rounding_limited_residual,
                        "in the goal's adjoint problem");
    add_goal_results(*goal,
                     value,
                     goal_estimate,
                     cycle_summaries.empty() ? nullptr :
                                               &cycle_summaries.back(),
                     parameters.adaptivity.target_error,
                     phase.wall_time(),
                     summary);
  }

  void
  PlateOnHalfspaceProblem::solve_standing_loads()
  {
    // The joints' LTE is that of the deflection the moving loads (patches,
    // axles, point loads) add to the plate under its standing loads
    // (weight, temperature, uniform pressure), as a falling-weight test
    // measures it (doc/formulation.md, "Joints"). Only a grid with joints
    // needs it; without standing loads it is zero.
    standing_solution.reinit(0);
    if (slab_grid->get_joints().empty())
      return;
    // Without moving loads the plate's state is the standing one.
    const LoadList standing = standing_loads(computed_loads);
    if (standing.size() == computed_loads.size())
      {
        standing_solution = contact.plate_solution;
        return;
      }
    const bool has_load   = !standing.empty();
    const bool has_moment = mindlin_plate->get_thermal_load().moment != 0;
    // A weightless curled plate on a tensionless soil is not held: the
    // moving loads alone hold it, and its deflections are theirs.
    if (!has_load && (!has_moment || parameters.foundation.tensionless))
      return;
    const auto solver = create_contact_solver(
      parameters, cycle_solver(summary.count("n_foundation_dofs")), 0, log);
    const ContactState state =
      solver->solve(*mindlin_plate,
                    *foundation_operator,
                    mindlin_plate->load_vector(standing),
                    contact.active_set);
    warn_rounding_floor(state.rounding_limited_residual,
                        "under the standing loads (for the joints' LTE)");
    standing_solution = state.plate_solution;
  }

  void
  PlateOnHalfspaceProblem::postprocess()
  {
    TimerOutput::Scope scope(timer_output, "output");
    solve_standing_loads();
    output->evaluate(*mindlin_plate,
                     contact.plate_solution,
                     pressure_field,
                     contact,
                     *foundation_operator,
                     parameters.output.probe_points,
                     summary,
                     standing_solution);
    summary.set("foundation_storage", foundation_operator->storage_name());
    summary.set_count("foundation_memory_bytes",
                      foundation_operator->memory_consumption() +
                        contact.factor_memory_bytes);
  }

  void
  PlateOnHalfspaceProblem::run_sweep()
  {
    // The last mesh, foundation operator and contact solver serve every
    // position (doc/formulation.md, "Critical position"): a bonded scene's
    // solver solves each load on its factorisation, a tensionless one
    // starts each position's active set from the last.
    TimerOutput::Scope       scope(timer_output, "sweep");
    const Parameters::Loads &loads      = parameters.loads;
    std::vector<bool>        warm_start = contact.active_set;
    std::vector<SweepRow>    rows;
    double                   rounding_limited_residual = 0;
    // the position whose loads the mesh resolves worst
    UnresolvedCells unresolved;
    for (unsigned int step = 0; step < loads.sweep_steps; ++step)
      {
        Interruption::check();
        Timer                phase;
        const Point<2>       offset         = loads.sweep_position(step);
        const LoadList       position_loads = loads_at(offset, true);
        const Vector<double> load = mindlin_plate->load_vector(position_loads);
        ContactState         state;
        if (parameters.foundation.tensionless)
          {
            state = contact_solver->solve(*mindlin_plate,
                                          *foundation_operator,
                                          load,
                                          warm_start);
            AssertThrow(state.converged,
                        ExcMessage("Loads/Sweep: the contact set did not "
                                   "settle within Contact/Max iterations "
                                   "at position " +
                                   std::to_string(step) + "."));
            warm_start = state.active_set;
          }
        else
          {
            state            = contact_solver->solve_linearised(load);
            state.in_contact = contact.in_contact;
          }
        rounding_limited_residual =
          std::max(rounding_limited_residual, state.rounding_limited_residual);
        {
          std::ostringstream mesh;
          mesh << "Loads/Sweep: the last cycle's mesh at position " << step
               << " (offset " << offset[0] << ", " << offset[1] << ")";
          UnresolvedCells here = cells_larger_than_deflection_length(
            position_loads, state, true, mesh.str());
          if (here.excess > unresolved.excess)
            unresolved = std::move(here);
        }
        SweepRow row;
        row.position     = offset;
        row.applied_load = symmetry.n_copies() * mindlin_plate->resultant(load);
        const FieldExtremum w =
          field_maximum(*mindlin_plate, state.plate_solution, PlateQuantity::w);
        const FieldExtremum bottom =
          field_maximum(*mindlin_plate,
                        state.plate_solution,
                        PlateQuantity::principal_stress_bottom);
        const FieldExtremum top =
          field_maximum(*mindlin_plate,
                        state.plate_solution,
                        PlateQuantity::principal_stress_top);
        row.max_w                    = w.value;
        row.max_w_at                 = w.location;
        row.max_stress_bottom        = bottom.value;
        row.max_stress_bottom_at     = bottom.location;
        row.max_stress_top           = top.value;
        row.max_stress_top_at        = top.location;
        const FoundationSpace &space = mindlin_plate->get_foundation_space();
        row.contact_area_fraction    = contact_area(state) / space.area();
        row.min_lte                  = std::numeric_limits<double>::quiet_NaN();
        const std::vector<JointResponse> joints =
          mindlin_plate->joint_responses(state.plate_solution,
                                         standing_solution);
        // the LTE of the joint the axles load most (the largest deflection
        // they add there); far joints' ratios of small deflections say
        // nothing of the transfer
        double most_loaded = 0;
        for (unsigned int j = 0; j < joints.size(); ++j)
          if (std::isfinite(joints[j].lte) && joints[j].w_loaded > most_loaded)
            {
              most_loaded       = joints[j].w_loaded;
              row.min_lte       = joints[j].lte;
              row.min_lte_joint = j;
            }
        row.contact_iterations = state.iterations;
        row.wall_time_s        = phase.wall_time();
        rows.push_back(row);
        if (parameters.output.verbosity > 0)
          log << std::defaultfloat << std::setprecision(6) << "sweep " << step
              << " at (" << offset[0] << ", " << offset[1]
              << "): max s1 bottom " << row.max_stress_bottom << ", top "
              << row.max_stress_top << ", " << row.contact_iterations
              << " contact iterations" << std::endl;
      }
    // no NaN or infinity reaches sweep.csv (doc/errors-and-limits.md)
    for (unsigned int k = 0; k < rows.size(); ++k)
      for (const double value : {rows[k].applied_load,
                                 rows[k].max_w,
                                 rows[k].max_stress_bottom,
                                 rows[k].max_stress_top,
                                 rows[k].contact_area_fraction})
        AssertThrow(std::isfinite(value) && std::abs(value) <= 0.1 * FLT_MAX,
                    ExcMessage("Loads/Sweep: a result at position " +
                               std::to_string(k) +
                               " is not a finite number or beyond 3.4e37; "
                               "the sweep is not written (doc/"
                               "errors-and-limits.md, \"Finite results\")."));
    warn_rounding_floor(rounding_limited_residual,
                        "at the worst of the sweep's positions");
    // the moving loads' edges and lift-off lines (the curled edges stay
    // where the cycles' warning found them)
    if (!unresolved.warning.empty())
      warn(unresolved.warning);
    output->write_sweep(rows);
    bool all_converged = true;
    for (const auto &s : cycle_summaries)
      all_converged = all_converged && s.flag("converged");
    output->write_summary(
      cycle_summaries, symmetry.name(), all_converged, *slab_grid, rows);
  }

  void
  PlateOnHalfspaceProblem::write_output()
  {
    check_results_are_finite();
    TimerOutput::Scope  scope(timer_output, "output");
    Timer               phase;
    const MindlinPlate &plate = *mindlin_plate;
    // Default profile: the centre line y = 0 across the plate.
    Point<2> start = parameters.output.profile_start,
             end   = parameters.output.profile_end;
    if (parameters.output.default_profile)
      {
        double x_min = 0, x_max = 0;
        for (const auto &cell : plate.get_foundation_space().cells)
          for (const Point<2> &v : cell.geometry.get_vertices())
            {
              x_min = std::min(x_min, v[0]);
              x_max = std::max(x_max, v[0]);
            }
        if (symmetry.x)
          x_min = -x_max;
        start = Point<2>(x_min, 0);
        end   = Point<2>(x_max, 0);
      }
    const Vector<double> &solution = contact.plate_solution;
    const unsigned int    cycle    = summary.count("cycle");
    // The files describe the whole plate (doc/outputs.md): a tested gap on
    // a mirror plane is the integral over the basis function's support, of
    // which the computed part holds one half (a quarter at the planes'
    // crossing).
    ContactState           whole_plate;
    const FoundationSpace &space = plate.get_foundation_space();
    const bool             rescale =
      symmetry.n_copies() > 1 && foundation_operator->gap_is_tested();
    if (rescale)
      {
        whole_plate = contact;
        for (unsigned int i = 0; i < whole_plate.gap.size(); ++i)
          whole_plate.gap[i] *= static_cast<double>(symmetry.n_copies()) /
                                space.node_images(i).size();
      }
    const ContactState &written = rescale ? whole_plate : contact;
    output->write_profile(cycle,
                          plate,
                          solution,
                          written,
                          start,
                          end,
                          parameters.output.profile_points);
    output->write_nodes_and_gauss_profile(
      cycle, plate, solution, written, start, end);
    if (parameters.output.vtu)
      output->write_vtu(cycle, plate, solution, written);
    summary.set("output_time_s", phase.wall_time());
    summary.set("wall_time_s",
                cycle_timer.wall_time() + setup_time_s + nested_start_time_s);

    const unsigned int verbosity = parameters.output.verbosity;
    if (verbosity > 0)
      {
        const auto &r = summary;
        log << std::scientific << std::setprecision(6) << "   applied load "
            << r.number("applied_load") << ", contact force "
            << r.number("contact_force") << std::endl
            << "   w in [" << r.number("min_w") << ", " << r.number("max_w")
            << "], q in [" << r.number("min_q") << ", " << r.number("max_q")
            << "]" << std::endl
            << "   nodes in contact " << r.count("contact_nodes")
            << ", contact area fraction " << std::fixed << std::setprecision(4)
            << r.number("contact_area_fraction") << std::defaultfloat
            << std::endl;
        if (parameters.foundation.tensionless)
          log << "   complementarity violation " << std::scientific
              << std::setprecision(1)
              << std::max(r.number("complementarity_violation"), 1e-16)
              << ", tensile nodes " << r.count("tensile_nodes")
              << ", largest penetration "
              << std::max(r.number("max_penetration"), 1e-16)
              << std::defaultfloat << std::endl;
        if (verbosity > 1)
          log << "   wall time " << r.number("wall_time_s") << " s"
              << std::endl;
      }

    cycle_summaries.push_back(summary);
    bool all_converged = true;
    for (const auto &s : cycle_summaries)
      all_converged = all_converged && s.flag("converged");
    output->write_summary(cycle_summaries,
                          symmetry.name(),
                          all_converged,
                          *slab_grid);
    output->write_convergence(cycle_summaries);
  }

  PointValues
  PlateOnHalfspaceProblem::values_at(const Point<2> &x) const
  {
    return output->point_values(*mindlin_plate,
                                contact.plate_solution,
                                pressure_field,
                                x);
  }

  bool
  PlateOnHalfspaceProblem::run_checks() const
  {
    bool all_passed = true;
    for (const Parameters::Check &check : parameters.verification.checks)
      {
        double      value = 0;
        std::string label = check.quantity;
        if (check.at_point)
          {
            PointValues v;
            try
              {
                v = values_at(check.location);
              }
            catch (...)
              {
                // on the first mesh (check_points_on_plate()), off the last:
                // a disk's point beyond its polygon
                log << "check " << label << "(" << check.location[0] << ","
                    << check.location[1]
                    << "): the point is not on the last mesh: FAILED"
                    << std::endl;
                all_passed = false;
                continue;
              }
            std::map<std::string, double> point    = {{"w", v.w},
                                                      {"q", v.q},
                                                      {"Mx", v.mx},
                                                      {"My", v.my}};
            const auto                    stresses = v.stresses.values();
            for (unsigned int i = 0; i < stresses.size(); ++i)
              point[Parameters::fibre_stress_names()[i]] = stresses[i];
            value = point.at(check.quantity);
            std::ostringstream where;
            where << "(" << check.location[0] << "," << check.location[1]
                  << ")";
            label += where.str();
          }
        else
          {
            // a cycle's number, or its goal's as "goal.value"
            // (Parameters::Verification)
            const ResultRecord &last = cycle_summaries.back();
            const auto          dot  = check.quantity.find('.');
            const ResultRecord *record =
              dot == std::string::npos ?
                &last :
                (last.has(check.quantity.substr(0, dot)) ?
                   &last.object(check.quantity.substr(0, dot)) :
                   nullptr);
            const std::string key =
              check.quantity.substr(dot == std::string::npos ? 0 : dot + 1);
            if (record == nullptr || !record->is_number(key))
              {
                log << "check " << label
                    << ": the last cycle has no number of this key: FAILED"
                    << std::endl;
                all_passed = false;
                continue;
              }
            value = record->number(key);
          }
        const double error = std::abs(value - check.reference) /
                             std::max(std::abs(check.reference), 1e-300);
        const bool passed =
          std::isfinite(value) && error <= check.relative_tolerance;
        all_passed = all_passed && passed;
        log << "check " << label << " = " << std::scientific
            << std::setprecision(5) << value << ", reference "
            << check.reference << ", relative error " << std::setprecision(1)
            << error << (passed ? " <= " : " > ") << check.relative_tolerance
            << std::defaultfloat << (passed ? ": ok" : ": FAILED") << std::endl;
      }
    return all_passed;
  }

  std::string
  short_error_message(const std::exception &error)
  {
    // an allocation that failed where no memory guard foresaw it (the
    // mesh, a plate factor): what() says only "std::bad_alloc"
    if (dynamic_cast<const std::bad_alloc *>(&error) != nullptr &&
        dynamic_cast<const std::bad_array_new_length *>(&error) == nullptr)
      return "out of memory (std::bad_alloc): the scene needs more memory "
             "than the process may use. Use fewer cells (Discretization/"
             "Subdivisions, Initial refinements, Adaptivity/Max cells) or, "
             "for the half-space, Foundation operator/Storage = fft or "
             "hierarchical (doc/errors-and-limits.md, \"Memory guard\").";
    // A deal.II exception's own text, not what(): what() is a C string,
    // cut short at a NUL that a quoted value may hold.
    std::string text = error.what();
    if (const auto *deal_error = dynamic_cast<const ExceptionBase *>(&error))
      {
        std::ostringstream info;
        deal_error->print_info(info);
        text = info.str();
      }
    const std::string marker = "Additional information:";
    const auto        at     = text.find(marker);
    std::string       message =
      (at == std::string::npos ? text : text.substr(at + marker.size()));
    message = message.substr(0, message.find("Stacktrace:"));
    // collapse the indentation and line breaks deal.II adds
    std::string collapsed;
    for (const char c : message)
      if (c == '\n' || c == '\t' || c == ' ')
        {
          if (!collapsed.empty() && collapsed.back() != ' ')
            collapsed += ' ';
        }
      else
        collapsed += c;
    while (!collapsed.empty() &&
           (collapsed.back() == ' ' || collapsed.back() == '-'))
      collapsed.pop_back();
    // A value or file name quoted in the message may hold control
    // characters: they are printed escaped, never raw.
    return printable(collapsed);
  }
} // namespace PlateOnHalfspace
