#include <deal.II/base/convergence_table.h>
#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <plate_on_halfspace/base/interruption.h>
#include <plate_on_halfspace/base/number_list.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/contact/contact_results.h>
#include <plate_on_halfspace/io/results_output.h>
#include <plate_on_halfspace/plate/field_extrema.h>
#include <plate_on_halfspace/plate/slab_results.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <iomanip>
#include <sstream>
#include <type_traits>
#include <variant>

namespace PlateOnHalfspace
{
  namespace
  {
    /** A record as JSON, its keys in the order of their declarations. */
    nlohmann::ordered_json
    to_json(const ResultRecord &record)
    {
      nlohmann::ordered_json json = nlohmann::ordered_json::object();
      for (const std::string &key : record.keys())
        json[key] = std::visit(
          [](const auto &v) -> nlohmann::ordered_json {
            using T = std::decay_t<decltype(v)>;
            if constexpr (std::is_same_v<T, ResultRecord::Null>)
              return nullptr;
            else if constexpr (std::is_same_v<T, double>)
              return std::isfinite(v) ? nlohmann::ordered_json(v) :
                                        nlohmann::ordered_json(nullptr);
            else if constexpr (std::is_same_v<T, ResultRecord::Nested>)
              {
                if (!v.is_array)
                  return to_json(v.records.front());
                nlohmann::ordered_json array = nlohmann::ordered_json::array();
                for (const ResultRecord &r : v.records)
                  array.push_back(to_json(r));
                return array;
              }
            else
              return nlohmann::ordered_json(v);
          },
          record.value(key));
      return json;
    }

    const bool declared_run = declare_results(
      "",
      0,
      {{{"finished"},
        "–",
        "false while the run is under way (and in an interrupted or killed "
        "run's summary.json); true in the last write of a finished run, just "
        "before `complete`",
        ResultKind::flag},
       {{"converged"},
        "–",
        "true if the run finished and every cycle's contact iteration "
        "converged (false while `finished` is false)",
        ResultKind::flag},
       {{"symmetry"},
        "–",
        "the mirror planes used: `none`, `x`, `y` or `xy`",
        ResultKind::text},
       {{"mpi_processes"},
        "–",
        "the number of MPI processes of the run (1 without `mpirun`; "
        "[parallel.md](parallel.md))",
        ResultKind::count},
       {{"partitioner"},
        "–",
        "how the mesh was split among them: `metis`, or `none` on one "
        "process",
        ResultKind::text},
       {{"cycles"},
        "–",
        "one object per cycle, in order (below)",
        ResultKind::array},
       {{"goal_target"},
        "–",
        "with `Adaptivity/Target error` > 0 only: `quantity`, "
        "`target_error`, the last cycle's `relative_error`, and `met` "
        "(whether the run stopped on reaching it)",
        ResultKind::object},
       {{"sweep"},
        "–",
        "with `Loads/Sweep` only: `steps`, `start`, `end` (the first and "
        "last offsets) and `envelope`: `max_w`, "
        "`max_principal_stress_bottom`, `max_principal_stress_top` (each "
        "`value`, `step`, `position` = the axles' offset, `at` = where on "
        "the plate), `min_lte` (the smallest LTE of the most loaded joint, "
        "with its `joint` index and `at` its middle), "
        "`min_contact_area_fraction`; `null` where no position has the "
        "value; and `applied_load`, the load the plate carries at each "
        "position in order (less than the axles' where a tyre hangs over "
        "the edge, which a `Warning:` line names) ([sweep.csv](#sweepcsv))",
        ResultKind::object}});

    const bool declared_goal_target = declare_results(
      "goal_target",
      0,
      {{{"quantity"}, "–", "the goal as written", ResultKind::text},
       {{"target_error"}, "–", "`Adaptivity/Target error`"},
       {{"relative_error"}, "–", "the last cycle's reported error"},
       {{"met"},
        "–",
        "whether the run stopped on reaching the target",
        ResultKind::flag}});

