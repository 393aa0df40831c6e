#include <deal.II/base/timer.h>

#include <deal.II/numerics/solution_transfer.h>

#include <plate_on_halfspace/contact/iterative_solver.h>
#include <plate_on_halfspace/halfspace/memory_guard.h>
#include <plate_on_halfspace/refinement/mesh_refinement.h>
#include <plate_on_halfspace/plate/plate_mesh.h>
#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <cmath>
#include <iomanip>
#include <optional>

namespace PlateOnHalfspace
{
  PlateOnHalfspaceProblem::PlateOnHalfspaceProblem(
    const SceneParameters &parameters,
    std::ostream          &log)
    : parameters(parameters)
    , log(log)
    , timer_output(log, TimerOutput::never, TimerOutput::wall_times)
  {}

  bool
  PlateOnHalfspaceProblem::run()
  {
    output = std::make_unique<ResultsOutput>(parameters.output_directory);
    // A run that fails keeps the earlier run's results (results_output.h).
    try
      {
        // A symmetric scene is solved on the part x >= 0 and/or y >= 0 of the
        // plate (mirror_symmetry.h), cut from the coarse mesh so that its
        // refinements are those of the whole plate's mesh.
        make_coarse_plate_mesh(parameters.plate,
                               parameters.discretization,
                               triangulation);
        symmetry       = choose_mirror_symmetry(parameters, triangulation);
        computed_loads = loads_on_computed_part(parameters.loads, symmetry);
        cut_to_computed_part(symmetry, triangulation);
        triangulation.refine_global(
          parameters.discretization.initial_refinements);
        if (parameters.output.verbosity > 0 && symmetry.n_copies() > 1)
          log << "symmetry " << symmetry.name() << ": computing "
              << (symmetry.n_copies() == 2 ? "half" : "a quarter")
              << " of the plate" << std::endl;

        mindlin_plate =
          std::make_unique<MindlinPlate>(parameters.plate,
                                         parameters.discretization);
        mindlin_plate->set_mirror_symmetry(symmetry);
        {
          TimerOutput::Scope scope(timer_output, "plate setup");
          Timer              setup_timer;
          mindlin_plate->setup(triangulation);
          setup_time_s = setup_timer.wall_time();
        }

        std::vector<bool> seed;
        for (unsigned int cycle = 0; cycle < parameters.adaptivity.cycles;
             ++cycle)
          {
            if (cycle > 0)
              {
                const auto transferred = refine_and_transfer_contact();
                if (!transferred)
                  {
                    log << "Adaptivity/Max cells reached: no further cycles."
                        << std::endl;
                    break;
                  }
                seed = *transferred;
              }
            solve_cycle(cycle, seed);
          }
      }
    catch (...)
      {
        const std::string note = output->abandon();
        if (!note.empty())
          log << note << std::endl;
        throw;
      }
    output->commit();
    if (parameters.output.verbosity > 1)
      timer_output.print_summary();
    return run_checks();
  }

  std::optional<std::vector<bool>>
  PlateOnHalfspaceProblem::refine_and_transfer_contact()
  {
    // the active set (not the wider set where q > 0) seeds the next cycle
    Vector<double> indicator(contact.active_set.size());
    for (unsigned int i = 0; i < indicator.size(); ++i)
      indicator[i] = contact.active_set[i] ? 1. : 0.;
    const Vector<double> old_field =
      mindlin_plate->foundation_field_to_solution(indicator);

    if (!mark_cells_for_refinement(parameters.adaptivity,
                                   *mindlin_plate,
                                   plate_solution,
                                   contact,
                                   parameters.loads,
                                   triangulation))
      return std::nullopt;
    SolutionTransfer<2> transfer(mindlin_plate->get_dof_handler());
    triangulation.prepare_coarsening_and_refinement();
    transfer.prepare_for_coarsening_and_refinement(old_field);
    triangulation.execute_coarsening_and_refinement();
    {
      TimerOutput::Scope scope(timer_output, "plate setup");
      Timer              setup_timer;
      mindlin_plate->setup(triangulation);
      setup_time_s = setup_timer.wall_time();
    }

    Vector<double> new_field(mindlin_plate->get_dof_handler().n_dofs());
    transfer.interpolate(old_field, new_field);
    const Vector<double> nodal =
      mindlin_plate->restrict_to_foundation(new_field);
    std::vector<bool> seed(nodal.size());
    for (unsigned int i = 0; i < nodal.size(); ++i)
      seed[i] = nodal[i] > 0.5;
    return seed;
  }

