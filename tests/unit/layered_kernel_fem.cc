// The surface settlement of a horizontally layered elastic soil under a
// uniformly loaded circle (pressure p on r < a), computed by the program's
// Hankel integral (settlement_under_uniform_circle, layered_profile.h),
//   w(r) = p a Int_0^inf G(k) J1(k a) J0(k r) dk,
// against an independent method: an axisymmetric linear elasticity finite
// element model of the soil in the r-z plane (z depth, downward), Q2
// elements for (u_r, u_z), strains e_rr = du_r/dr, e_tt = u_r/r, e_zz =
// du_z/dz, 2 e_rz = du_r/dz + du_z/dr, everything integrated with the
// weight r (no quadrature point lies on the axis, where u_r = 0 is
// imposed). The pressure loads the surface z = 0 for r < a, which is free
// elsewhere. Layers are bonded, or frictionless on a rigid base (u_z = 0,
// u_r free there); a frictionless interface between two elastic layers
// would need duplicated horizontal degrees of freedom and is not modelled.
//
// The mesh is a tensor product (subdivided_hyper_rectangle) graded
// geometrically (ratio 1.5) from cells of a/10^4 at the load's edge r = a,
// where the surface stress jumps, and at the surface, with r = a and the
// interfaces on cell boundaries. The truncated domain:
// - over a rigid base: depth = the layers', lateral boundary (u_r = 0) at
//   R = 4000 max(a, depth). Bonded to the base, the response decays
//   exponentially with r/depth (R = 30 depth would do to 1e-11), but a
//   layer on a frictionless base is a membrane in the far field, u_r ~ 1/r:
//   R = 30 depth makes w(a) 1.4e-4 too small, an error falling like R^-2
//   (1e-8 at R = 4000 depth);
// - over a half-space: R = Z = 4000 max(a, depth), and the far boundaries
//   r = R, z = Z carry the exact Boussinesq field of the total load P = p
//   pi a^2 as a point load on the base material, which is the layered
//   soil's far field to leading order (R = Z = 10^4 max(a, depth) changes
//   w by less than 1e-7 relative).
// The solution is converged by uniform refinement of that mesh (three
// meshes, direct solver): the value on the finest mesh is reported, its
// error estimated by Richardson's extrapolation with the observed rate
// (Q2 point values converge like h^4 here, the differences shrink by 13
// to 15 per refinement) and required below 2e-5 relative.
//
// The cases (kPa, m):
// 1. a homogeneous half-space, w(0) = 2 (1 - nu^2) p a / E and w(a) = 4 (1
//    - nu^2) p a / (pi E) exactly: the finite element model (tolerance
//    1e-5) and, for the Hankel integral, a top layer of the base's own
//    material (tolerance 1e-8);
// 2. a soft layer on bedrock (a raft on clay, h = 2a), bonded and
//    frictionless;
// 3. a stiff granular layer (h1 = a, E1/Eb = 8) over the subgrade
//    half-space, under a tyre;
// 4. a pavement's base, subbase and subgrade on bedrock, and the same
//    base and subbase over the subgrade as a half-space.
// 5. a near-rigid disk on clay over bedrock, the program's plate against
//    the finite element model's smooth rigid punch (the plate level).
// The finite element and Hankel values differ by 3e-6 relative at most,
// the finite element model's discretisation error: its Richardson
// extrapolation agrees with the Hankel integral to 5e-7. Loads and moduli
// are chosen so that no printed value lies near a rounding boundary.

#include <deal.II/base/function.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/dofs/dof_handler.h>
#include <deal.II/dofs/dof_tools.h>

#include <deal.II/fe/fe_q.h>
#include <deal.II/fe/fe_system.h>
#include <deal.II/fe/fe_values.h>
#include <deal.II/fe/mapping_q1.h>

#include <deal.II/grid/grid_generator.h>
#include <deal.II/grid/tria.h>

#include <deal.II/lac/affine_constraints.h>
#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_direct.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <deal.II/numerics/vector_tools.h>

