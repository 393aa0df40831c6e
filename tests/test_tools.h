/**
 * Small helpers shared by the unit tests: scenes from the shipped parameter
 * files, plate variants set past the parameter checks, the hard simple
 * support of the Navier tests.
 */
#ifndef plate_on_halfspace_test_tools_h
#define plate_on_halfspace_test_tools_h

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/fe/component_mask.h>
#include <deal.II/fe/fe_values.h>

#include <deal.II/grid/grid_generator.h>

#include <deal.II/numerics/vector_tools.h>

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

namespace TestTools
{
  using namespace dealii;
  using namespace PlateOnHalfspace;

  /** Run the scene @p text (a whole parameter file), its log discarded. */
  inline std::unique_ptr<PlateOnHalfspaceProblem>
  run_scene_text(const std::string &text)
  {
    SceneParameters parameters;
    parameters.read_from_string(text);
    static std::ostringstream log; // the problem keeps a reference
    auto problem = std::make_unique<PlateOnHalfspaceProblem>(parameters, log);
    problem->run();
    return problem;
  }

  /**
   * The scene text of a rectangular slab @p length_x x @p length_y of
   * thickness @p thickness (E = 3e7, nu = 0.15) on a dense liquid of
   * modulus @p k, bonded or tensionless (@p contact), on Subdivisions
   * @p nx x @p ny refined @p refinements times, quietly, results in
   * ./results; @p extra adds entries (subsections may be entered again).
   */
  inline std::string
  slab_on_dense_liquid(const double       length_x,
                       const double       length_y,
                       const double       thickness,
                       const double       k,
                       const std::string &contact,
                       const unsigned int nx,
                       const unsigned int ny,
                       const unsigned int refinements,
                       const std::string &extra)
  {
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Length x = " << length_x
        << "\n set Length y = " << length_y
        << "\n set Thickness = " << thickness
        << "\n set Young's modulus = 3e7\n set Poisson's ratio = 0.15\nend\n"
        << "subsection Foundation\n set Model = dense liquid\n"
        << " set Modulus of subgrade reaction = " << k
        << "\n set Contact = " << contact << "\nend\n"
        << "subsection Discretization\n set Subdivisions x = " << nx
        << "\n set Subdivisions y = " << ny
        << "\n set Initial refinements = " << refinements << "\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n"
        << extra;
    return prm.str();
  }

  /**
   * The parameter text of parameters/@p scene (tests are in tests/unit, so
   * SOURCE_DIR/../.. is the project) with the entries @p extra appended:
   * quiet, results in ./results, no verification checks, the whole plate
   * (Symmetry = none unless @p extra says otherwise).
   */
  inline std::string
  scene_text(const std::string &scene, const std::string &extra)
  {
    std::ostringstream prm;
    prm << "include " << SOURCE_DIR << "/../../parameters/" << scene << "\n"
        << "set Output directory = results\n"
        // the whole plate: tests look at its node vectors and matrices
        // (a test of symmetry sets Symmetry in @p extra)
        << "subsection Discretization\n set Symmetry = none\nend\n"
        << "subsection Verification\n set Checks =\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n"
        << extra;
    return prm.str();
  }

  /** Run scene_text() of @p scene and @p extra. */
  inline std::unique_ptr<PlateOnHalfspaceProblem>
  solve_scene(const std::string &scene, const std::string &extra)
  {
    return run_scene_text(scene_text(scene, extra));
  }

  /**
   * A run's warnings but the one about cells larger than the length the
   * deflection varies over (checked by app/load_warnings), which coarse
   * test meshes draw as well.
   */
  inline std::vector<std::string>
  warnings_but_resolution(const std::vector<std::string> &all)
  {
    std::vector<std::string> others;
    for (const std::string &w : all)
      if (w.find("over which the deflection varies") == std::string::npos)
        others.push_back(w);
    return others;
  }

  /**
   * The integral of the plate's deflection over the footprint, 1^T M w
   * (= 1^T A q with the Galerkin operator).
   */
  inline double
  integral_of_deflection(const PlateOnHalfspaceProblem &problem)
  {
    Vector<double> mw(problem.contact_state().w.size());
    problem.foundation().mass_matrix().vmult(mw, problem.contact_state().w);
    double integral = 0;
    for (const double v : mw)
      integral += v;
    return integral;
  }