    const bool declared_probes = declare_results(
      "cycles",
      70,
      {{{"probes"},
        "–",
        "one object per `Output/Probe points` entry, in order (below)",
        ResultKind::array}});

    const bool declared_probe = declare_results(
      "cycles.probes",
      0,
      {{{"x", "y"}, "length", "the point"},
       {{"w"}, "length", "the deflection there"},
       {{"q"}, "force/length²", "the pressure field there"},
       {{"Mx", "My"},
        "force·length/length",
        "the moments there (with the thermal moment)"},
       {{"stress_bottom", "stress_top"},
        "force/length²",
        "`[sxx, syy, sxy]` of the bottom and the top fibre, tension "
        "positive",
        ResultKind::list}});

    /**
     * Mx, My, Mxy from the rotation gradients and the thermal moment
     * (doc/formulation.md, "Conventions" and "Temperature"), and the
     * fibre stresses (MindlinPlate::fibre_stresses()).
     */
    class MomentsPostprocessor : public DataPostprocessor<2>
    {
    public:
      explicit MomentsPostprocessor(const MindlinPlate &plate)
        : plate(plate)
      {}

      void
      evaluate_vector_field(
        const DataPostprocessorInputs::Vector<2> &inputs,
        std::vector<Vector<double>> &computed_quantities) const override
      {
        for (unsigned int p = 0; p < inputs.solution_gradients.size(); ++p)
          {
            const auto &g = inputs.solution_gradients[p];
            // g[c][d] = d u_c / d x_d; components 1, 2 are beta_x, beta_y
            Tensor<2, 2> grad_beta;
            for (unsigned int c = 0; c < 2; ++c)
              grad_beta[c] = g[1 + c];
            const Moments   m   = plate.moments_of_rotation_gradient(grad_beta);
            Vector<double> &out = computed_quantities[p];
            out[0]              = m.mx;
            out[1]              = m.my;
            out[2]              = m.mxy;
            const auto stresses = plate.fibre_stresses(m).values();
            std::copy(stresses.begin(), stresses.end(), out.begin() + 3);
          }
      }

      std::vector<std::string>
      get_names() const override
      {
        std::vector<std::string> names = {"Mx", "My", "Mxy"};
        names.insert(names.end(),
                     Parameters::fibre_stress_names().begin(),
                     Parameters::fibre_stress_names().end());
        return names;
      }

      UpdateFlags
      get_needed_update_flags() const override
      {
        return update_gradients;
      }

    private:
      const MindlinPlate &plate;
    };

    /**
     * DataOut that writes the <Piece> of its own patches alone, as each rank
     * contributes to DataOut::write_vtu_in_parallel() (the default VtkFlags,
     * as there): empty without patches unless @p even_if_empty.
     */
    class PieceDataOut : public DataOut<2>
    {
    public:
      std::string
      piece(const bool even_if_empty = false) const
      {
        std::ostringstream out;
        if (!get_patches().empty() || even_if_empty)
          DataOutBase::write_vtu_main(get_patches(),
                                      get_dataset_names(),
                                      get_nonscalar_data_ranges(),
                                      DataOutBase::VtkFlags(),
                                      out);
        return out.str();
      }
    };

    std::string
    two_digits(const unsigned int cycle)
    {
      std::ostringstream s;
      s << std::setw(2) << std::setfill('0') << cycle;
      return s.str();
    }

  } // namespace