#include <plate_on_halfspace/soil/layered_profile.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

/** The mesh's geometric growth ratio and smallest cell (times a). */
constexpr double growth        = 1.5;
constexpr double smallest_cell = 1e-4;

/**
 * Cells filling [0, length], h0 growth^i scaled to fit exactly, no cell larger
 * than h_max.
 */
std::vector<double>
graded(const double length, const double h0, const double h_max)
{
  std::vector<double> steps;
  double              sum = 0, h = std::min(h0, h_max);
  while (sum < length)
    {
      steps.push_back(h);
      sum += h;
      h = std::min(h * growth, h_max);
    }
  if (steps.size() > 1 && sum - length > 0.5 * steps.back())
    {
      sum -= steps.back();
      steps.pop_back();
    }
  for (double &step : steps)
    step *= length / sum;
  return steps;
}

/**
 * Cells h0 growth^i out to @p length, the last one cut to fit (or merged with
 * its neighbour if less than half a cell is left): so that a longer
 * truncated domain only appends cells and the truncation is studied on
 * an otherwise unchanged mesh.
 */
std::vector<double>
outwards(const double length, const double h0)
{
  std::vector<double> steps;
  double              sum = 0, h = h0;
  while (sum + h < length)
    {
      steps.push_back(h);
      sum += h;
      h *= growth;
    }
  if (!steps.empty() && length - sum < 0.5 * h)
    steps.back() += length - sum;
  else
    steps.push_back(length - sum);
  return steps;
}

/**
 * (u_r, u_z) of a point load P on the surface of a homogeneous half-space
 * (Boussinesq), z depth, u_z positive downwards.
 */
class Boussinesq : public Function<2>
{
public:
  Boussinesq(const double P, const double E, const double nu)
    : Function<2>(2)
    , factor(P / (4. * numbers::PI * E / (2. * (1. + nu))))
    , nu(nu)
  {}

  double
  value(const Point<2> &x, const unsigned int component) const override
  {
    const double r = x[0], z = x[1], rho = std::sqrt(r * r + z * z);
    if (component == 1)
      return factor * (2. * (1. - nu) / rho + z * z / (rho * rho * rho));
    return factor *
           (r * z / (rho * rho * rho) - (1. - 2. * nu) * r / (rho * (rho + z)));
  }

private:
  const double factor, nu;
};

/**
 * Surface settlements at the centre and at the circle's edge, and the total
 * force on the circle.
 */
struct Settlements
{
  double centre, edge, force;
};

/**
 * The finite element settlements of @p profile, on the graded mesh refined
 * @p refinements times, under the pressure @p p on r < @p a or, if @p punch
 * is positive, under a smooth rigid punch of radius @p a pressed @p punch
 * into the soil (u_z = punch on r <= a, no shear): then the force is the
 * punch's, 2 pi u.K u / punch (the stiffness K is integrated with the weight
 * r only).
 */
