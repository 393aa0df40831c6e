#include <deal.II/base/exceptions.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/fe_values.h>

#include <deal.II/numerics/data_out.h>
#include <deal.II/numerics/data_postprocessor.h>

#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/io/results_output.h>
#include <plate_on_halfspace/plate/field_extrema.h>

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <regex>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
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

    std::string
    two_digits(const unsigned int cycle)
    {
      std::ostringstream s;
      s << std::setw(2) << std::setfill('0') << cycle;
      return s.str();
    }

    /** Where @p name is written before it is renamed into place, so that
     *  a run never leaves a half-written result file. */
    std::filesystem::path
    temporary_path(const std::string &directory, const std::string &name)
    {
      return std::filesystem::path(directory) / ("." + name + ".tmp");
    }
  } // namespace

  ResultsOutput::ResultsOutput(const std::string &directory,
                               const MPI_Comm     communicator)
    : directory(directory)
    , previous_run((std::filesystem::path(directory) / "previous-run").string())
    , failed_run((std::filesystem::path(directory) / "failed-run").string())
    , communicator(communicator)
  {
    if (!writes_files())
      return;
    std::error_code error;
    std::filesystem::create_directories(directory, error);
    AssertThrow(!error && std::filesystem::is_directory(directory),
                ExcMessage("Output directory: cannot create <" + directory +
                           ">: " + error.message()));
    // previous-run/ left by a run that was killed holds the last good
    // results; the files beside it are the killed run's.
    if (std::filesystem::exists(previous_run))
      {
        std::filesystem::remove_all(failed_run);
        move_result_files(directory, failed_run);
      }
    else
      move_result_files(directory, previous_run);
  }

  ResultsOutput::~ResultsOutput()
  {
    if (!finished)
      try
        {
          abandon();
        }
      catch (...)
        {
          // nothing more can be done while unwinding
        }
  }

  bool
  ResultsOutput::is_result_file(const std::string &name)
  {
    static const std::regex pattern(
      R"((summary\.json|convergence\.txt|solution\.pvd|solution-\d+\.vtu|)"
      R"((gauss-profile|profile|nodes)-\d+\.csv))");
    return std::regex_match(name, pattern);
  }

  unsigned int
  ResultsOutput::move_result_files(const std::string &from,
                                   const std::string &to)
  {
    if (!std::filesystem::is_directory(from))
      return 0;
    std::vector<std::filesystem::path> files;
    for (const auto &entry : std::filesystem::directory_iterator(from))
      if (entry.is_regular_file() &&
          is_result_file(entry.path().filename().string()))
        files.push_back(entry.path());
    if (!files.empty())
      std::filesystem::create_directories(to);
    for (const auto &file : files)
      std::filesystem::rename(file,
                              std::filesystem::path(to) / file.filename());
    return files.size();
  }

  bool
  ResultsOutput::writes_files() const
  {
    return rank_in(communicator) == 0;
  }

  void
  ResultsOutput::commit()
  {
    finished = true;
    if (!writes_files())
      return;
    std::filesystem::remove_all(previous_run);
    std::filesystem::remove_all(failed_run);
  }

  std::string
  ResultsOutput::abandon()
  {
    finished = true;
    if (!writes_files())
      return "";
    std::filesystem::remove_all(failed_run);
    const unsigned int written = move_result_files(directory, failed_run);
    move_result_files(previous_run, directory);
    std::filesystem::remove_all(previous_run);
    if (written == 0)
      return "";
    return "The failed run's results are in <" + failed_run +
           ">; the earlier results in <" + directory + "> are kept.";
  }

  void
  ResultsOutput::write_file(const std::string &name,
                            const std::string &text) const
  {
    if (!writes_files())
      return;
    const std::filesystem::path target =
      std::filesystem::path(directory) / name;
    const std::filesystem::path temporary = temporary_path(directory, name);
    {
      std::ofstream file(temporary);
      file << text;
      file.close();
      AssertThrow(file,
                  ExcMessage("Output directory: cannot write <" +
                             temporary.string() + ">."));
    }
    std::filesystem::rename(temporary, target);
  }

  void
  ResultsOutput::evaluate(const MindlinPlate   &plate,
                          const Vector<double> &solution,
                          const Vector<double> &pressure_field,
                          const ContactState   &contact,
                          CycleSummary         &summary,
                          const Vector<double> &standing) const
  {
    // Peaks of the finite element fields over the plate, each with its
    // location: the extremes of the fields, not of samples, so a probe's
    // value does not lie beyond them. q is the nodal pressure field in the
    // w-space, so its peaks bound the nodal values.
    const auto set =
      [](const FieldExtremum &peak, double &value, Point<2> &location) {
        value    = peak.value;
        location = peak.location;
      };
    const FieldExtrema w = field_extrema(plate, solution, PlateQuantity::w);
    set(w.maximum, summary.max_w, summary.max_w_at);
    set(w.minimum, summary.min_w, summary.min_w_at);
    const FieldExtrema q =
      field_extrema(plate, pressure_field, PlateQuantity::w);
    set(q.maximum, summary.max_q, summary.max_q_at);
    set(q.minimum, summary.min_q, summary.min_q_at);
    const FieldExtrema mx = field_extrema(plate, solution, PlateQuantity::mx);
    set(mx.maximum, summary.max_mx, summary.max_mx_at);
    set(mx.minimum, summary.min_mx, summary.min_mx_at);
    const FieldExtrema my = field_extrema(plate, solution, PlateQuantity::my);
    set(my.maximum, summary.max_my, summary.max_my_at);
    set(my.minimum, summary.min_my, summary.min_my_at);
    set(field_maximum(plate, solution, PlateQuantity::principal_moment),
        summary.max_principal_moment,
        summary.max_principal_moment_at);
    set(field_maximum(plate, solution, PlateQuantity::principal_stress_bottom),
        summary.max_principal_stress_bottom,
        summary.max_principal_stress_bottom_at);
    set(field_maximum(plate, solution, PlateQuantity::principal_stress_top),
        summary.max_principal_stress_top,
        summary.max_principal_stress_top_at);

    // per slab and per joint of a grid of slabs; a slab of the mirrored
    // part reads its image
    summary.slabs.clear();
    summary.joints = plate.joint_responses(solution, standing);
    if (const SlabGrid *grid = plate.get_slab_grid();
        grid != nullptr && grid->n_slabs() > 1)
      {
        const MirrorSymmetry &symmetry = plate.get_foundation_space().symmetry;
        for (const Slab &slab : grid->get_slabs())
          {
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
            CycleSummary::SlabPeaks peaks;
            const FieldExtremum     bottom =
              field_maximum(plate,
                            solution,
                            PlateQuantity::principal_stress_bottom,
                            computed);
            const FieldExtremum top = field_maximum(
              plate, solution, PlateQuantity::principal_stress_top, computed);
            peaks.max_principal_stress_bottom = bottom.value;
            peaks.max_principal_stress_bottom_at =
              symmetry.from_computed_part(bottom.location, centre);
            peaks.max_principal_stress_top = top.value;
            peaks.max_principal_stress_top_at =
              symmetry.from_computed_part(top.location, centre);
            summary.slabs.push_back(peaks);
          }
      }

    const FoundationSpace &space    = plate.get_foundation_space();
    const auto [area, contact_area] = space.area_in_contact(contact.in_contact);
    summary.contact_area_fraction   = contact_area / area;
    // Nodes in contact on the whole plate: a node of the computed part
    // stands for its distinct mirror images.
    // The same for the nodes whose pressure coefficient is tensile.
    summary.contact_nodes = 0;
    summary.tensile_nodes = 0;
    for (unsigned int i = 0; i < space.n_nodes(); ++i)
      {
        const unsigned int images =
          space.symmetry.images(space.node_locations[i]).size();
        if (contact.in_contact[i])
          summary.contact_nodes += images;
        if (contact.pressure_coefficients[i] < 0)
          summary.tensile_nodes += images;
      }
    summary.complementarity_violation = contact.complementarity_violation;
    summary.max_penetration           = contact.max_penetration;
    summary.contact_iterations        = contact.iterations;
    summary.converged                 = contact.converged;
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
    values.location    = x;
    values.w           = plate.point_value(solution, y, 0);
    values.q           = plate.point_value(pressure_field, y, 0);
    const auto located = plate.locate(y);
    Moments    m       = plate.moments(located.first, located.second, solution);
    values.mx          = m.mx;
    values.my          = m.my;
    // Mxy, and with it sxy, is odd across each mirror plane the point was
    // reflected in.
    for (unsigned int d = 0; d < 2; ++d)
      if (x[d] != y[d])
        m.mxy = -m.mxy;
    values.stresses = plate.fibre_stresses(m);
    return values;
  }

  void
  ResultsOutput::write_summary(const std::vector<CycleSummary> &cycles,
                               const std::string               &symmetry,
                               const bool                       converged,
                               const SlabGrid                  &slab_grid,
                               const std::vector<SweepRow>     &sweep) const
  {
    nlohmann::ordered_json summary;
    summary["converged"]           = converged;
    summary["symmetry"]            = symmetry;
    const unsigned int n_processes = n_ranks(communicator);
    summary["mpi_processes"]       = n_processes;
    // The mesh's cells are split among the ranks by METIS
    // (partition_plate_mesh()); one rank holds them all.
    summary["partitioner"] = n_processes > 1 ? "metis" : "none";
    summary["cycles"]      = nlohmann::ordered_json::array();
    for (const CycleSummary &c : cycles)
      {
        nlohmann::ordered_json j;
        j["cycle"]                     = c.cycle;
        j["n_cells"]                   = c.n_cells;
        j["n_dofs"]                    = c.n_dofs;
        j["n_foundation_dofs"]         = c.n_foundation_dofs;
        j["contact_iterations"]        = c.contact_iterations;
        j["contact_nodes"]             = c.contact_nodes;
        j["contact_area_fraction"]     = c.contact_area_fraction;
        j["applied_load"]              = c.applied_load;
        j["contact_force"]             = c.contact_force;
        j["complementarity_violation"] = c.complementarity_violation;
        j["tensile_nodes"]             = c.tensile_nodes;
        j["max_penetration"]           = c.max_penetration;
        // each peak and where it is
        const auto peak = [&j](const std::string &name,
                               const double       value,
                               const Point<2>    &location) {
          j[name]         = value;
          j[name + "_at"] = {location[0], location[1]};
        };
        peak("max_w", c.max_w, c.max_w_at);
        peak("min_w", c.min_w, c.min_w_at);
        peak("max_q", c.max_q, c.max_q_at);
        peak("min_q", c.min_q, c.min_q_at);
        peak("max_Mx", c.max_mx, c.max_mx_at);
        peak("min_Mx", c.min_mx, c.min_mx_at);
        peak("max_My", c.max_my, c.max_my_at);
        peak("min_My", c.min_my, c.min_my_at);
        peak("max_principal_moment",
             c.max_principal_moment,
             c.max_principal_moment_at);
        peak("max_principal_stress_bottom",
             c.max_principal_stress_bottom,
             c.max_principal_stress_bottom_at);
        peak("max_principal_stress_top",
             c.max_principal_stress_top,
             c.max_principal_stress_top_at);
        j["wall_time_s"]                   = c.wall_time_s;
        j["assembly_time_s"]               = c.assembly_time_s;
        j["foundation_time_s"]             = c.foundation_time_s;
        j["foundation_integration_time_s"] = c.foundation_integration_time_s;
        j["foundation_compression_time_s"] = c.foundation_compression_time_s;
        j["foundation_factorization_time_s"] =
          c.foundation_factorization_time_s;
        j["solve_time_s"]              = c.solve_time_s;
        j["output_time_s"]             = c.output_time_s;
        j["foundation_storage"]        = c.foundation_storage;
        j["foundation_memory_bytes"]   = c.foundation_memory_bytes;
        j["foundation_nodes_per_rank"] = c.foundation_nodes_per_rank;
        j["converged"]                 = c.converged;
        j["coupled_matrix_rcond"]      = c.coupled_matrix_rcond;
        j["foundation_block_rcond"]    = c.foundation_block_rcond;
        j["probes"]                    = nlohmann::ordered_json::array();
        for (const PointValues &p : c.probes)
          j["probes"].push_back({{"x", p.location[0]},
                                 {"y", p.location[1]},
                                 {"w", p.w},
                                 {"q", p.q},
                                 {"Mx", p.mx},
                                 {"My", p.my},
                                 {"stress_bottom", p.stresses.bottom},
                                 {"stress_top", p.stresses.top}});
        const auto number = [](const double value) {
          return std::isfinite(value) ? nlohmann::ordered_json(value) :
                                        nlohmann::ordered_json(nullptr);
        };
        const SlabGrid *grid = &slab_grid;
        if (grid != nullptr && !c.slabs.empty())
          {
            j["slabs"] = nlohmann::ordered_json::array();
            for (unsigned int s = 0; s < c.slabs.size(); ++s)
              {
                const Slab &slab = grid->get_slabs()[s];
                const auto &p    = c.slabs[s];
                j["slabs"].push_back({{"x1", slab.lower[0]},
                                      {"y1", slab.lower[1]},
                                      {"x2", slab.upper[0]},
                                      {"y2", slab.upper[1]},
                                      {"max_principal_stress_bottom",
                                       number(p.max_principal_stress_bottom)},
                                      {"max_principal_stress_bottom_at",
                                       {p.max_principal_stress_bottom_at[0],
                                        p.max_principal_stress_bottom_at[1]}},
                                      {"max_principal_stress_top",
                                       number(p.max_principal_stress_top)},
                                      {"max_principal_stress_top_at",
                                       {p.max_principal_stress_top_at[0],
                                        p.max_principal_stress_top_at[1]}}});
              }
          }
        if (grid != nullptr && !c.joints.empty())
          {
            j["joints"] = nlohmann::ordered_json::array();
            for (unsigned int k = 0; k < c.joints.size(); ++k)
              {
                const Joint           &joint = grid->get_joints()[k];
                const JointResponse   &r     = c.joints[k];
                nlohmann::ordered_json entry;
                entry["x1"]   = joint.start[0];
                entry["y1"]   = joint.start[1];
                entry["x2"]   = joint.end[0];
                entry["y2"]   = joint.end[1];
                entry["kind"] = joint.axis == 0 ? "transverse" : "longitudinal";
                entry["load_transfer"] =
                  Parameters::Joints::name(joint.transfer);
                entry["lte"]             = number(r.lte);
                entry["lte_at"]          = {r.lte_at[0], r.lte_at[1]};
                entry["w_loaded"]        = r.w_loaded;
                entry["w_unloaded"]      = r.w_unloaded;
                entry["max_shear_force"] = r.max_shear_force;
                if (joint.transfer == Parameters::Joints::LoadTransfer::dowels)
                  {
                    double largest = 0, bearing = 0;
                    entry["dowels"] = nlohmann::ordered_json::array();
                    for (const DowelForce &d : r.dowels)
                      {
                        entry["dowels"].push_back(
                          {{"x", d.location[0]},
                           {"y", d.location[1]},
                           {"force", d.force},
                           {"bearing_stress", d.bearing_stress}});
                        largest = std::max(largest, std::abs(d.force));
                        bearing = std::max(bearing, d.bearing_stress);
                      }
                    entry["max_dowel_force"]          = largest;
                    entry["max_dowel_bearing_stress"] = bearing;
                  }
                j["joints"].push_back(entry);
              }
          }
        if (c.has_goal)
          {
            nlohmann::ordered_json goal;
            goal["quantity"] = c.goal.quantity;
            goal["value"]    = c.goal.value;
            if (c.goal.has_location)
              goal["at"] = {c.goal.location[0], c.goal.location[1]};
            goal["estimated_error"] = c.goal.estimated_error;
            if (c.goal.has_dwr)
              goal["dwr"] = c.goal.dwr;
            else
              goal["dwr"] = nullptr;
            if (c.goal.has_change)
              goal["change"] = c.goal.change;
            else
              goal["change"] = nullptr;
            goal["relative_error"] = c.goal.relative_error;
            goal["time_s"]         = c.goal.time_s;
            j["goal"]              = goal;
          }
        summary["cycles"].push_back(j);
      }
    // Whether the last cycle met Adaptivity/Target error.
    if (!cycles.empty() && cycles.back().has_goal &&
        cycles.back().goal.target_error > 0)
      {
        const CycleSummary::Goal &goal = cycles.back().goal;
        summary["goal_target"]         = {{"quantity", goal.quantity},
                                          {"target_error", goal.target_error},
                                          {"relative_error", goal.relative_error},
                                          {"met", goal.target_met}};
      }
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
      }
    write_file("summary.json", summary.dump(2) + "\n");
  }

  void
  ResultsOutput::write_sweep(const std::vector<SweepRow> &sweep) const
  {
    std::ostringstream csv;
    csv << "step,x,y,max_w,max_w_x,max_w_y,max_s1_bottom,max_s1_bottom_x,"
           "max_s1_bottom_y,max_s1_top,max_s1_top_x,max_s1_top_y,"
           "contact_area_fraction,min_lte,min_lte_joint,contact_iterations,"
           "wall_time_s\n"
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
        csv << ',' << r.contact_iterations << ',' << r.wall_time_s << '\n';
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
    std::ostringstream     nodes;
    nodes << "x,y,w,q,gap,contact\n" << std::setprecision(10);
    // The whole plate: the nodes of the computed part and, for a symmetric
    // scene, their distinct mirror images.
    for (unsigned int i = 0; i < space.n_nodes(); ++i)
      for (const Point<2> &x : space.symmetry.images(space.node_locations[i]))
        nodes << x[0] << ',' << x[1] << ',' << contact.w[i] << ','
              << contact.q[i] << ',' << contact.gap[i] << ','
              << (contact.in_contact[i] ? 1 : 0) << '\n';
    write_file("nodes-" + two_digits(cycle) + ".csv", nodes.str());

    // Gauss points of the cells the line crosses or borders, keeping those
    // nearest to the line in each cell.
    const Tensor<1, 2> direction = (end - start) / end.distance(start);
    const auto         distance  = [&](const Point<2> &x) {
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

    DataOut<2> data_out;
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
        // MPI-IO writes them into one file, renamed by rank 0 once complete.
        const types::subdomain_id rank = rank_in(communicator);
        data_out.set_cell_selection(
          [rank](const Triangulation<2>::cell_iterator &cell) {
            return cell->is_active() && cell->subdomain_id() == rank;
          });
        data_out.build_patches(2);
        const std::filesystem::path temporary = temporary_path(directory, name);
        data_out.write_vtu_in_parallel(temporary.string(), communicator);
        if (writes_files())
          std::filesystem::rename(temporary,
                                  std::filesystem::path(directory) / name);
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
  ResultsOutput::write_convergence(ConvergenceTable &table) const
  {
    std::ostringstream text;
    table.write_text(text, TableHandler::org_mode_table);
    write_file("convergence.txt", text.str());
  }
} // namespace PlateOnHalfspace