  void
  ResultsOutput::evaluate(const MindlinPlate          &plate,
                          const Vector<double>        &solution,
                          const Vector<double>        &pressure_field,
                          const ContactState          &contact,
                          const FoundationOperator    &foundation,
                          const std::vector<Point<2>> &probe_points,
                          ResultRecord                &record,
                          const Vector<double>        &standing) const
  {
    (void)declared_probes;
    (void)declared_probe;
    add_peak_results(plate, solution, pressure_field, record);
    add_contact_results(plate.get_foundation_space(),
                        foundation,
                        contact,
                        record);
    record.set_empty_array("probes");
    for (const Point<2> &x : probe_points)
      {
        PointValues values;
        try
          {
            values = point_values(plate, solution, pressure_field, x);
          }
        catch (...)
          {
            AssertThrow(false,
                        ExcMessage(
                          "Output/Probe points: " + point_text(x[0], x[1]) +
                          " is not on the plate."));
          }
        ResultRecord &probe = record.add_item("probes");
        probe.set("x", x[0]);
        probe.set("y", x[1]);
        probe.set("w", values.w);
        probe.set("q", values.q);
        probe.set("Mx", values.mx);
        probe.set("My", values.my);
        const FibreStresses &s = values.stresses;
        probe.set("stress_bottom",
                  ResultRecord::Numbers(s.bottom.begin(), s.bottom.end()));
        probe.set("stress_top",
                  ResultRecord::Numbers(s.top.begin(), s.top.end()));
      }
    add_slab_and_joint_results(plate, solution, standing, record);
  }

  PointValues
  ResultsOutput::point_values(const MindlinPlate   &plate,
                              const Vector<double> &solution,
                              const Vector<double> &pressure_field,
                              const Point<2>       &x) const
  {
    // w, q, Mx and My are even across a mirror plane: a point of the
    // mirrored-away part reads its image in the computed part.
    const Point<2> y =
      plate.get_foundation_space().symmetry.to_computed_part(x);
    PointValues values;
    values.location = x;
    values.w        = plate.point_value(solution, y, 0);
    values.q        = plate.point_value(pressure_field, y, 0);
    // The moments jump across cell edges and joints: at a point on an
    // edge, a vertex or a joint, the mean of the cells there, as on the
    // whole plate, where a mirror plane's cells on the other side have the
    // same Mx and My and the opposite Mxy.
    Moments m = plate.mean_moments(plate.cells_at(y), solution);
    if (plate.on_mirror_plane(y))
      m.mxy = 0;
    values.mx = m.mx;
    values.my = m.my;
    // Mxy, and with it sxy, is odd across each mirror plane the point was
    // reflected in (a zero stays +0).
    if (m.mxy != 0)
      m.mxy *= plate.get_foundation_space().symmetry.odd_field_sign(x);
    values.stresses = plate.fibre_stresses(m);
    return values;
  }