  void
  PlateOnHalfspaceProblem::solve_cycle(const unsigned int       cycle,
                                       const std::vector<bool> &seed)
  {
    Timer         timer, phase;
    MindlinPlate &plate = *mindlin_plate;
    plate.assemble_loads(computed_loads,
                         parameters.plate.unit_weight *
                           parameters.plate.thickness);

    // Sums over the computed part times the copies that make the plate.
    const double copies = symmetry.n_copies();
    CycleSummary summary;
    summary.cycle                = cycle;
    summary.n_cells              = triangulation.n_active_cells();
    summary.n_dofs               = plate.n_unconstrained_dofs();
    summary.n_foundation_dofs    = plate.get_foundation_dofs().size();
    summary.applied_load         = copies * plate.applied_load();
    const unsigned int verbosity = parameters.output.verbosity;
    if (verbosity > 0)
      log << "cycle " << cycle << ": " << summary.n_cells << " cells, "
          << summary.n_dofs << " dofs, " << summary.n_foundation_dofs
          << " foundation nodes" << std::endl;

    // Storage = auto and Solver = auto are decided for this cycle's mesh.
    const std::string storage =
      parameters.foundation_storage(summary.n_foundation_dofs);
    const bool iterative =
      parameters.iterative_contact_solver(summary.n_foundation_dofs);
    if (!foundation_operator || foundation_operator->storage_name() != storage)
      foundation_operator = create_foundation_operator(parameters, storage);
    if (storage != "hierarchical")
      check_dense_foundation_memory(summary.n_foundation_dofs, iterative);
    LAPACKFullMatrix<double> plate_stiffness;
    Vector<double>           plate_load;
    // The iterative solver works on the sparse plate: no condensation.
    if (!iterative)
      {
        TimerOutput::Scope scope(timer_output, "condense plate");
        plate.condense(plate_stiffness, plate_load);
      }
    summary.assembly_time_s = setup_time_s + phase.wall_time();
    phase.restart();
    {
      TimerOutput::Scope scope(timer_output, "build half-space operator");
      foundation_operator->build(plate.get_foundation_space(), {});
    }
    summary.foundation_time_s = phase.wall_time();
    {
      const auto &times = foundation_operator->build_times();
      summary.foundation_compression_time_s   = times.compression;
      summary.foundation_factorization_time_s = times.factorization;
      summary.foundation_integration_time_s =
        std::max(0.,
                 summary.foundation_time_s - times.compression -
                   times.factorization);
    }
    phase.restart();

    {
      TimerOutput::Scope scope(timer_output, "contact solve");
      if (iterative)
        {
          // A half-space operator that provides products and an
          // approximate inverse itself (a hierarchical matrix) is used as
          // it is; the dense Galerkin operator gets a Cholesky factor of A.
          std::unique_ptr<DenseGalerkinFlexibility> dense;
          const auto                               *flexibility =
            dynamic_cast<const PreconditionedFlexibility *>(
              foundation_operator.get());
          if (flexibility == nullptr)
            {
              dense = std::make_unique<DenseGalerkinFlexibility>(
                *foundation_operator);
              flexibility = dense.get();
            }
          const IterativeContactSolver solver(parameters.contact,
                                              parameters.foundation.tensionless,
                                              ConjugateGradientControl(),
                                              verbosity,
                                              log);
          contact = solver.solve(
            plate, *foundation_operator, *flexibility, seed, &plate_solution);
        }
      else
        {
          const ContactSolver solver(parameters.contact,
                                     parameters.foundation.tensionless,
                                     verbosity,
                                     log);
          contact = solver.solve(plate_stiffness,
                                 plate_load,
                                 *foundation_operator,
                                 plate.get_foundation_space(),
                                 seed);
          plate.expand(contact.w, plate_solution);
        }
      pressure_field = plate.foundation_field_to_solution(contact.q);
    }
    summary.solve_time_s = phase.wall_time();
    phase.restart();
    TimerOutput::Scope output_scope(timer_output, "output");

    // Equilibrium: the integral of q is the sum of the nodal forces M q.
    Vector<double> forces;
    foundation_operator->nodal_forces(contact.pressure_coefficients, forces);
    summary.contact_force =
      copies * std::accumulate(forces.begin(), forces.end(), 0.);
    output->evaluate(plate, plate_solution, contact, summary);
    summary.foundation_storage      = foundation_operator->storage_name();
    summary.foundation_memory_bytes = foundation_operator->memory_consumption();
    summary.coupled_matrix_rcond    = contact.coupled_rcond;
    summary.foundation_block_rcond =
      foundation_operator->contact_block_reciprocal_condition_number();
    for (const Point<2> &x : parameters.output.probe_points)
      {
        try
          {
            summary.probes.push_back(values_at(x));
          }
        catch (...)
          {
            AssertThrow(false,
                        ExcMessage("Output/Probe points: (" +
                                   std::to_string(x[0]) + ", " +
                                   std::to_string(x[1]) +
                                   ") is not on the plate."));
          }
      }

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
    output->write_profile(cycle,
                          plate,
                          plate_solution,
                          contact,
                          start,
                          end,
                          parameters.output.profile_points);
    output->write_nodes_and_gauss_profile(
      cycle, plate, plate_solution, contact, start, end);
    if (parameters.output.vtu)
      output->write_vtu(cycle, plate, plate_solution, contact);
    summary.output_time_s = phase.wall_time();
    summary.wall_time_s   = timer.wall_time() + setup_time_s;

    if (verbosity > 0)
      {
        log << std::scientific << std::setprecision(6) << "   applied load "
            << summary.applied_load << ", contact force "
            << summary.contact_force << std::endl
            << "   w in [" << summary.min_w << ", " << summary.max_w
            << "], q in [" << summary.min_q << ", " << summary.max_q << "]"
            << std::endl
            << "   nodes in contact " << summary.contact_nodes
            << ", contact area fraction " << std::fixed << std::setprecision(4)
            << summary.contact_area_fraction << std::defaultfloat << std::endl;
        if (parameters.foundation.tensionless)
          log << "   complementarity violation " << std::scientific
              << std::setprecision(1)
              << std::max(summary.complementarity_violation, 1e-16)
              << ", tensile nodes " << summary.tensile_nodes
              << ", largest penetration "
              << std::max(summary.max_penetration, 1e-16) << std::defaultfloat
              << std::endl;
        if (verbosity > 1)
          log << "   wall time " << summary.wall_time_s << " s" << std::endl;
      }

    cycle_summaries.push_back(summary);
    bool all_converged = true;
    for (const auto &s : cycle_summaries)
      all_converged = all_converged && s.converged;
    output->write_summary(cycle_summaries, symmetry.name(), all_converged);
    add_convergence_row(summary);
    output->write_convergence(convergence);

    AssertThrow(contact.converged,
                ExcMessage("Contact/Max iterations (" +
                           std::to_string(parameters.contact.max_iterations) +
                           ") reached before the contact set settled."));
  }