Settlements
finite_element_settlements(const LayeredProfile &profile,
                           const double          a,
                           const double          p,
                           const unsigned int    refinements,
                           const double          punch = 0)
{
  const bool half_space = (profile.base == LayeredProfile::Base::half_space);
  const bool frictionless =
    (profile.interfaces == LayeredProfile::Interfaces::frictionless);
  AssertThrow(!frictionless || (!half_space && profile.layers.size() == 1),
              ExcMessage("Frictionless only for one layer on a rigid base."));
  AssertThrow(punch == 0 || !half_space,
              ExcMessage("A punch only on layers over a rigid base: the far "
                         "field over a half-space needs the force."));
  const double depth  = profile.depth();
  const double length = std::max(a, depth);
  const double R      = 4000. * length;
  const double Z      = half_space ? R : depth;
  const double h_min  = smallest_cell * a;

  // r: towards the load's edge from both sides; z: from the surface down
  // through the layers, no cell larger than half its layer.
  std::vector<double> r_steps = graded(a, h_min, 0.1 * a);
  std::reverse(r_steps.begin(), r_steps.end());
  const std::vector<double> beyond = outwards(R - a, h_min);
  r_steps.insert(r_steps.end(), beyond.begin(), beyond.end());
  std::vector<double> z_steps, interfaces;
  double              h = h_min;
  for (const SoilLayer &layer : profile.layers)
    {
      const std::vector<double> steps =
        graded(layer.thickness, h, std::max(0.5 * layer.thickness, h_min));
      z_steps.insert(z_steps.end(), steps.begin(), steps.end());
      h = growth * steps.back();
      interfaces.push_back((interfaces.empty() ? 0. : interfaces.back()) +
                           layer.thickness);
    }
  if (half_space)
    {
      const std::vector<double> below = outwards(Z - depth, h);
      z_steps.insert(z_steps.end(), below.begin(), below.end());
    }

  // Boundary ids: 0 axis, 1 r = R, 2 surface, 3 bottom.
  Triangulation<2> triangulation;
  GridGenerator::subdivided_hyper_rectangle(
    triangulation, {r_steps, z_steps}, Point<2>(), Point<2>(R, Z), true);
  for (const auto &cell : triangulation.active_cell_iterators())
    {
      const auto layer = std::upper_bound(interfaces.begin(),
                                          interfaces.end(),
                                          cell->center()[1]);
      cell->set_material_id(layer - interfaces.begin());
    }
  triangulation.refine_global(refinements);

  const FESystem<2> fe(FE_Q<2>(2), 2);
  DoFHandler<2>     dof_handler(triangulation);
  dof_handler.distribute_dofs(fe);

  const ComponentMask       radial(std::vector<bool>{true, false});
  const ComponentMask       vertical(std::vector<bool>{false, true});
  AffineConstraints<double> constraints;
  VectorTools::interpolate_boundary_values(
    dof_handler, 0, Functions::ZeroFunction<2>(2), constraints, radial);
  if (half_space)
    {
      const Boussinesq far_field(p * numbers::PI * a * a,
                                 profile.base_youngs_modulus,
                                 profile.base_poissons_ratio);
      for (const types::boundary_id id : {1, 3})
        VectorTools::interpolate_boundary_values(dof_handler,
                                                 id,
                                                 far_field,
                                                 constraints);
    }
  else
    {
      VectorTools::interpolate_boundary_values(
        dof_handler, 1, Functions::ZeroFunction<2>(2), constraints, radial);
      VectorTools::interpolate_boundary_values(dof_handler,
                                               3,
                                               Functions::ZeroFunction<2>(2),
                                               constraints,
                                               frictionless ? vertical :
                                                              ComponentMask());
    }
  if (punch > 0)
    {
      std::map<types::global_dof_index, Point<2>> support;
      DoFTools::map_dofs_to_support_points(MappingQ1<2>(),
                                           dof_handler,
                                           support,
                                           vertical);
      for (const auto &[dof, x] : support)
        if (std::abs(x[1]) < 1e-12 * a && x[0] <= a * (1. + 1e-12))
          {
            constraints.add_line(dof);
            constraints.set_inhomogeneity(dof, punch);
          }
    }
  constraints.close();

  DynamicSparsityPattern dsp(dof_handler.n_dofs());
  DoFTools::make_sparsity_pattern(dof_handler, dsp, constraints, false);
  SparsityPattern sparsity;
  sparsity.copy_from(dsp);
  SparseMatrix<double> matrix(sparsity);
  // The unconstrained stiffness, for the punch's force.
  DynamicSparsityPattern full_dsp(punch > 0 ? dof_handler.n_dofs() : 0);
  if (punch > 0)
    DoFTools::make_sparsity_pattern(dof_handler, full_dsp);
  SparsityPattern full_sparsity;
  full_sparsity.copy_from(full_dsp);
  SparseMatrix<double> full_matrix(full_sparsity);
  Vector<double> rhs(dof_handler.n_dofs()), solution(dof_handler.n_dofs());

  const QGauss<2>                      quadrature(3);
  const QGauss<1>                      face_quadrature(3);
  FEValues<2>                          fe_values(fe,
                        quadrature,
                        update_values | update_gradients |
                          update_quadrature_points | update_JxW_values);
  FEFaceValues<2>                      fe_face_values(fe,
                                 face_quadrature,
                                 update_values | update_quadrature_points |
                                   update_JxW_values);
  const unsigned int                   n = fe.n_dofs_per_cell();
  FullMatrix<double>                   cell_matrix(n, n);
  Vector<double>                       cell_rhs(n);
  std::vector<types::global_dof_index> dof_indices(n);
  // Strains (e_rr, e_tt, e_zz, 2 e_rz) of each shape function.
  std::vector<std::array<double, 4>> strain(n);
  for (const auto &cell : dof_handler.active_cell_iterators())
    {
      const unsigned int id     = cell->material_id();
      const double       E      = id < profile.layers.size() ?
                                    profile.layers[id].youngs_modulus :
                                    profile.base_youngs_modulus;
      const double       nu     = id < profile.layers.size() ?
                                    profile.layers[id].poissons_ratio :
                                    profile.base_poissons_ratio;
      const double       lambda = E * nu / ((1. + nu) * (1. - 2. * nu));
      const double       mu     = E / (2. * (1. + nu));
      fe_values.reinit(cell);
      cell_matrix = 0;
      cell_rhs    = 0;
      for (unsigned int q = 0; q < quadrature.size(); ++q)
        {
          const double r = fe_values.quadrature_point(q)[0];
          for (unsigned int i = 0; i < n; ++i)
            {
              const unsigned int c = fe.system_to_component_index(i).first;
              const Tensor<1, 2> g = fe_values.shape_grad_component(i, q, c);
              if (c == 0)
                strain[i] = {{g[0],
                              fe_values.shape_value_component(i, q, c) / r,
                              0,
                              g[1]}};
              else
                strain[i] = {{0, 0, g[1], g[0]}};
            }
          const double weight = r * fe_values.JxW(q);
          for (unsigned int i = 0; i < n; ++i)
            {
              const std::array<double, 4> &e     = strain[i];
              const double                 trace = e[0] + e[1] + e[2];
              const std::array<double, 4>  stress{
                {lambda * trace + 2 * mu * e[0],
                  lambda * trace + 2 * mu * e[1],
                  lambda * trace + 2 * mu * e[2],
                  mu * e[3]}};
              for (unsigned int j = 0; j < n; ++j)
                cell_matrix(i, j) +=
                  weight *
                  (stress[0] * strain[j][0] + stress[1] * strain[j][1] +
                   stress[2] * strain[j][2] + stress[3] * strain[j][3]);
            }
        }
      for (const unsigned int f : cell->face_indices())
        if (punch == 0 && cell->face(f)->at_boundary() &&
            cell->face(f)->boundary_id() == 2 && cell->face(f)->center()[0] < a)
          {
            fe_face_values.reinit(cell, f);
            for (unsigned int q = 0; q < face_quadrature.size(); ++q)
              for (unsigned int i = 0; i < n; ++i)
                if (fe.system_to_component_index(i).first == 1)
                  cell_rhs(i) += p *
                                 fe_face_values.shape_value_component(i, q, 1) *
                                 fe_face_values.quadrature_point(q)[0] *
                                 fe_face_values.JxW(q);
          }
      cell->get_dof_indices(dof_indices);
      constraints.distribute_local_to_global(
        cell_matrix, cell_rhs, dof_indices, matrix, rhs);
      if (punch > 0)
        full_matrix.add(dof_indices, cell_matrix);
    }

  SparseDirectUMFPACK solver;
  solver.initialize(matrix);
  solver.vmult(solution, rhs);
  constraints.distribute(solution);

  // r = 0 and r = a on the surface are vertices of the mesh.
  Settlements settlements{std::nan(""),
                          std::nan(""),
                          punch > 0 ?
                            2. * numbers::PI *
                              full_matrix.matrix_norm_square(solution) / punch :
                            p * numbers::PI * a * a};
  for (const auto &cell : dof_handler.active_cell_iterators())
    for (const unsigned int v : cell->vertex_indices())
      if (std::abs(cell->vertex(v)[1]) < 1e-12 * a)
        {
          if (std::abs(cell->vertex(v)[0]) < 1e-12 * a)
            settlements.centre = solution(cell->vertex_dof_index(v, 1));
          else if (std::abs(cell->vertex(v)[0] - a) < 1e-12 * a)
            settlements.edge = solution(cell->vertex_dof_index(v, 1));
        }
  return settlements;
}