  void
  ResultsOutput::write_summary(const std::vector<ResultRecord> &cycles,
                               const std::string               &symmetry,
                               const bool                       converged,
                               const SlabGrid                  &slab_grid,
                               const std::vector<SweepRow>     &sweep)
  {
    // Until commit() the run has not finished: an interrupted or killed
    // run's summary.json must not claim convergence (doc/outputs.md).
    (void)declared_run;
    (void)declared_goal_target;
    ResultRecord run("");
    run.set("finished", false);
    run.set("converged", false);
    run.set("symmetry", symmetry);
    const unsigned int n_processes = n_ranks(communicator);
    run.set_count("mpi_processes", n_processes);
    // The mesh's cells are split among the ranks by METIS
    // (partition_plate_mesh()); one rank holds them all.
    run.set("partitioner", n_processes > 1 ? "metis" : "none");
    run.set_empty_array("cycles");
    for (const ResultRecord &c : cycles)
      run.add_item("cycles") = c;
    // Whether the last cycle met Adaptivity/Target error.
    if (!cycles.empty() && cycles.back().has("goal") &&
        cycles.back().object("goal").number("target_error") > 0)
      {
        const ResultRecord &goal   = cycles.back().object("goal");
        ResultRecord       &target = run.set_object("goal_target");
        target.set("quantity", goal.text("quantity"));
        target.set("target_error", goal.number("target_error"));
        if (goal.is_number("relative_error"))
          target.set("relative_error", goal.number("relative_error"));
        else
          target.set_null("relative_error");
        target.set("met", goal.flag("target_met"));
      }
    if (!sweep.empty())
      run.set_null("sweep");
    nlohmann::ordered_json summary = to_json(run);
    if (!sweep.empty())
      {
        // the envelope: each extreme with the position where it occurs
        const auto extreme = [&](const auto &value, const bool largest) {
          unsigned int best = sweep.size();
          for (unsigned int k = 0; k < sweep.size(); ++k)
            if (std::isfinite(value(sweep[k])) &&
                (best == sweep.size() ||
                 (largest ? value(sweep[k]) > value(sweep[best]) :
                            value(sweep[k]) < value(sweep[best]))))
              best = k;
          return best;
        };
        nlohmann::ordered_json envelope;
        const auto             entry = [&](const std::string &name,
                               const unsigned int k,
                               const double       value,
                               const Point<2>    &at) {
          if (k == sweep.size())
            {
              envelope[name] = nullptr;
              return;
            }
          envelope[name] = {{"value", value},
                            {"step", k},
                            {"position",
                             {sweep[k].position[0], sweep[k].position[1]}},
                            {"at", {at[0], at[1]}}};
        };
        unsigned int k =
          extreme([](const SweepRow &r) { return r.max_w; }, true);
        entry("max_w", k, sweep[k].max_w, sweep[k].max_w_at);
        k =
          extreme([](const SweepRow &r) { return r.max_stress_bottom; }, true);
        entry("max_principal_stress_bottom",
              k,
              sweep[k].max_stress_bottom,
              sweep[k].max_stress_bottom_at);
        k = extreme([](const SweepRow &r) { return r.max_stress_top; }, true);
        entry("max_principal_stress_top",
              k,
              sweep[k].max_stress_top,
              sweep[k].max_stress_top_at);
        k = extreme([](const SweepRow &r) { return r.min_lte; }, false);
        if (k < sweep.size())
          {
            const Joint &joint = slab_grid.get_joints()[sweep[k].min_lte_joint];
            entry("min_lte",
                  k,
                  sweep[k].min_lte,
                  joint.start + 0.5 * (joint.end - joint.start));
            envelope["min_lte"]["joint"] = sweep[k].min_lte_joint;
          }
        else
          envelope["min_lte"] = nullptr;
        k = extreme([](const SweepRow &r) { return r.contact_area_fraction; },
                    false);
        entry("min_contact_area_fraction",
              k,
              sweep[k].contact_area_fraction,
              sweep[k].position);
        envelope["min_contact_area_fraction"].erase("at");
        summary["sweep"] = {
          {"steps", sweep.size()},
          {"start", {sweep.front().position[0], sweep.front().position[1]}},
          {"end", {sweep.back().position[0], sweep.back().position[1]}},
          {"envelope", envelope}};
        // the load each position puts on the plate: less than the axles'
        // where a tyre hangs over the edge (a warning says so)
        nlohmann::ordered_json applied = nlohmann::ordered_json::array();
        for (const SweepRow &r : sweep)
          applied.push_back(r.applied_load);
        summary["sweep"]["applied_load"] = applied;
      }
    summary_text      = summary.dump(2) + "\n";
    summary_converged = converged;
    summary_cycles    = cycles.size();
    write_file("summary.json", summary_text);
  }

  void
  ResultsOutput::write_sweep(const std::vector<SweepRow> &sweep) const
  {
    std::ostringstream csv;
    csv << "step,x,y,max_w,max_w_x,max_w_y,max_s1_bottom,max_s1_bottom_x,"
           "max_s1_bottom_y,max_s1_top,max_s1_top_x,max_s1_top_y,"
           "contact_area_fraction,min_lte,min_lte_joint,contact_iterations,"
           "wall_time_s,applied_load\n"
        << std::setprecision(10);
    for (unsigned int k = 0; k < sweep.size(); ++k)
      {
        const SweepRow &r = sweep[k];
        csv << k << ',' << r.position[0] << ',' << r.position[1] << ','
            << r.max_w << ',' << r.max_w_at[0] << ',' << r.max_w_at[1] << ','
            << r.max_stress_bottom << ',' << r.max_stress_bottom_at[0] << ','
            << r.max_stress_bottom_at[1] << ',' << r.max_stress_top << ','
            << r.max_stress_top_at[0] << ',' << r.max_stress_top_at[1] << ','
            << r.contact_area_fraction << ',';
        if (std::isfinite(r.min_lte))
          csv << r.min_lte << ',' << r.min_lte_joint;
        else
          csv << ',';
        csv << ',' << r.contact_iterations << ',' << r.wall_time_s << ','
            << r.applied_load << '\n';
      }
    write_file("sweep.csv", csv.str());
  }


