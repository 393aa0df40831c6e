#include <deal.II/base/exceptions.h>
#include <deal.II/base/timer.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>
#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>

#include <plate_on_halfspace/base/distributed_sparse_direct.h>
#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/base/sum_over_ranks.h>
#include <plate_on_halfspace/contact/pressure_preconditioner.h>
#include <plate_on_halfspace/halfspace/interface.h>
#include <plate_on_halfspace/plate/mindlin_plate.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace PlateOnHalfspace
{
  namespace
  {
    /** D = this fraction of diag(F) (see PlateOnSpringsPreconditioner). */
    constexpr double spring_flexibility_fraction = 0.1;

    /** (F̃^{-1})_CC: the set does not change it. */
    class SoilInversePreconditioner : public PressurePreconditioner
    {
    public:
      explicit SoilInversePreconditioner(FoundationOperator &foundation)
      {
        const Timer timer;
        inverse = foundation.make_approximate_inverse();
        time    = timer.wall_time();
      }

      void
      use_contact_set(const std::vector<bool> &) override
      {}

      void
      vmult(Vector<double> &y, const Vector<double> &x) const override
      {
        inverse->vmult(y, x);
      }

      std::size_t
      memory_consumption() const override
      {
        return inverse->memory_consumption();
      }

      double
      factorization_time() const override
      {
        return time;
      }

      std::string
      name() const override
      {
        return "soil inverse";
      }

    private:
      std::unique_ptr<ApproximateInverse> inverse;
      double                              time = 0;
    };

    /**
     * The plate on springs (see the header): K + U^T D^{-1} U factorised
     * for the set of the last use_contact_set() that changed it, with
     * U = B_C N (the springs act on the foundation deflections through the
     * test coupling B, the same coupling as the gap).
     */
    class PlateOnSpringsPreconditioner : public PressurePreconditioner
    {
    public:
      PlateOnSpringsPreconditioner(const MindlinPlate       &plate,
                                   const FoundationOperator &foundation);

      void
      use_contact_set(const std::vector<bool> &contact_set) override;

      void
      vmult(Vector<double> &y, const Vector<double> &x) const override;

      std::size_t
      memory_consumption() const override
      {
        // on several processes this rank's share of MUMPS's factor
        return factor.memory_consumption() +
               (distributed ? distributed->memory_consumption() : 0) +
               sparsity.memory_consumption() +
               supported_plate.memory_consumption() +
               soil_diagonal.memory_consumption() *
                 3; // the diagonal, D^{-1} and the set
      }

      double
      factorization_time() const override
      {
        return time;
      }

      std::string
      name() const override
      {
        return "plate on springs";
      }

    private:
      /** f = N^T B_C^T x: the springs' forces on the plate's DoFs. */
      void
      spring_forces(const Vector<double> &x, Vector<double> &f) const;

      const MindlinPlate         &plate;
      const SparseMatrix<double> &test_coupling;
      Vector<double>              soil_diagonal;
      Vector<double>              inverse_springs; ///< D^{-1} on C, else 0
      std::vector<bool>           factored_set;
      SparsityPattern             sparsity;
      SparseMatrix<double>        supported_plate;
      std::vector<types::global_dof_index> solved_dofs;
      SparseCholesky factor{"the plate on springs (Contact/Preconditioner)"};
      std::unique_ptr<DistributedSparseDirect> distributed;
      double                                   time = 0;
    };

    PlateOnSpringsPreconditioner::PlateOnSpringsPreconditioner(
      const MindlinPlate       &plate,
      const FoundationOperator &foundation)
      : plate(plate)
      , test_coupling(foundation.test_coupling())
      , soil_diagonal(foundation.flexibility_diagonal())
    {
      // The diagonal exceeds F on the pressure modes inside the cells, on
      // which the plate is stiff too; springs of a tenth of it halved the
      // iterations per contact set over l/h = 0.1 ... 10 (doc/performance.md,
      // "Preconditioning the contact pressures").
      soil_diagonal *= spring_flexibility_fraction;
      for (unsigned int i = 0; i < soil_diagonal.size(); ++i)
        AssertThrow(soil_diagonal[i] > 0 && std::isfinite(soil_diagonal[i]),
                    ExcMessage("The soil's flexibility has a diagonal entry "
                               "that is not positive: it is not positive "
                               "definite. " +
                               foundation.soil().definiteness_advice()));
      // K's pattern and that of the springs, U^T U on the foundation DoFs
      // (two foundation nodes couple where one pressure coefficient tests
      // both).
      const SparseMatrix<double> &stiffness = plate.get_stiffness_matrix();
      const auto                 &foundation_dofs = plate.get_foundation_dofs();
      const unsigned int          n_dofs          = stiffness.m();
      DynamicSparsityPattern      pattern(n_dofs, n_dofs);
      for (unsigned int row = 0; row < n_dofs; ++row)
        for (auto entry = stiffness.begin(row); entry != stiffness.end(row);
             ++entry)
          pattern.add(row, entry->column());
      std::vector<types::global_dof_index> tested;
      for (unsigned int i = 0; i < test_coupling.m(); ++i)
        {
          tested.clear();
          for (auto b = test_coupling.begin(i); b != test_coupling.end(i); ++b)
            tested.push_back(foundation_dofs[b->column()]);
          std::sort(tested.begin(), tested.end());
          for (const auto row : tested)
            pattern.add_entries(row, tested.begin(), tested.end(), true);
        }
      sparsity.copy_from(pattern);
      supported_plate.reinit(sparsity);
      const AffineConstraints<double> &constraints = plate.get_constraints();
      for (types::global_dof_index i = 0; i < n_dofs; ++i)
        if (!constraints.is_constrained(i))
          solved_dofs.push_back(i);
    }

    void
    PlateOnSpringsPreconditioner::use_contact_set(
      const std::vector<bool> &contact_set)
    {
      if (contact_set == factored_set)
        return;
      const Timer timer;
      factored_set = contact_set;
      inverse_springs.reinit(soil_diagonal.size());
      for (unsigned int i = 0; i < soil_diagonal.size(); ++i)
        if (contact_set[i])
          inverse_springs[i] = 1. / soil_diagonal[i];

      // K + U^T D^{-1} U, U = B_C N.
      const SparseMatrix<double> &stiffness = plate.get_stiffness_matrix();
      const auto                 &foundation_dofs = plate.get_foundation_dofs();
      supported_plate                             = 0.;
      for (unsigned int row = 0; row < stiffness.m(); ++row)
        for (auto entry = stiffness.begin(row); entry != stiffness.end(row);
             ++entry)
          supported_plate.add(row, entry->column(), entry->value());
      for (unsigned int i = 0; i < test_coupling.m(); ++i)
        if (contact_set[i])
          for (auto a = test_coupling.begin(i); a != test_coupling.end(i); ++a)
            for (auto b = test_coupling.begin(i); b != test_coupling.end(i);
                 ++b)
              supported_plate.add(foundation_dofs[a->column()],
                                  foundation_dofs[b->column()],
                                  a->value() * b->value() * inverse_springs[i]);

      // The set carries the plate (the contact solver checks it first), so
      // the springs hold every rigid motion and nothing needs pinning.
      const MPI_Comm communicator = plate.get_communicator();
      if (n_ranks(communicator) > 1)
        {
          std::vector<bool> solved(stiffness.m(), false);
          for (const auto i : solved_dofs)
            solved[i] = true;
          distributed = std::make_unique<DistributedSparseDirect>();
          distributed->factorize(supported_plate,
                                 solved,
                                 plate.locally_owned_dofs(),
                                 communicator);
        }
      else
        factor.factorize(supported_plate, solved_dofs);
      time += timer.wall_time();
    }

    void
    PlateOnSpringsPreconditioner::spring_forces(const Vector<double> &x,
                                                Vector<double>       &f) const
    {
      const auto &foundation_dofs = plate.get_foundation_dofs();
      f.reinit(supported_plate.m());
      for (unsigned int i = 0; i < test_coupling.m(); ++i)
        if (factored_set[i] && x[i] != 0.)
          for (auto b = test_coupling.begin(i); b != test_coupling.end(i); ++b)
            f[foundation_dofs[b->column()]] += b->value() * x[i];
    }

    void
    PlateOnSpringsPreconditioner::vmult(Vector<double>       &y,
                                        const Vector<double> &x) const
    {
      AssertThrow(!factored_set.empty(),
                  ExcMessage("PlateOnSpringsPreconditioner::vmult before "
                             "use_contact_set()."));
      // y = D^{-1} (x - U (K + U^T D^{-1} U)^{-1} U^T D^{-1} x); off the
      // factored set only the springs, y = D^{-1} x.
      const unsigned int n = soil_diagonal.size();
      Vector<double>     scaled(n), f, deflections;
      for (unsigned int i = 0; i < n; ++i)
        scaled[i] = x[i] * inverse_springs[i];
      spring_forces(scaled, f);
      const auto &foundation_dofs = plate.get_foundation_dofs();
      // the deflections at the foundation nodes: all that U needs
      if (distributed)
        distributed->solve_at(f, foundation_dofs, deflections);
      else
        {
          std::vector<double> block(solved_dofs.size());
          for (unsigned int c = 0; c < solved_dofs.size(); ++c)
            block[c] = f[solved_dofs[c]];
          factor.solve(block, 1);
          Vector<double> u(f.size());
          for (unsigned int c = 0; c < solved_dofs.size(); ++c)
            u[solved_dofs[c]] = block[c];
          deflections.reinit(foundation_dofs.size());
          for (unsigned int j = 0; j < foundation_dofs.size(); ++j)
            deflections[j] = u[foundation_dofs[j]];
        }
      y.reinit(n);
      for (unsigned int i = 0; i < n; ++i)
        {
          double tested_deflection = 0;
          if (factored_set[i])
            for (auto b = test_coupling.begin(i); b != test_coupling.end(i);
                 ++b)
              tested_deflection += b->value() * deflections[b->column()];
          y[i] = (x[i] - tested_deflection) / soil_diagonal[i];
        }
    }
  } // namespace

  std::unique_ptr<PressurePreconditioner>
  make_soil_inverse_preconditioner(FoundationOperator &foundation)
  {
    return std::make_unique<SoilInversePreconditioner>(foundation);
  }

  std::unique_ptr<PressurePreconditioner>
  make_plate_on_springs_preconditioner(const MindlinPlate       &plate,
                                       const FoundationOperator &foundation)
  {
    return std::make_unique<PlateOnSpringsPreconditioner>(plate, foundation);
  }

  PreconditionerEstimate
  estimate_preconditioners(const double radius_of_relative_stiffness,
                           const double smallest_cell,
                           const double plate_diameter,
                           const bool   continuum_soil)
  {
    // The symbols of doc/formulation.md ("Preconditioning the contact
    // pressures") in x = k l, k from 2 pi/L (the lowest mode that the
    // rigid motions leave) to pi/h: S/F = x^-e (e = 3 for a continuum, 4
    // for the dense liquid). The springs D exceed F by a factor mu at
    // k = pi/h (the diagonal of a Galerkin matrix against its modes inside
    // the cells; 30 from the iterations measured in doc/performance.md,
    // "Preconditioning the contact pressures") and fall below it like
    // k h/pi for a continuum, while a dense liquid is local at every k.
    const double e  = continuum_soil ? 3. : 4.;
    const double mu = 30;
    const double x0 = 2 * M_PI * radius_of_relative_stiffness / plate_diameter;
    const double x1 = M_PI * radius_of_relative_stiffness / smallest_cell;
    PreconditionerEstimate estimate;
    estimate.soil_inverse = (1. + std::pow(x0, -e)) / (1. + std::pow(x1, -e));
    double largest = 1, smallest = std::numeric_limits<double>::max();
    const unsigned int samples = 400;
    for (unsigned int s = 0; s <= samples; ++s)
      {
        const double x       = x0 * std::pow(x1 / x0, double(s) / samples);
        const double springs = mu * (continuum_soil ? x / x1 : 1.);
        const double lambda =
          (1. + std::pow(x, -e)) / (springs + std::pow(x, -e));
        largest  = std::max(largest, lambda);
        smallest = std::min(smallest, lambda);
      }
    estimate.plate_on_springs = largest / smallest;
    // 50 eps |H q| measured (iterative_solver.cc, rounding_floor_factor)
    estimate.rounding_floor =
      50 * std::numeric_limits<double>::epsilon() * std::pow(x0, -e);
    return estimate;
  }

  PreconditionerEstimate
  estimate_preconditioners(const MindlinPlate &plate, const SoilModel &soil)
  {
    double smallest_cell = std::numeric_limits<double>::max();
    for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
      smallest_cell = std::min(smallest_cell, cell->minimum_vertex_distance());
    const double l =
      soil.radius_of_relative_stiffness(plate.flexural_rigidity());
    const bool continuum = dynamic_cast<const ElasticSoil *>(&soil) != nullptr;
    return estimate_preconditioners(l,
                                    smallest_cell,
                                    maximal_distance(
                                      plate.get_foundation_space()),
                                    continuum);
  }
} // namespace PlateOnHalfspace