  void
  PlateOnHalfspaceProblem::add_convergence_row(const CycleSummary &summary)
  {
    // One row per cycle: size, effort, the quantities of interest with
    // their relative change from the previous cycle, and the time split.
    convergence.add_value("cycle", summary.cycle);
    convergence.add_value("cells", summary.n_cells);
    convergence.add_value("dofs", summary.n_dofs);
    convergence.add_value("foundation dofs", summary.n_foundation_dofs);
    convergence.add_value("contact its", summary.contact_iterations);
    const CycleSummary *previous =
      cycle_summaries.size() > 1 ?
        &cycle_summaries[cycle_summaries.size() - 2] :
        nullptr;
    const auto add_quantity = [&](const std::string &name,
                                  const double       value,
                                  const double       previous_value) {
      convergence.add_value(name, value);
      convergence.set_scientific(name, true);
      convergence.set_precision(name, 6);
      const std::string change = "change " + name;
      // relative change; the first cycle has none ("-": 0 would read as
      // converged)
      if (previous)
        convergence.add_value(change,
                              std::abs(value - previous_value) /
                                std::max(std::abs(value), 1e-300));
      else
        convergence.add_value(change, std::string("-"));
      convergence.set_scientific(change, true);
      convergence.set_precision(change, 2);
    };
    add_quantity("max w", summary.max_w, previous ? previous->max_w : 0.);
    add_quantity("max Mx", summary.max_mx, previous ? previous->max_mx : 0.);
    add_quantity("max q", summary.max_q, previous ? previous->max_q : 0.);
    add_quantity("contact fraction",
                 summary.contact_area_fraction,
                 previous ? previous->contact_area_fraction : 0.);
    convergence.add_value("contact force", summary.contact_force);
    convergence.set_scientific("contact force", true);
    convergence.set_precision("contact force", 6);
    for (const auto &[name, value] :
         std::vector<std::pair<std::string, double>>{
           {"assembly [s]", summary.assembly_time_s},
           {"foundation [s]", summary.foundation_time_s},
           {"solve [s]", summary.solve_time_s},
           {"output [s]", summary.output_time_s},
           {"total [s]", summary.wall_time_s}})
      {
        convergence.add_value(name, value);
        convergence.set_precision(name, 3);
      }
  }

  PointValues
  PlateOnHalfspaceProblem::values_at(const Point<2> &x) const
  {
    return output->point_values(*mindlin_plate,
                                plate_solution,
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
            const PointValues v = values_at(check.location);
            value               = (check.quantity == "w"  ? v.w :
                                   check.quantity == "q"  ? v.q :
                                   check.quantity == "Mx" ? v.mx :
                                                            v.my);
            std::ostringstream where;
            where << "(" << check.location[0] << "," << check.location[1]
                  << ")";
            label += where.str();
          }
        else
          {
            const CycleSummary &s = cycle_summaries.back();
            value = (check.quantity == "applied_load"  ? s.applied_load :
                     check.quantity == "contact_force" ? s.contact_force :
                     check.quantity == "max_w"         ? s.max_w :
                     check.quantity == "min_w"         ? s.min_w :
                     check.quantity == "max_q"         ? s.max_q :
                     check.quantity == "min_q"         ? s.min_q :
                                                         s.contact_area_fraction);
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
    const std::string text   = error.what();
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
    return collapsed;
  }
} // namespace PlateOnHalfspace