  void
  ResultsOutput::write_profile(const unsigned int    cycle,
                               const MindlinPlate   &plate,
                               const Vector<double> &solution,
                               const ContactState   &contact,
                               const Point<2>       &start,
                               const Point<2>       &end,
                               const unsigned int    n_points) const
  {
    const Vector<double> pressure =
      plate.foundation_field_to_solution(contact.q);
    std::ostringstream csv;
    csv << "x,y,w,q,Mx,My";
    for (const std::string &name : Parameters::fibre_stress_names())
      csv << ',' << name;
    csv << '\n' << std::setprecision(10);
    for (unsigned int k = 0; k < n_points; ++k)
      {
        // a safe point every 1024 points: a profile of 10^6 points takes
        // tens of seconds (base/interruption.h)
        if (k % 1024 == 0)
          Interruption::check_if_alone();
        const Point<2> x = start + (end - start) * (k / double(n_points - 1));
        PointValues    values;
        try
          {
            values = point_values(plate, solution, pressure, x);
          }
        catch (...)
          {
            continue; // off the plate (e.g. across a disk's polygon)
          }
        csv << x[0] << ',' << x[1] << ',' << values.w << ',' << values.q << ','
            << values.mx << ',' << values.my;
        for (const double s : values.stresses.values())
          csv << ',' << s;
        csv << '\n';
      }
    write_file("profile-" + two_digits(cycle) + ".csv", csv.str());
  }

