#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <plate_on_halfspace/scene/input_checks.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <filesystem>
#include <fstream>
#include <limits>
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
  } // namespace

  void
  SceneParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Output directory",
                      "output",
                      Patterns::Anything(),
                      "Directory for summary.json, profiles, VTU and "
                      "convergence.txt (created if missing).");
    Parameters::Plate::declare_parameters(prm);
    Parameters::Joints::declare_parameters(prm);
    Parameters::Foundation::declare_parameters(prm);
    Parameters::FoundationOperator::declare_parameters(prm);
    Parameters::Temperature::declare_parameters(prm);
    Parameters::Loads::declare_parameters(prm);
    Parameters::Discretization::declare_parameters(prm);
    Parameters::Contact::declare_parameters(prm);
    Parameters::Adaptivity::declare_parameters(prm);
    Parameters::Output::declare_parameters(prm);
    Parameters::Verification::declare_parameters(prm);
  }

  namespace
  {
    /**
     * Why @p parameters cannot use the hierarchical half-space operator
     * (the message of the first condition it breaks), or "" if it can:
     * Storage = hierarchical is refused with this message, and Storage =
     * auto stays dense.
     */
    std::string
    hierarchical_storage_obstacle(const SceneParameters &parameters)
    {
      if (parameters.contact.solver == Parameters::Contact::Solver::direct)
        return "Foundation operator/Storage = hierarchical needs Contact/"
               "Solver = iterative or auto (the direct solver forms the "
               "dense block the hierarchical matrix avoids).";
      if (parameters.discretization.flexibility !=
          Parameters::Discretization::Flexibility::galerkin)
        return "Foundation operator/Storage = hierarchical needs the "
               "symmetric half-space operator, Discretization/Flexibility "
               "= galerkin.";
      if (parameters.foundation.tensionless &&
          parameters.contact.method != Parameters::Contact::Method::active_set)
        return "Foundation operator/Storage = hierarchical needs Contact/"
               "Method = active set (element exclusion rebuilds the "
               "operator).";
      return "";
    }
  } // namespace

  void
  SceneParameters::parse_parameters(ParameterHandler &prm)
  {
    output_directory = prm.get("Output directory");
    require(!output_directory.empty(), "Output directory must not be empty.");
    plate.parse_parameters(prm);
    joints.parse_parameters(prm);
    foundation.parse_parameters(prm);
    foundation_operator.parse_parameters(prm);
    temperature.parse_parameters(prm);
    loads.parse_parameters(prm);
    discretization.parse_parameters(prm);
    contact.parse_parameters(prm);
    adaptivity.parse_parameters(prm);
    output.parse_parameters(prm);
    verification.parse_parameters(prm);

    if (plate.shape == Parameters::Plate::Shape::slabs)
      joints.check();
    if (discretization.flexibility ==
        Parameters::Discretization::Flexibility::collocation)
      require(plate.shape != Parameters::Plate::Shape::slabs,
              "Discretization/Flexibility = collocation needs one slab: "
              "the nodes facing each other across a joint would collocate "
              "the same settlement twice; use galerkin for Plate/Shape = "
              "slabs.");
    if (discretization.flexibility ==
        Parameters::Discretization::Flexibility::collocation)
      require(plate.shape != Parameters::Plate::Shape::disk,
              "Discretization/Flexibility = collocation needs axis-aligned "
              "rectangular cells (the paper's closed-form integral); use "
              "galerkin for Plate/Shape = disk.");
    if (foundation.model == Parameters::Foundation::Model::dense_liquid)
      {
        // Below this the soil no longer holds the plate in any digit that
        // the flexibility 1/k and its products can carry (tests/unit/
        // temperature_curling's k -> 0 limit uses k t / E = 8e-12).
        const double smallest = 1e-15 * plate.youngs_modulus / plate.thickness;
        std::ostringstream limit;
        limit << smallest << " for this plate (got "
              << foundation.subgrade_modulus << ")";
        require(foundation.subgrade_modulus >= smallest,
                "Foundation/Modulus of subgrade reaction must be at least "
                "1e-15 E/t = " +
                  limit.str() + ": a softer soil does not hold the plate.");
        // The dense liquid is a sparse operator: nothing may densify it,
        // and the paper's element exclusion and collocation belong to the
        // half-space (doc/formulation.md, "Dense-liquid foundation").
        require(foundation_operator.storage ==
                  Parameters::FoundationOperator::Storage::automatic,
                "Foundation operator/Storage applies to the half-space; "
                "with Foundation/Model = dense liquid leave it auto (the "
                "dense liquid is stored sparse).");
        require(contact.solver != Parameters::Contact::Solver::direct,
                "Contact/Solver = direct condenses the plate onto a dense "
                "foundation block; with Foundation/Model = dense liquid use "
                "iterative or auto.");
        require(!foundation.tensionless ||
                  contact.method == Parameters::Contact::Method::active_set,
                "Contact/Method = element exclusion is the paper's method "
                "for the half-space; with Foundation/Model = dense liquid "
                "use active set.");
        require(discretization.flexibility ==
                  Parameters::Discretization::Flexibility::galerkin,
                "Discretization/Flexibility = collocation is the paper's "
                "half-space operator; with Foundation/Model = dense liquid "
                "use galerkin.");
      }
    if (foundation_operator.storage ==
        Parameters::FoundationOperator::Storage::hierarchical)
      {
        const std::string obstacle = hierarchical_storage_obstacle(*this);
        require(obstacle.empty(), obstacle);
      }
    if (adaptivity.goal.kind != Parameters::Goal::Kind::none)
      {
        // doc/formulation.md, "Goal-oriented refinement": the dual problem
        // is the primal one only for a symmetric operator, and the dual
        // weights are reconstructed on patches of 2 x 2 cells.
        require(discretization.flexibility ==
                  Parameters::Discretization::Flexibility::galerkin,
                "Adaptivity/Goal needs the symmetric half-space operator, "
                "Discretization/Flexibility = galerkin (the error estimate "
                "solves the adjoint problem with the same operator).");
        require(discretization.initial_refinements >= 1,
                "Adaptivity/Goal needs Discretization/Initial refinements "
                ">= 1: the error estimate reconstructs the dual solution "
                "on patches of 2 x 2 cells of a refined mesh.");
      }
    if (contact.solver == Parameters::Contact::Solver::iterative)
      {
        require(discretization.flexibility ==
                  Parameters::Discretization::Flexibility::galerkin,
                "Contact/Solver = iterative needs the symmetric half-space "
                "operator, Discretization/Flexibility = galerkin.");
        require(!foundation.tensionless ||
                  contact.method == Parameters::Contact::Method::active_set,
                "Contact/Solver = iterative needs Contact/Method = active "
                "set (element exclusion rebuilds the operator).");
      }
  }

  Parameters::FoundationOperator::Storage
  SceneParameters::foundation_storage(
    const unsigned int n_foundation_nodes) const
  {
    using Storage = Parameters::FoundationOperator::Storage;
    if (foundation.model == Parameters::Foundation::Model::dense_liquid)
      return Storage::sparse;
    if (foundation_operator.storage != Storage::automatic)
      return foundation_operator.storage;
    const bool allowed = hierarchical_storage_obstacle(*this).empty();
    return (allowed &&
            n_foundation_nodes >= foundation_operator.hierarchical_from) ?
             Storage::hierarchical :
             Storage::dense;
  }

  Parameters::Contact::Solver
  SceneParameters::contact_solver(const unsigned int n_foundation_nodes) const
  {
    using Solver = Parameters::Contact::Solver;
    if (contact.solver != Solver::automatic)
      return contact.solver;
    return foundation_storage(n_foundation_nodes) ==
               Parameters::FoundationOperator::Storage::dense ?
             Solver::direct :
             Solver::iterative;
  }

  unsigned int
  SceneParameters::max_goal_foundation_nodes() const
  {
    return foundation.model == Parameters::Foundation::Model::dense_liquid ?
             std::numeric_limits<unsigned int>::max() :
             20000;
  }

  void
  SceneParameters::read(const std::string &filename)
  {
    AssertThrow(std::filesystem::is_regular_file(filename) &&
                  std::ifstream(filename).good(),
                ExcMessage("Cannot open the parameter file <" + filename +
                           ">."));
    std::ostringstream text;
    text << std::ifstream(filename).rdbuf();
    ParameterHandler prm;
    declare_parameters(prm);
    // parse_input() also follows "include other.prm" lines, so tests can
    // derive from the shipped scenes. Its messages name the line, not the
    // section and the allowed values: input_checks.h adds them.
    try
      {
        prm.parse_input(filename);
      }
    catch (const std::exception &error)
      {
        AssertThrow(false,
                    ExcMessage(explain_parameter_file_error(error,
                                                            text.str(),
                                                            filename)));
      }
    parse_parameters(prm);
  }

  void
  SceneParameters::read_from_string(const std::string &text)
  {
    ParameterHandler prm;
    declare_parameters(prm);
    try
      {
        prm.parse_input_from_string(text);
      }
    catch (const std::exception &error)
      {
        // deal.II names a string "input string"
        AssertThrow(false,
                    ExcMessage(explain_parameter_file_error(error,
                                                            text,
                                                            "input string")));
      }
    parse_parameters(prm);
  }
} // namespace PlateOnHalfspace
