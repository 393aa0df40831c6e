#include <deal.II/base/parallel.h>
#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/dynamic_sparsity_pattern.h>

#include <plate_on_halfspace/base/sparse_cholesky.h>
#include <plate_on_halfspace/halfspace/cell_pair_quadrature.h>
#include <plate_on_halfspace/halfspace/cell_pair_summation.h>
#include <plate_on_halfspace/halfspace/grid_convolution.h>
#include <plate_on_halfspace/halfspace/split_kernel_operator.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <map>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    /** alpha erf(r / sigma) / r, the smooth far field (value at 0 too). */
    double
    far_kernel(const double alpha, const double sigma, const double r)
    {
      return r > 0 ? alpha * std::erf(r / sigma) / r :
                     alpha * 2. / (sigma * std::sqrt(M_PI));
    }

    /**
     * -alpha erf(r / sigma) / r: the remainder that turns the integrator's
     * alpha / r into the near field alpha erfc(r / sigma) / r.
     */
    class MinusFarField : public SmoothRadialFunction
    {
    public:
      MinusFarField(const double alpha, const double sigma)
        : alpha(alpha)
        , sigma(sigma)
      {}

      double
      value(const double r) const override
      {
        return -far_kernel(alpha, sigma, r);
      }

      double
      length_scale() const override
      {
        return sigma;
      }

    private:
      const double alpha, sigma;
    };

    /** The near field's Cholesky factor as F̃^{-1} (see the class doc). */
    class NearFieldInverse : public ApproximateInverse
    {
    public:
      NearFieldInverse(
        std::function<void(Vector<double> &, const Vector<double> &)> solve,
        const std::size_t                                             bytes)
        : solve(std::move(solve))
        , bytes(bytes)
      {}

      void
      vmult(Vector<double> &q, const Vector<double> &s) const override
      {
        solve(q, s);
      }

      std::size_t
      memory_consumption() const override
      {
        return bytes;
      }

    private:
      const std::function<void(Vector<double> &, const Vector<double> &)> solve;
      const std::size_t                                                   bytes;
    };

    /** A term of the near field: computed cell first, cell l (an image). */
    struct Term
    {
      unsigned int first, cell;
    };
  } // namespace

  struct SplitKernelFftOperator::CellPoints
  {
    std::vector<unsigned int> nodes;
    std::vector<Point<2>>     points;
    /** JxW psi_a at point q: [q * nodes.size() + a]. */
    std::vector<double> weighted_values;
    /** The grid nodes and B-spline weights of each point. */
    std::vector<GridConvolution::Stencil> stencils;
  };

  SplitKernelSettings
  split_kernel_settings(const double tolerance)
  {
    // doc/formulation.md, "Split-kernel FFT storage": the cutoff makes the
    // dropped erfc tail a tenth of the tolerance; the spline order and
    // sigma / h bound the gridding error (about (h / sigma)^p), the Gauss
    // points the far field's quadrature on a cell of size sigma.
    SplitKernelSettings settings;
    if (tolerance >= 1e-4)
      settings = {4, 3., 0., 3};
    else if (tolerance >= 1e-5)
      settings = {6, 2.5, 0., 4};
    else if (tolerance >= 1e-6)
      settings = {6, 3., 0., 4};
    else
      settings = {8, 3., 0., 5};
    const double target = 0.1 * tolerance;
    double       low = 0.5, high = 10.;
    for (unsigned int i = 0; i < 60; ++i)
      {
        const double mid                       = 0.5 * (low + high);
        (std::erfc(mid) > target ? low : high) = mid;
      }
    settings.cutoff = high;
    return settings;
  }

  SplitKernelFftOperator::SplitKernelFftOperator(
    std::shared_ptr<const ElasticSoil> soil,
    const double                       tolerance)
    : elastic(std::move(soil))
    , tolerance(tolerance)
  {
    soil_model = elastic;
  }

  SplitKernelFftOperator::~SplitKernelFftOperator() = default;

  void
  SplitKernelFftOperator::build(const FoundationSpace   &space,
                                const std::vector<bool> &cell_in_foundation)
  {
    AssertThrow(std::find(cell_in_foundation.begin(),
                          cell_in_foundation.end(),
                          false) == cell_in_foundation.end(),
                ExcMessage("Foundation operator/Storage = fft does not "
                           "support Contact/Method = element exclusion "
                           "(use active set)."));
    build_mass_matrix(space, cell_in_foundation);
    set_pressure_basis(space, true);
    const SurfaceKernel kernel = elastic->kernel(maximal_distance(space));
    AssertThrow(!kernel.remainder,
                ExcMessage("Foundation operator/Storage = fft holds the "
                           "homogeneous half-space only; Foundation/Model = " +
                           elastic->name() + " needs dense or hierarchical."));
    alpha = kernel.alpha;

    const std::vector<FoundationSpace::Cell> cells =
      CellPairSummation::cells_with_images(space);
    n_computed                       = space.cells.size();
    const unsigned int       n_cells = cells.size();
    const CellPairIntegrator integrator(cells,
                                        elastic->singular_quadrature_order());

    // The split length: the median cell size, so that most cells meet
    // their near field within a few neighbours; the grid no finer than 64
    // nodes per cell on average.
    const SplitKernelSettings settings = split_kernel_settings(tolerance);
    std::vector<double>       sizes(n_computed);
    std::vector<Point<2>>     centres(n_cells);
    std::vector<double>       diameters(n_cells);
    Point<2>                  low(std::numeric_limits<double>::max(),
                 std::numeric_limits<double>::max());
    Point<2>                  high = -low;
    for (unsigned int c = 0; c < n_cells; ++c)
      {
        centres[c]   = cells[c].geometry.map(Point<2>(0.5, 0.5));
        diameters[c] = cells[c].geometry.diameter();
        if (c < n_computed)
          sizes[c] = std::sqrt(cells[c].geometry.area());
        for (const Point<2> &v : cells[c].geometry.get_vertices())
          for (unsigned int d = 0; d < 2; ++d)
            {
              low[d]  = std::min(low[d], v[d]);
              high[d] = std::max(high[d], v[d]);
            }
      }
    std::nth_element(sizes.begin(),
                     sizes.begin() + sizes.size() / 2,
                     sizes.end());
    double       sigma   = sizes[sizes.size() / 2];
    const double area    = (high[0] - low[0]) * (high[1] - low[1]);
    sigma                = std::max(sigma,
                     settings.sigma_over_h * std::sqrt(area / (64. * n_cells)));
    const double spacing = sigma / settings.sigma_over_h;
    const double cutoff  = settings.cutoff * sigma;

    // The far field: Gauss points on every cell, more on cells larger
    // than sigma (its quadrature error grows with size / sigma).
    far_points.assign(n_computed, CellPoints());
    std::size_t n_points = 0;
    for (unsigned int c = 0; c < n_computed; ++c)
      {
        const double       ratio = diameters[c] / (std::sqrt(2.) * sigma);
        const unsigned int m =
          std::max(settings.gauss_points,
                   static_cast<unsigned int>(
                     std::ceil(settings.gauss_points * ratio - 1e-9)));
        const QGauss<2> rule(std::min(m, 64u));
        CellPoints     &cp = far_points[c];
        cp.nodes           = integrator.nodes(c);
        integrator.tabulate(c, rule, cp.points, cp.weighted_values);
        n_points += cp.points.size();
      }
    // The grid is symmetric about its centre: on the mirror planes, so
    // that the images' charges are the reflected grid charges.
    Point<2> centre = 0.5 * (low + high);
    if (space.symmetry.x)
      centre[0] = 0.;
    if (space.symmetry.y)
      centre[1] = 0.;
    reflections = space.symmetry.reflections();
    grid        = std::make_unique<GridConvolution>(
      centre,
      spacing,
      std::array<double, 2>{
               {std::max(high[0] - centre[0], centre[0] - low[0]) + spacing,
                std::max(high[1] - centre[1], centre[1] - low[1]) + spacing}},
      settings.spline_order,
      [a = alpha, sigma](const double r) { return far_kernel(a, sigma, r); });

    // The near field's terms, in CellPairSummation's canonical order
    // (first, other, image), from buckets as wide as the reach of a pair.
    const double largest =
      *std::max_element(diameters.begin(), diameters.end());
    const double width  = cutoff + largest;
    const auto   bucket = [&](const Point<2> &p) {
      return std::make_pair(static_cast<long long>(std::floor(p[0] / width)),
                            static_cast<long long>(std::floor(p[1] / width)));
    };
    std::map<std::pair<long long, long long>, std::vector<unsigned int>>
      buckets;
    for (unsigned int c = 0; c < n_cells; ++c)
      buckets[bucket(centres[c])].push_back(c);
    std::vector<Term>                                  terms;
    std::vector<std::pair<unsigned int, unsigned int>> singular;
    std::vector<std::pair<unsigned int, unsigned int>> candidates;
    for (unsigned int first = 0; first < n_computed; ++first)
      {
        candidates.clear();
        const auto home = bucket(centres[first]);
        for (long long dx = -1; dx <= 1; ++dx)
          for (long long dy = -1; dy <= 1; ++dy)
            {
              const auto found =
                buckets.find({home.first + dx, home.second + dy});
              if (found == buckets.end())
                continue;
              for (const unsigned int l : found->second)
                {
                  const unsigned int other = l % n_computed, r = l / n_computed;
                  const double       gap = centres[first].distance(centres[l]) -
                                     0.5 * (diameters[first] + diameters[l]);
                  if (other >= first && gap < cutoff)
                    candidates.emplace_back(other, r);
                }
            }
        std::sort(candidates.begin(), candidates.end());
        for (const auto &[other, r] : candidates)
          {
            const unsigned int l = r * n_computed + other;
            terms.push_back({first, l});
            if (integrator.singular_pair(first, l))
              singular.emplace_back(first, l);
          }
      }
    const auto near_remainder = std::make_shared<MinusFarField>(alpha, sigma);
    const SurfaceKernel near_kernel(alpha, near_remainder);
    integrator.integrate_singular_pairs(singular, near_remainder.get());

    {
      DynamicSparsityPattern pattern(space.n_nodes());
      for (const Term &t : terms)
        {
          const auto &a = integrator.nodes(t.first),
                     &b = integrator.nodes(t.cell);
          for (const unsigned int i : a)
            for (const unsigned int j : b)
              {
                pattern.add(i, j);
                pattern.add(j, i);
              }
        }
      near_sparsity.copy_from(pattern);
    }
    near_field.reinit(near_sparsity);

    // Integrate in chunks (tasks), scatter each chunk in order: the sum
    // does not depend on the threads.
    const std::size_t               chunk = 16384;
    std::vector<FullMatrix<double>> blocks(std::min(chunk, terms.size()));
    for (std::size_t begin = 0; begin < terms.size(); begin += chunk)
      {
        const std::size_t end = std::min(terms.size(), begin + chunk);
        parallel::apply_to_subranges(
          begin,
          end,
          [&](const std::size_t from, const std::size_t to) {
            const std::vector<bool> all;
            for (std::size_t k = from; k < to; ++k)
              {
                const Term &t = terms[k];
                integrator.integrate_kernel(
                  t.first, t.cell, near_kernel, blocks[k - begin], all, all);
                if (t.first == t.cell % n_computed && t.cell >= n_computed)
                  symmetrise_self_image_block(integrator.nodes(t.first),
                                              integrator.nodes(t.cell),
                                              blocks[k - begin]);
              }
          },
          64);
        for (std::size_t k = begin; k < end; ++k)
          {
            const Term               &t     = terms[k];
            const FullMatrix<double> &block = blocks[k - begin];
            const auto               &a     = integrator.nodes(t.first),
                       &b                   = integrator.nodes(t.cell);
            const bool transposed           = t.first != t.cell % n_computed;
            for (unsigned int i = 0; i < a.size(); ++i)
              for (unsigned int j = 0; j < b.size(); ++j)
                {
                  near_field.add(a[i], b[j], block(i, j));
                  if (transposed)
                    near_field.add(b[j], a[i], block(i, j));
                }
          }
      }

    for (CellPoints &cp : far_points)
      {
        cp.stencils.resize(cp.points.size());
        for (unsigned int q = 0; q < cp.points.size(); ++q)
          cp.stencils[q] = grid->stencil(cp.points[q]);
      }

    chosen.sigma             = sigma;
    chosen.spacing           = spacing;
    chosen.cutoff            = cutoff;
    chosen.spline_order      = settings.spline_order;
    chosen.grid_nodes        = grid->n_grid_nodes();
    chosen.near_entries      = near_sparsity.n_nonzero_elements();
    chosen.near_pairs        = terms.size();
    chosen.quadrature_points = n_points;
  }

  void
  SplitKernelFftOperator::apply_far_field(const Vector<double> &values,
                                          Vector<double> &settlement) const
  {
    // Spread the computed cells' charges in a fixed number of parts, each
    // onto its own grid, summed in order: the same sum with any number of
    // threads.
    constexpr unsigned int           n_parts = 4;
    std::vector<std::vector<double>> parts(n_parts);
    const auto                       part_range = [&](const unsigned int part) {
      return std::make_pair(std::size_t(n_computed) * part / n_parts,
                            std::size_t(n_computed) * (part + 1) / n_parts);
    };
    parallel::apply_to_subranges(
      0u,
      n_parts,
      [&](const unsigned int from, const unsigned int to) {
        for (unsigned int part = from; part < to; ++part)
          {
            parts[part]       = grid->new_field();
            const auto [b, e] = part_range(part);
            for (std::size_t c = b; c < e; ++c)
              {
                const CellPoints  &cp = far_points[c];
                const unsigned int n  = cp.nodes.size();
                for (unsigned int q = 0; q < cp.points.size(); ++q)
                  {
                    double charge = 0;
                    for (unsigned int a = 0; a < n; ++a)
                      charge +=
                        cp.weighted_values[q * n + a] * values[cp.nodes[a]];
                    grid->spread(cp.stencils[q], charge, parts[part].data());
                  }
              }
          }
      },
      1);
    std::vector<double> charges = std::move(parts[0]), potentials;
    for (unsigned int part = 1; part < n_parts; ++part)
      for (std::size_t k = 0; k < charges.size(); ++k)
        charges[k] += parts[part][k];
    // The mirror images carry the same pressure at the reflected points
    // (doc/formulation.md, "Symmetry").
    grid->add_reflections(charges, reflections);
    grid->convolve(charges, potentials);
    // Potentials at each point in parallel, then added to the nodes in
    // order.
    std::vector<std::vector<double>> at_points(n_computed);
    parallel::apply_to_subranges(
      0u,
      n_computed,
      [&](const unsigned int from, const unsigned int to) {
        for (unsigned int c = from; c < to; ++c)
          {
            const CellPoints &cp = far_points[c];
            at_points[c].resize(cp.points.size());
            for (unsigned int q = 0; q < cp.points.size(); ++q)
              at_points[c][q] =
                grid->interpolate(cp.stencils[q], potentials.data());
          }
      },
      256);
    for (unsigned int c = 0; c < n_computed; ++c)
      {
        const CellPoints  &cp = far_points[c];
        const unsigned int n  = cp.nodes.size();
        for (unsigned int q = 0; q < cp.points.size(); ++q)
          for (unsigned int a = 0; a < n; ++a)
            settlement[cp.nodes[a]] +=
              cp.weighted_values[q * n + a] * at_points[c][q];
      }
  }

  void
  SplitKernelFftOperator::apply_to_values(const Vector<double> &values,
                                          Vector<double> &settlement) const
  {
    settlement.reinit(values.size());
    near_field.vmult(settlement, values);
    apply_far_field(values, settlement);
  }

  void
  SplitKernelFftOperator::apply(const Vector<double> &q,
                                Vector<double>       &s) const
  {
    apply_in_pressure_basis(
      q, s, [this](const Vector<double> &values, Vector<double> &settlement) {
        apply_to_values(values, settlement);
      });
  }

  Vector<double>
  SplitKernelFftOperator::flexibility_diagonal() const
  {
    const unsigned int n = n_nodes();
    // The far field's A_jj from about 4 of the Gauss points of each cell
    // of node j (every copy), their weights rescaled to the cell's: the
    // springs need the local flexibility to a factor of a few
    // (contact/pressure_preconditioner.h), and all points would cost
    // (16 points)^2 kernel values per pair of cells.
    std::vector<std::vector<std::pair<unsigned int, unsigned int>>> cells_of(n);
    for (unsigned int c = 0; c < far_points.size(); ++c)
      for (unsigned int a = 0; a < far_points[c].nodes.size(); ++a)
        cells_of[far_points[c].nodes[a]].emplace_back(c, a);
    std::vector<std::array<double, 2>> signs = {{{1., 1.}}};
    signs.insert(signs.end(), reflections.begin(), reflections.end());
    const double   sigma = chosen.sigma;
    Vector<double> far_diagonal(n);
    const auto     every = [](const CellPoints &cp) {
      return std::max<std::size_t>(1, cp.points.size() / 4);
    };
    // sum over a cell's every step-th point of JxW psi_a, and the ratio
    // that rescales it to the whole cell's
    const auto scale = [&](const CellPoints &cp, const unsigned int a) {
      double all = 0, some = 0;
      for (unsigned int p = 0; p < cp.points.size(); ++p)
        all += cp.weighted_values[p * cp.nodes.size() + a];
      for (unsigned int p = 0; p < cp.points.size(); p += every(cp))
        some += cp.weighted_values[p * cp.nodes.size() + a];
      return some != 0. ? all / some : 0.;
    };
    for (unsigned int j = 0; j < n; ++j)
      {
        double sum = 0;
        for (const auto &[k, a] : cells_of[j])
          for (const auto &[l, b] : cells_of[j])
            for (const auto &sign : signs)
              {
                const CellPoints &ck = far_points[k], &cl = far_points[l];
                double            part = 0;
                for (unsigned int p = 0; p < ck.points.size(); p += every(ck))
                  for (unsigned int r = 0; r < cl.points.size(); r += every(cl))
                    {
                      const Point<2> y(sign[0] * cl.points[r][0],
                                       sign[1] * cl.points[r][1]);
                      part +=
                        ck.weighted_values[p * ck.nodes.size() + a] *
                        cl.weighted_values[r * cl.nodes.size() + b] *
                        far_kernel(alpha, sigma, ck.points[p].distance(y));
                    }
                sum += part * scale(ck, a) * scale(cl, b);
              }
        far_diagonal[j] = sum;
      }
    Vector<double> diagonal(n);
    if (!positive_basis)
      {
        for (unsigned int i = 0; i < n; ++i)
          diagonal[i] = near_field.diag_element(i) + far_diagonal[i];
        return diagonal;
      }
    // (T^T N T)_ii exactly, the far part without the cross terms.
    std::vector<std::vector<std::pair<unsigned int, double>>> columns(n);
    for (unsigned int j = 0; j < transform.m(); ++j)
      for (auto t = transform.begin(j); t != transform.end(j); ++t)
        columns[t->column()].emplace_back(j, t->value());
    for (unsigned int i = 0; i < n; ++i)
      {
        double sum = 0;
        for (const auto &[j, tj] : columns[i])
          {
            sum += tj * tj * far_diagonal[j];
            for (const auto &[k, tk] : columns[i])
              sum += tj * tk * near_field.el(j, k);
          }
        diagonal[i] = sum;
      }
    return diagonal;
  }

  std::unique_ptr<ApproximateInverse>
  SplitKernelFftOperator::make_approximate_inverse()
  {
    // The near field on the mass matrix's pattern plus the far field's
    // long waves as pi alpha sigma M (doc/formulation.md, "Split-kernel FFT
    // storage"); a larger shift where that is not positive definite.
    auto factor = std::make_shared<SparseCholesky>();
    std::vector<types::global_dof_index> rows(n_nodes());
    for (unsigned int i = 0; i < rows.size(); ++i)
      rows[i] = i;
    double shift = M_PI * alpha * chosen.sigma;
    for (unsigned int attempt = 0;; ++attempt)
      {
        SparseMatrix<double> local(mass_sparsity);
        for (unsigned int i = 0; i < local.m(); ++i)
          for (auto e = local.begin(i); e != local.end(i); ++e)
            e->value() =
              near_field.el(i, e->column()) + shift * mass.el(i, e->column());
        try
          {
            factor->factorize(local, rows);
            break;
          }
        catch (const ExcMessage &)
          {
            AssertThrow(attempt < 6,
                        ExcMessage("Foundation operator/Storage = fft: the "
                                   "near field is not positive definite."));
            shift *= 4;
          }
      }
    const bool basis = positive_basis;
    auto       solve = [this, factor, basis](Vector<double>       &q,
                                       const Vector<double> &s) {
      Vector<double> tested(s.size());
      if (basis)
        apply_inverse_transpose_transform(s, tested);
      else
        tested = s;
      std::vector<double> block(tested.begin(), tested.end());
      factor->solve(block, 1);
      Vector<double> values(block.begin(), block.end());
      q.reinit(s.size());
      if (basis)
        coefficients_from_values(values, q);
      else
        q = values;
    };
    return std::make_unique<NearFieldInverse>(solve,
                                              factor->memory_consumption());
  }

  std::string
  SplitKernelFftOperator::build_report() const
  {
    std::ostringstream text;
    text << std::setprecision(3) << "Foundation operator/Storage = fft: "
         << "kernel split at sigma = " << chosen.sigma << ", near field of "
         << chosen.near_pairs << " cell pairs within " << chosen.cutoff << " ("
         << chosen.near_entries << " entries), far field on "
         << chosen.quadrature_points << " Gauss points and a grid of "
         << chosen.grid_nodes << " nodes (spacing " << chosen.spacing
         << ", B-splines of order " << chosen.spline_order << ", FFT "
         << grid->fft_sizes()[0] << " x " << grid->fft_sizes()[1] << ")";
    return text.str();
  }

  std::size_t
  SplitKernelFftOperator::memory_consumption() const
  {
    std::size_t bytes = coupling_memory_consumption() +
                        near_field.memory_consumption() +
                        near_sparsity.memory_consumption() +
                        (grid ? grid->memory_consumption() : 0);
    for (const CellPoints &cp : far_points)
      bytes += cp.nodes.size() * sizeof(unsigned int) +
               cp.points.size() *
                 (sizeof(Point<2>) + sizeof(GridConvolution::Stencil)) +
               cp.weighted_values.size() * sizeof(double);
    return bytes;
  }
} // namespace PlateOnHalfspace