/**
 * The finest of three meshes' value and its relative error estimate,
 * Richardson's with the observed rate (at most h^4, the differences'
 * ratio capped at 16): an estimate that grows as the observed rate drops,
 * infinite unless the differences shrink.
 */
struct Converged
{
  double value, error_estimate;
};

Converged
richardson(const std::array<double, 3> &values)
{
  const double last = std::abs(values[2] - values[1]);
  const double ratio =
    std::min(16., std::abs(values[1] - values[0]) / std::max(last, 1e-300));
  return {values[2],
          ratio > 1. ? last / (ratio - 1.) / std::abs(values[2]) :
                       std::numeric_limits<double>::infinity()};
}

/**
 * Print the finite element settlements at r = 0 and r = a against the
 * Hankel integral's (relative tolerance 1e-4) and the finite element
 * model's convergence verdicts; return the converged values.
 */
Settlements
compare(const std::string    &name,
        const LayeredProfile &profile,
        const double          a,
        const double          p)
{
  std::array<double, 3> centre, edge;
  for (unsigned int refinements = 0; refinements < 3; ++refinements)
    {
      const Settlements w =
        finite_element_settlements(profile, a, p, refinements);
      centre[refinements] = w.centre;
      edge[refinements]   = w.edge;
    }
  const Converged fem_centre = richardson(centre);
  const Converged fem_edge   = richardson(edge);
  check_below(name + ": finite elements, rel. error estimate w(0)",
              fem_centre.error_estimate,
              2e-5);
  check_below(name + ": finite elements, rel. error estimate w(a)",
              fem_edge.error_estimate,
              2e-5);
  check(name + ": w(0) [m], finite elements vs Hankel",
        fem_centre.value,
        settlement_under_uniform_circle(profile, a, p, 0.),
        1e-4);
  check(name + ": w(a) [m], finite elements vs Hankel",
        fem_edge.value,
        settlement_under_uniform_circle(profile, a, p, a),
        1e-4);
  return {fem_centre.value, fem_edge.value, p * numbers::PI * a * a};
}