  void
  ResultsOutput::write_nodes_and_gauss_profile(const unsigned int    cycle,
                                               const MindlinPlate   &plate,
                                               const Vector<double> &solution,
                                               const ContactState   &contact,
                                               const Point<2>       &start,
                                               const Point<2>       &end) const
  {
    const FoundationSpace &space = plate.get_foundation_space();
    // The whole plate: the nodes of the computed part and, for a symmetric
    // scene, their distinct mirror images (FoundationSpace::node_images());
    // written in parts of 4096 nodes (at 10^5 nodes the whole text is 60 MB).
    unsigned int      next = 0;
    std::string       text;
    const std::string name = "nodes-" + two_digits(cycle) + ".csv";
    write_file_in_parts(name, [&](std::string_view &part) {
      Interruption::check_if_alone();
      std::ostringstream rows;
      rows << std::setprecision(10);
      if (next == 0)
        rows << "x,y,w,q,gap,contact\n";
      const unsigned int end = std::min(space.n_nodes(), next + 4096);
      for (; next < end; ++next)
        for (const Point<2> &x : space.node_images(next))
          rows << x[0] << ',' << x[1] << ',' << contact.w[next] << ','
               << contact.q[next] << ',' << contact.gap[next] << ','
               << (contact.in_contact[next] ? 1 : 0) << '\n';
      text = rows.str();
      part = text;
      return next < space.n_nodes();
    });

    // Gauss points of the cells the segment from start to end crosses or
    // borders, keeping those nearest to it in each cell among those that
    // lie across the segment (beside it, not beyond its ends).
    const double       length    = end.distance(start);
    const Tensor<1, 2> direction = (end - start) / length;
    const auto         distance  = [&](const Point<2> &x) {
      const double along = (x - start) * direction;
      if (along < -1e-12 * length || along > (1 + 1e-12) * length)
        return std::numeric_limits<double>::max();
      const Tensor<1, 2> d = x - start;
      return std::abs(d[0] * direction[1] - d[1] * direction[0]);
    };
    const QGauss<2>                    rule(2);
    FEValues<2>                        values(plate.get_fe(),
                       rule,
                       update_gradients | update_quadrature_points);
    std::vector<Tensor<2, 2>>          grad(rule.size());
    std::vector<std::array<double, 4>> rows;
    // (Mx and My are even across mirror planes: the images of a cell's
    // Gauss points, never on a plane, carry its values.)
    std::vector<std::array<double, 2>> transforms = {{{1., 1.}}};
    for (const auto &signs : space.symmetry.reflections())
      transforms.push_back(signs);
    for (const auto &signs : transforms)
      for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
        {
          values.reinit(cell);
          std::vector<Point<2>> points;
          for (const Point<2> &x : values.get_quadrature_points())
            points.emplace_back(signs[0] * x[0], signs[1] * x[1]);
          double nearest = std::numeric_limits<double>::max();
          for (const Point<2> &x : points)
            nearest = std::min(nearest, distance(x));
          if (nearest > cell->diameter() / 2)
            continue;
          values[FEValuesExtractors::Vector(1)].get_function_gradients(solution,
                                                                       grad);
          for (unsigned int q = 0; q < rule.size(); ++q)
            if (distance(points[q]) <= nearest * (1 + 1e-8))
              {
                const Moments m = plate.moments_of_rotation_gradient(grad[q]);
                rows.push_back({{points[q][0], points[q][1], m.mx, m.my}});
              }
        }
    std::sort(rows.begin(), rows.end(), [&](const auto &a, const auto &b) {
      return (Point<2>(a[0], a[1]) - start) * direction <
             (Point<2>(b[0], b[1]) - start) * direction;
    });
    std::ostringstream csv;
    csv << "x,y,Mx,My\n" << std::setprecision(10);
    for (const auto &r : rows)
      csv << r[0] << ',' << r[1] << ',' << r[2] << ',' << r[3] << '\n';
    write_file("gauss-profile-" + two_digits(cycle) + ".csv", csv.str());
  }