  /**
   * A plate of thickness @p t with D = 1 and nu = 0.3, every other entry
   * (the element and the shear integration among them) at the program's
   * default, read through the parameter code. @p loads: entries of
   * subsection Loads.
   */
  inline SceneParameters
  unit_rigidity_plate(const double t, const std::string &loads = "")
  {
    std::ostringstream text;
    text << std::setprecision(17) << "subsection Plate\n"
         << "  set Thickness = " << t << "\n"
         << "  set Young's modulus = " << 10.92 / (t * t * t) << "\n"
         << "  set Poisson's ratio = 0.3\n"
         << "end\n"
         << "subsection Loads\n"
         << loads << "end\n";
    SceneParameters parameters;
    parameters.read_from_string(text.str());
    return parameters;
  }

  /**
   * The same plate with the given element and shear integration, set
   * directly: the parameter file refuses the unstable combinations
   * (reduced with heterosis or lagrange) that the plate tests examine.
   */
  inline SceneParameters
  unit_rigidity_plate(const std::string &element,
                      const std::string &integration,
                      const double       t,
                      const std::string &loads = "")
  {
    SceneParameters parameters = unit_rigidity_plate(t, loads);
    using D                    = Parameters::Discretization;
    D &d                       = parameters.discretization;
    d.element = (element == "serendipity" ? D::Element::serendipity :
                 element == "heterosis"   ? D::Element::heterosis :
                                            D::Element::lagrange);
    d.shear_integration =
      (integration == "reduced"   ? D::ShearIntegration::reduced :
       integration == "selective" ? D::ShearIntegration::selective :
                                    D::ShearIntegration::full);
    return parameters;
  }

  /**
   * Hard simple support of a rectangle from GridGenerator: w = 0 on the
   * boundary, beta_y = 0 on x = const (boundary ids 0, 1), beta_x = 0 on
   * y = const (ids 2, 3).
   */
  inline void
  hard_simple_support(const DoFHandler<2>       &dof_handler,
                      AffineConstraints<double> &constraints)
  {
    const Functions::ZeroFunction<2> zero(3);
    VectorTools::interpolate_boundary_values(
      dof_handler,
      {{0, &zero}, {1, &zero}, {2, &zero}, {3, &zero}},
      constraints,
      ComponentMask(std::vector<bool>{true, false, false}));
    VectorTools::interpolate_boundary_values(
      dof_handler,
      {{2, &zero}, {3, &zero}},
      constraints,
      ComponentMask(std::vector<bool>{false, true, false}));
    VectorTools::interpolate_boundary_values(
      dof_handler,
      {{0, &zero}, {1, &zero}},
      constraints,
      ComponentMask(std::vector<bool>{false, false, true}));
  }

  /** Deflection and moment Mx at the centre of a plate. */
  struct CentreValues
  {
    double w, mx;
  };

  /**
   * The plate of @p p alone on the square [-1/2, 1/2]^2 with n x n cells
   * and the hard simple support (the Navier problems): centre values.
   */
  inline CentreValues
  simply_supported_square_centre(const SceneParameters &p, const unsigned int n)
  {
    Triangulation<2> triangulation;
    GridGenerator::subdivided_hyper_rectangle(triangulation,
                                              {n, n},
                                              Point<2>(-0.5, -0.5),
                                              Point<2>(0.5, 0.5),
                                              /*colorize=*/true);
    MindlinPlate plate(p.plate, p.discretization);
    plate.setup(triangulation, hard_simple_support);
    plate.assemble_loads(make_loads(p.loads, 0.));
    Vector<double> solution;
    plate.solve_unsupported(solution);
    const auto located = plate.locate(Point<2>(0., 0.));
    return {plate.point_value(solution, Point<2>(0., 0.), 0),
            plate.moments(located.first, located.second, solution).mx};
  }
  /** The 4 x 4 Gauss points of every cell of @p plate: where a goal
   *  estimate's half-space residual evaluates the settlement. */
  inline std::vector<dealii::Point<2>>
  cell_gauss_points(const PlateOnHalfspace::MindlinPlate &plate)
  {
    const dealii::QGauss<2>       rule(4);
    dealii::FEValues<2>           values(plate.get_fe(),
                               rule,
                               dealii::update_quadrature_points);
    std::vector<dealii::Point<2>> points;
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      {
        values.reinit(cell);
        for (const dealii::Point<2> &x : values.get_quadrature_points())
          points.push_back(x);
      }
    return points;
  }
} // namespace TestTools

#endif