int
main()
{
  initlog();
  using Base       = LayeredProfile::Base;
  using Interfaces = LayeredProfile::Interfaces;

  // 1. Homogeneous half-space under a tyre: a top layer (h = a) of the
  // base's own material.
  {
    const double   a = 0.15, p = 700., E = 1e5, nu = 0.3;
    LayeredProfile soil;
    soil.layers               = {{a, E, nu}};
    soil.base                 = Base::half_space;
    soil.base_youngs_modulus  = E;
    soil.base_poissons_ratio  = nu;
    const double exact_centre = 2. * (1. - nu * nu) * p * a / E;
    const double exact_edge   = 4. * (1. - nu * nu) * p * a / (numbers::PI * E);
    const Settlements fem     = compare("homogeneous half-space", soil, a, p);
    check("homogeneous half-space: w(0) [m], finite elements vs exact",
          fem.centre,
          exact_centre,
          1e-5);
    check("homogeneous half-space: w(a) [m], finite elements vs exact",
          fem.edge,
          exact_edge,
          1e-5);
    check("homogeneous half-space: w(0) [m], Hankel vs exact",
          settlement_under_uniform_circle(soil, a, p, 0.),
          exact_centre,
          1e-8);
    check("homogeneous half-space: w(a) [m], Hankel vs exact",
          settlement_under_uniform_circle(soil, a, p, a),
          exact_edge,
          1e-8);
  }

  // 2. A raft on soft clay (h = 2a) over bedrock, bonded and frictionless.
  {
    const double   a = 0.5, p = 100.;
    LayeredProfile soil;
    soil.layers = {{2. * a, 5e4, 0.3}};
    soil.base   = Base::rigid;
    compare("clay on bedrock, bonded", soil, a, p);
    soil.interfaces = Interfaces::frictionless;
    compare("clay on bedrock, frictionless", soil, a, p);
  }

  // 3. A granular layer (h1 = a, E1/Eb = 8) over the subgrade, under a tyre.
  {
    const double   a = 0.15, p = 700.;
    LayeredProfile soil;
    soil.layers              = {{a, 4e5, 0.35}};
    soil.base                = Base::half_space;
    soil.base_youngs_modulus = 5e4;
    soil.base_poissons_ratio = 0.4;
    compare("granular layer over subgrade", soil, a, p);
  }

  // 4. Base, subbase and subgrade on bedrock at 1.5 m; the same base and
  // subbase over the subgrade as a half-space.
  {
    const double   a = 0.15, p = 800.;
    LayeredProfile soil;
    soil.layers = {{0.2, 3e5, 0.35}, {0.3, 1.5e5, 0.35}, {1.0, 5e4, 0.4}};
    soil.base   = Base::rigid;
    compare("pavement on bedrock", soil, a, p);
    soil.layers.pop_back();
    soil.base                = Base::half_space;
    soil.base_youngs_modulus = 5e4;
    soil.base_poissons_ratio = 0.4;
    compare("pavement over subgrade half-space", soil, a, p);
  }

  // 5. A near-rigid disk (radius a, 2a thick) under a central point load on
  // clay (h = 2a) over bedrock: the program's plate against the finite
  // element model's smooth rigid punch, at the tolerance its half-space
  // counterpart meets against the exact punch (tests/app/rigid_disk).
  {
    const double   a = 1., P = 1000., punch = 1e-3;
    LayeredProfile soil;
    soil.layers = {{2. * a, 1e4, 0.3}};
    soil.base   = Base::rigid;
    std::array<double, 3> force;
    for (unsigned int refinements = 0; refinements < 3; ++refinements)
      force[refinements] =
        finite_element_settlements(soil, a, 0., refinements, punch).force;
    const Converged fem = richardson(force);
    check_below("near-rigid disk on clay over bedrock: finite elements, rel. "
                "error estimate of the punch's force",
                fem.error_estimate,
                1e-4);
    std::ostringstream prm;
    prm << "set Output directory = results\n"
        << "subsection Plate\n set Shape = disk\n set Radius = " << a
        << "\n set Thickness = " << 2. * a
        << "\n set Young's modulus = 3e7\n set Poisson's ratio = 0.2\nend\n"
        << "subsection Foundation\n set Model = layered\n set Layers = "
        << 2. * a << ", 1e4, 0.3\n set Base = rigid\n"
        << " set Contact = bonded\nend\n"
        << "subsection Loads\n set Point loads = 0,0," << P << "\nend\n"
        << "subsection Discretization\n set Initial refinements = 2\nend\n"
        << "subsection Adaptivity\n set Cycles = 3\n"
        << " set Refinement = adaptive\n set Refine fraction = 0.3\nend\n"
        << "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n";
    const auto plate = TestTools::run_scene_text(prm.str());
    // w at r = a/2: under the load a Mindlin plate's w has a logarithmic
    // shear singularity.
    check("near-rigid disk on clay over bedrock: w(a/2) [m], plate vs "
          "finite element punch",
          plate->values_at(Point<2>(0.5 * a, 0)).w,
          P * punch / fem.value,
          3e-3);
  }
}