  void
  ResultsOutput::write_vtu(const unsigned int    cycle,
                           const MindlinPlate   &plate,
                           const Vector<double> &solution,
                           const ContactState   &contact)
  {
    // q, gap and the contact indicator share the Q2 space of w: pack them
    // into the three components of one vector on the plate's FESystem.
    const auto    &fe = plate.get_fe();
    Vector<double> indicator(contact.q.size());
    for (unsigned int i = 0; i < indicator.size(); ++i)
      indicator[i] = contact.in_contact[i] ? 1. : 0.;
    const Vector<double> fields[3] = {
      plate.foundation_field_to_solution(contact.q),
      plate.foundation_field_to_solution(contact.gap),
      plate.foundation_field_to_solution(indicator)};
    Vector<double>                       packed(solution.size());
    std::vector<types::global_dof_index> dofs(fe.n_dofs_per_cell());
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      {
        cell->get_dof_indices(dofs);
        for (unsigned int i = 0; i < 9; ++i)
          for (unsigned int c = 0; c < 3; ++c)
            packed[dofs[fe.component_to_system_index(c, i)]] =
              fields[c][dofs[fe.component_to_system_index(0, i)]];
      }

    PieceDataOut data_out;
    data_out.attach_dof_handler(plate.get_dof_handler());
    std::vector<DataComponentInterpretation::DataComponentInterpretation>
      solution_kind = {
        DataComponentInterpretation::component_is_scalar,
        DataComponentInterpretation::component_is_part_of_vector,
        DataComponentInterpretation::component_is_part_of_vector};
    data_out.add_data_vector(solution,
                             std::vector<std::string>{"w", "beta", "beta"},
                             DataOut<2>::type_dof_data,
                             solution_kind);
    data_out.add_data_vector(packed,
                             std::vector<std::string>{"q", "gap", "contact"});
    const MomentsPostprocessor moments(plate);
    data_out.add_data_vector(solution, moments);
    // each cell's slab (plate/slab_grid.h): the joints lie where it changes
    Vector<float> slab(
      plate.get_dof_handler().get_triangulation().n_active_cells());
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      slab[cell->active_cell_index()] = cell->material_id();
    data_out.add_data_vector(slab, "slab", DataOut<2>::type_cell_data);
    const std::string name = "solution-" + two_digits(cycle) + ".vtu";
    if (n_ranks(communicator) == 1)
      {
        data_out.build_patches(2);
        std::ostringstream vtu;
        data_out.write_vtu(vtu);
        write_file(name, vtu.str());
      }
    else
      {
        // Every rank holds the whole solution on the whole mesh; each
        // builds the patches of its own cells (partition_plate_mesh()) and
        // sends its <Piece> to rank 0, which writes the one file as every
        // other: to a temporary name created afresh, never through a link.
        // (MPI-IO would open a path on every rank, following whatever link
        // is planted there.)
        const types::subdomain_id rank = rank_in(communicator);
        data_out.set_cell_selection(
          [rank](const Triangulation<2>::cell_iterator &cell) {
            return cell->is_active() && cell->subdomain_id() == rank;
          });
        data_out.build_patches(2);
        const std::vector<std::string> pieces =
          Utilities::MPI::gather(communicator, data_out.piece(), 0);
        if (writes_files())
          {
            std::ostringstream vtu;
            DataOutBase::write_vtu_header(vtu, DataOutBase::VtkFlags());
            bool any = false;
            for (const std::string &piece : pieces)
              {
                vtu << piece;
                any = any || !piece.empty();
              }
            // a file without any piece is not valid VTU: rank 0 writes its
            // empty one (as DataOut::write_vtu_in_parallel() does)
            if (!any)
              vtu << data_out.piece(true);
            DataOutBase::write_vtu_footer(vtu);
            write_file(name, vtu.str());
          }
      }
    if (!writes_files())
      return;

    pvd_records.erase(std::remove_if(pvd_records.begin(),
                                     pvd_records.end(),
                                     [&](const auto &r) {
                                       return r.second == name;
                                     }),
                      pvd_records.end());
    pvd_records.emplace_back(cycle, name);
    std::ostringstream pvd;
    DataOutBase::write_pvd_record(pvd, pvd_records);
    write_file("solution.pvd", pvd.str());
  }

  void
  ResultsOutput::write_convergence(
    const std::vector<ResultRecord> &cycles) const
  {
    // One row per cycle of the declared columns; a quantity's relative
    // change from the previous cycle follows it, "-" on the first (0 would
    // read as converged), and a column a cycle lacks reads "-".
    ConvergenceTable table;
    for (const ConvergenceColumn &column : declared_convergence_columns())
      {
        bool present = false;
        for (const ResultRecord &c : cycles)
          {
            double value;
            present = present || column.value(c, value);
          }
        if (!present)
          continue;
        const std::string change = "change " + column.name;
        for (unsigned int k = 0; k < cycles.size(); ++k)
          {
            double value = 0, previous = 0;
            if (!column.value(cycles[k], value))
              table.add_value(column.name, std::string("-"));
            else if (column.precision == 0 && !column.scientific)
              table.add_value(column.name,
                              static_cast<unsigned long long>(value));
            else
              table.add_value(column.name, value);
            if (!column.with_change)
              continue;
            if (k > 0 && column.value(cycles[k], value) &&
                column.value(cycles[k - 1], previous))
              table.add_value(change,
                              std::abs(value - previous) /
                                std::max(std::abs(value), 1e-300));
            else
              table.add_value(change, std::string("-"));
          }
        table.set_scientific(column.name, column.scientific);
        table.set_precision(column.name, column.precision);
        if (column.with_change)
          {
            table.set_scientific(change, true);
            table.set_precision(change, 2);
          }
      }
    std::ostringstream text;
    table.write_text(text, TableHandler::org_mode_table);
    write_file("convergence.txt", text.str());
  }
} // namespace PlateOnHalfspace
