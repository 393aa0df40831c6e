#include <deal.II/base/exceptions.h>

#include <deal.II/fe/fe.h>

#include <plate_on_halfspace/base/result_record.h>
#include <plate_on_halfspace/plate/field_extrema.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <vector>

namespace PlateOnHalfspace
{
  namespace
  {
    using CellIterator = typename DoFHandler<2>::active_cell_iterator;

    /** Lattice of reference points sampled in every cell: 0, 1/4, ..., 1
     *  per direction (vertices, edge midpoints and centre included, i.e. the
     *  nodes of the Q2 element). */
    constexpr unsigned int lattice_points_1d = 5;
    constexpr unsigned int n_lattice_points =
      lattice_points_1d * lattice_points_1d;
    /** Cells refined by the local search: at least the best few by lattice
     *  value, at most this many in all. */
    constexpr unsigned int n_best_cells       = 8;
    constexpr unsigned int max_searched_cells = 64;
    /** The local search stops when its step is below this (reference
     *  coordinates, i.e. relative to the cell size). */
    constexpr double smallest_step = 1e-7;
    /** A step must gain this much (relative to the field's magnitude):
     *  differences below it are rounding. */
    constexpr double relative_gain = 1e-14;
    /** Peaks within this (relative to the field's magnitude) are ties. */
    constexpr double relative_tie = 1e-9;
    /** Evaluations of one local search at most. */
    constexpr unsigned int max_evaluations = 2000;

    /** Shape values and reference gradients of the scalar base element
     *  (FE_Q) at one reference point. */
    struct ShapeData
    {
      std::vector<double>       values;
      std::vector<Tensor<1, 2>> gradients;
    };

    /**
     * One quantity of a solution on one cell at any reference point: the
     * cell's coefficients per component and its vertices (MappingQ1, the
     * bilinear map, as MindlinPlate's FEValues), the base element's shape
     * functions evaluated at the point or taken from precomputed ShapeData.
     */
    class CellField
    {
    public:
      CellField(const MindlinPlate   &plate,
                const Vector<double> &solution,
                const PlateQuantity   quantity)
        : base(plate.get_fe().base_element(0))
        , solution(solution)
        , quantity(quantity)
        , plate(plate)
        , local_values(plate.get_fe().n_dofs_per_cell())
      {
        const FiniteElement<2> &fe = plate.get_fe();
        AssertThrow(fe.n_base_elements() == 1 && fe.n_components() == 3,
                    ExcMessage("field extrema: the plate element must be "
                               "three copies of one scalar element"));
        AssertThrow(solution.size() == plate.get_dof_handler().n_dofs(),
                    ExcDimensionMismatch(solution.size(),
                                         plate.get_dof_handler().n_dofs()));
        for (unsigned int i = 0; i < fe.n_dofs_per_cell(); ++i)
          {
            component.push_back(fe.system_to_component_index(i).first);
            base_index.push_back(fe.system_to_component_index(i).second);
          }
        for (auto &c : coefficients)
          c.resize(base.n_dofs_per_cell());
      }

      /** Whether the quantity needs gradients (moments) or values (w). */
      bool
      needs_gradients() const
      {
        return quantity != PlateQuantity::w;
      }

      void
      reinit(const CellIterator &cell)
      {
        cell->get_dof_values(solution, local_values);
        for (unsigned int i = 0; i < local_values.size(); ++i)
          coefficients[component[i]][base_index[i]] = local_values[i];
        for (unsigned int v = 0; v < 4; ++v)
          vertices[v] = cell->vertex(v);
      }

      void
      shape_data(const Point<2> &p, ShapeData &data) const
      {
        const unsigned int n = base.n_dofs_per_cell();
        data.values.resize(needs_gradients() ? 0 : n);
        data.gradients.resize(needs_gradients() ? n : 0);
        for (unsigned int k = 0; k < n; ++k)
          if (needs_gradients())
            data.gradients[k] = base.shape_grad(k, p);
          else
            data.values[k] = base.shape_value(k, p);
      }

      /** The quantity at @p p, whose shape data is @p shapes. NaN if the
       *  cell is degenerate there. */
      double
      value(const Point<2> &p, const ShapeData &shapes) const
      {
        const unsigned int n = base.n_dofs_per_cell();
        if (!needs_gradients())
          {
            double w = 0;
            for (unsigned int k = 0; k < n; ++k)
              w += coefficients[0][k] * shapes.values[k];
            return w;
          }
        // reference gradients of beta_x and beta_y
        Tensor<1, 2> gx, gy;
        for (unsigned int k = 0; k < n; ++k)
          {
            gx += coefficients[1][k] * shapes.gradients[k];
            gy += coefficients[2][k] * shapes.gradients[k];
          }
        // J = dx/dp of the bilinear map: columns dx/ds, dx/dt
        const Tensor<1, 2> xs = (vertices[1] - vertices[0]) * (1. - p[1]) +
                                (vertices[3] - vertices[2]) * p[1];
        const Tensor<1, 2> xt = (vertices[2] - vertices[0]) * (1. - p[0]) +
                                (vertices[3] - vertices[1]) * p[0];
        const double det = xs[0] * xt[1] - xt[0] * xs[1];
        if (!(det > 0))
          return std::numeric_limits<double>::quiet_NaN();
        // physical gradient = J^{-T} reference gradient:
        // d/dx = ( xt[1] d/ds - xs[1] d/dt) / det,
        // d/dy = (-xt[0] d/ds + xs[0] d/dt) / det
        Tensor<2, 2> grad_beta;
        grad_beta[0][0] = (xt[1] * gx[0] - xs[1] * gx[1]) / det;
        grad_beta[0][1] = (-xt[0] * gx[0] + xs[0] * gx[1]) / det;
        grad_beta[1][0] = (xt[1] * gy[0] - xs[1] * gy[1]) / det;
        grad_beta[1][1] = (-xt[0] * gy[0] + xs[0] * gy[1]) / det;
        return moment_quantity(plate,
                               plate.moments_of_rotation_gradient(grad_beta),
                               quantity);
      }

      /** The quantity at any reference point @p p. */
      double
      value(const Point<2> &p) const
      {
        shape_data(p, scratch);
        return value(p, scratch);
      }

      /** The physical point of the reference point @p p. */
      Point<2>
      map(const Point<2> &p) const
      {
        return Point<2>(vertices[0] * ((1. - p[0]) * (1. - p[1])) +
                        vertices[1] * (p[0] * (1. - p[1])) +
                        vertices[2] * ((1. - p[0]) * p[1]) +
                        vertices[3] * (p[0] * p[1]));
      }

    private:
      const FiniteElement<2>            &base;
      const Vector<double>              &solution;
      const PlateQuantity                quantity;
      const MindlinPlate                &plate;
      std::vector<unsigned int>          component, base_index;
      Vector<double>                     local_values;
      std::array<std::vector<double>, 3> coefficients;
      std::array<Point<2>, 4>            vertices;
      mutable ShapeData                  scratch;
    };

    Point<2>
    lattice_point(const unsigned int q)
    {
      const double h = 1. / (lattice_points_1d - 1);
      return Point<2>(h * (q % lattice_points_1d), h * (q / lattice_points_1d));
    }

    /** What the lattice sweep keeps of a cell. */
    struct CellSamples
    {
      CellIterator cell;
      /** Largest and smallest finite lattice value (NaN if none). */
      double       high       = std::numeric_limits<double>::quiet_NaN();
      double       low        = std::numeric_limits<double>::quiet_NaN();
      unsigned int high_point = 0, low_point = 0;
      /** How far the field may rise above (fall below) its lattice values
       *  between lattice points: a quadratic with second difference d over
       *  a lattice step rises by at most d/8 between two points; twice that
       *  per direction, and the mixed difference, for safety. */
      double rise = 0;
    };

    CellSamples
    sample(const CellField              &field,
           const CellIterator           &cell,
           const std::vector<ShapeData> &lattice_shapes)
    {
      CellSamples                          samples;
      std::array<double, n_lattice_points> f;
      samples.cell = cell;
      for (unsigned int q = 0; q < n_lattice_points; ++q)
        {
          f[q] = field.value(lattice_point(q), lattice_shapes[q]);
          if (!std::isfinite(f[q]))
            continue;
          if (!(f[q] <= samples.high)) // also when high is NaN
            {
              samples.high       = f[q];
              samples.high_point = q;
            }
          if (!(f[q] >= samples.low))
            {
              samples.low       = f[q];
              samples.low_point = q;
            }
        }
      double     dss = 0, dtt = 0, dst = 0;
      const auto at = [&f](const unsigned int i, const unsigned int j) {
        return f[i + lattice_points_1d * j];
      };
      const auto largest = [](double &d, const double candidate) {
        if (std::isfinite(candidate))
          d = std::max(d, std::abs(candidate));
      };
      for (unsigned int j = 0; j < lattice_points_1d; ++j)
        for (unsigned int i = 0; i < lattice_points_1d; ++i)
          {
            if (i > 0 && i + 1 < lattice_points_1d)
              largest(dss, at(i - 1, j) - 2 * at(i, j) + at(i + 1, j));
            if (j > 0 && j + 1 < lattice_points_1d)
              largest(dtt, at(i, j - 1) - 2 * at(i, j) + at(i, j + 1));
            if (i + 1 < lattice_points_1d && j + 1 < lattice_points_1d)
              largest(dst,
                      at(i + 1, j + 1) - at(i + 1, j) - at(i, j + 1) +
                        at(i, j));
          }
      samples.rise = (dss + dtt + dst) / 4;
      return samples;
    }

    /**
     * Projected Newton steps for the largest value of sign * field from the
     * compass search's point @p p (value @p value): gradient and Hessian by
     * central differences in reference coordinates (the cell's polynomial
     * extends beyond the cell), the coordinates on a bound of [0,1]^2 with
     * the gradient pointing out held fixed. A step is taken only where the
     * Hessian of the free coordinates is negative definite, if it is short
     * (a few compass steps) and does not lose more than rounding (a
     * relative_gain of the field's @p magnitude); it locates
     * a peak to the accuracy of the gradient rather than of the value, i.e.
     * far below the compass search's step.
     */
    std::pair<double, Point<2>>
    polish(const CellField &field,
           const double     sign,
           Point<2>         p,
           double           value,
           const double     magnitude)
    {
      const double     gain  = relative_gain * magnitude;
      constexpr double delta = 1e-3;
      for (unsigned int step = 0; step < 4; ++step)
        {
          // values relative to the field's magnitude: no overflow in the
          // Hessian's determinant for any finite field
          const double scale = std::max(
            {std::abs(value), magnitude, std::numeric_limits<double>::min()});
          const auto f = [&](const double ds, const double dt) {
            return sign * field.value(p + Tensor<1, 2>({ds, dt})) / scale;
          };
          const double f_0  = value / scale;
          const double f_sp = f(delta, 0), f_sm = f(-delta, 0),
                       f_tp = f(0, delta), f_tm = f(0, -delta);
          const double f_pp = f(delta, delta), f_pm = f(delta, -delta),
                       f_mp = f(-delta, delta), f_mm = f(-delta, -delta);
          const Tensor<1, 2> g(
            {(f_sp - f_sm) / (2 * delta), (f_tp - f_tm) / (2 * delta)});
          const double h_ss = (f_sp - 2 * f_0 + f_sm) / (delta * delta),
                       h_tt = (f_tp - 2 * f_0 + f_tm) / (delta * delta),
                       h_st = (f_pp - f_pm - f_mp + f_mm) / (4 * delta * delta);
          if (!std::isfinite(g[0] + g[1] + h_ss + h_tt + h_st))
            break;
          // coordinates held on their bound
          std::array<bool, 2> free;
          for (unsigned int c = 0; c < 2; ++c)
            free[c] = !((p[c] <= 0. && g[c] < 0) || (p[c] >= 1. && g[c] > 0));
          Tensor<1, 2> d;
          if (free[0] && free[1])
            {
              const double det = h_ss * h_tt - h_st * h_st;
              if (!(h_ss < 0 && det > 0))
                break;
              d[0] = -(h_tt * g[0] - h_st * g[1]) / det;
              d[1] = -(-h_st * g[0] + h_ss * g[1]) / det;
            }
          else if (free[0] || free[1])
            {
              const unsigned int c   = free[0] ? 0 : 1;
              const double       hcc = (c == 0 ? h_ss : h_tt);
              if (!(hcc < 0))
                break;
              d[c] = -g[c] / hcc;
            }
          else
            break;
          if (!(d.norm() <= 1e-3))
            break;
          Point<2> candidate = p + d;
          for (unsigned int c = 0; c < 2; ++c)
            candidate[c] = std::min(1., std::max(0., candidate[c]));
          const double v = sign * field.value(candidate);
          if (!(v >= value - gain))
            break;
          const bool converged = candidate.distance(p) < 1e-12;
          p                    = candidate;
          value                = v;
          if (converged)
            break;
        }
      return {value, p};
    }

    /**
     * Compass search for the largest value of sign * field on the reference
     * square from @p start: try steps of length h along the axes and the
     * diagonals (projected onto [0,1]^2), move to the best that gains more
     * than rounding (relative_gain of the field's @p magnitude), halve h
     * when none does, stop when h < smallest_step; then polish().
     * Returns sign * field and the point.
     */
    std::pair<double, Point<2>>
    climb(const CellField &field,
          const double     sign,
          const Point<2>  &start,
          const double     magnitude)
    {
      const double                             gain = relative_gain * magnitude;
      static const std::array<Tensor<1, 2>, 8> directions = {
        {Tensor<1, 2>({1., 0.}),
         Tensor<1, 2>({-1., 0.}),
         Tensor<1, 2>({0., 1.}),
         Tensor<1, 2>({0., -1.}),
         Tensor<1, 2>({1., 1.}),
         Tensor<1, 2>({1., -1.}),
         Tensor<1, 2>({-1., 1.}),
         Tensor<1, 2>({-1., -1.})}};
      Point<2>     p           = start;
      double       value       = sign * field.value(p);
      double       h           = 1. / (lattice_points_1d - 1);
      unsigned int evaluations = 1;
      while (h >= smallest_step && evaluations < max_evaluations)
        {
          Point<2> best_point = p;
          double   best       = value;
          for (const Tensor<1, 2> &d : directions)
            {
              Point<2> candidate = p + h * d;
              for (unsigned int c = 0; c < 2; ++c)
                candidate[c] = std::min(1., std::max(0., candidate[c]));
              if (candidate == p)
                continue;
              const double v = sign * field.value(candidate);
              ++evaluations;
              if (std::isfinite(v) && v > value + gain && v > best)
                {
                  best       = v;
                  best_point = candidate;
                }
            }
          if (best_point == p)
            h /= 2;
          else
            {
              p     = best_point;
              value = best;
            }
        }
      return polish(field, sign, p, value, magnitude);
    }

    /** Whether @p a comes before @p b: smaller x, then smaller y, equal
     *  within @p tolerance. */
    bool
    comes_before(const Point<2> &a, const Point<2> &b, const double tolerance)
    {
      if (std::abs(a[0] - b[0]) > tolerance)
        return a[0] < b[0];
      return a[1] < b[1] - tolerance;
    }

    /**
     * The largest value of sign * field over the plate, from the lattice
     * samples of every cell: the local search in the cells that can hold
     * it, then the tie rule of field_maximum().
     */
    FieldExtremum
    search(const MindlinPlate             &plate,
           CellField                      &field,
           const std::vector<CellSamples> &samples,
           const double                    sign,
           const double                    magnitude)
    {
      // sign * (the lattice value of the right side)
      const auto key = [sign](const CellSamples &s) {
        return sign > 0 ? s.high : -s.low;
      };
      std::vector<unsigned int> finite;
      for (unsigned int c = 0; c < samples.size(); ++c)
        if (std::isfinite(key(samples[c])))
          finite.push_back(c);
      FieldExtremum result;
      if (finite.empty())
        {
          result.value           = std::numeric_limits<double>::quiet_NaN();
          result.cell            = plate.get_dof_handler().begin_active();
          result.reference_point = Point<2>();
          result.location        = result.cell->vertex(0);
          return result;
        }

      // the best cells by lattice value (ties: the earlier cell)
      const auto by_key = [&](const unsigned int a, const unsigned int b) {
        const double ka = key(samples[a]), kb = key(samples[b]);
        return ka > kb || (ka == kb && a < b);
      };
      const unsigned int n_best =
        std::min<unsigned int>(n_best_cells, finite.size());
      std::partial_sort(finite.begin(),
                        finite.begin() + n_best,
                        finite.end(),
                        by_key);
      const double              best_lattice_value = key(samples[finite[0]]);
      std::vector<unsigned int> searched(finite.begin(),
                                         finite.begin() + n_best);
      // and every other cell whose field may rise above the best lattice
      // value between its lattice points, the most promising first
      std::vector<unsigned int> promising;
      for (unsigned int i = n_best; i < finite.size(); ++i)
        {
          const CellSamples &s = samples[finite[i]];
          if (key(s) + s.rise > best_lattice_value)
            promising.push_back(finite[i]);
        }
      const auto by_bound = [&](const unsigned int a, const unsigned int b) {
        const double ka = key(samples[a]) + samples[a].rise,
                     kb = key(samples[b]) + samples[b].rise;
        return ka > kb || (ka == kb && a < b);
      };
      const unsigned int n_promising =
        std::min<unsigned int>(promising.size(),
                               max_searched_cells - searched.size());
      std::partial_sort(promising.begin(),
                        promising.begin() + n_promising,
                        promising.end(),
                        by_bound);
      searched.insert(searched.end(),
                      promising.begin(),
                      promising.begin() + n_promising);
      std::sort(searched.begin(), searched.end()); // cell order

      struct Found
      {
        double       value;
        Point<2>     reference_point, location;
        CellIterator cell;
        double       size;
      };
      std::vector<Found> found;
      double             best = -std::numeric_limits<double>::infinity();
      for (const unsigned int c : searched)
        {
          const CellSamples &s = samples[c];
          field.reinit(s.cell);
          const auto [value, p] =
            climb(field,
                  sign,
                  lattice_point(sign > 0 ? s.high_point : s.low_point),
                  magnitude);
          found.push_back({value, p, field.map(p), s.cell, s.cell->diameter()});
          best = std::max(best, value);
        }
      // ties: the smallest x, then y
      const Found *chosen = nullptr;
      for (const Found &f : found)
        if (f.value >= best - relative_tie * magnitude &&
            (chosen == nullptr ||
             comes_before(f.location,
                          chosen->location,
                          1e-6 * std::min(f.size, chosen->size))))
          chosen = &f;
      result.value           = sign * chosen->value;
      result.location        = chosen->location;
      result.cell            = chosen->cell;
      result.reference_point = chosen->reference_point;
      return result;
    }

    /** The lattice sweep over all cells, then the searches asked for. */
    FieldExtrema
    find_extrema(const MindlinPlate      &plate,
                 const Vector<double>    &solution,
                 const PlateQuantity      quantity,
                 const bool               minimum,
                 const bool               maximum,
                 const types::material_id slab = numbers::invalid_material_id)
    {
      CellField              field(plate, solution, quantity);
      std::vector<ShapeData> lattice_shapes(n_lattice_points);
      for (unsigned int q = 0; q < n_lattice_points; ++q)
        field.shape_data(lattice_point(q), lattice_shapes[q]);
      std::vector<CellSamples> samples;
      samples.reserve(
        plate.get_dof_handler().get_triangulation().n_active_cells());
      double magnitude = 0;
      for (const auto &cell : plate.get_dof_handler().active_cell_iterators())
        {
          if (slab != numbers::invalid_material_id &&
              cell->material_id() != slab)
            continue;
          field.reinit(cell);
          samples.push_back(sample(field, cell, lattice_shapes));
          for (const double v : {samples.back().high, samples.back().low})
            if (std::isfinite(v))
              magnitude = std::max(magnitude, std::abs(v));
        }
      FieldExtrema extrema;
      if (minimum)
        extrema.minimum = search(plate, field, samples, -1., magnitude);
      if (maximum)
        extrema.maximum = search(plate, field, samples, 1., magnitude);
      return extrema;
    }
  } // namespace

  double
  moment_quantity(const MindlinPlate &plate,
                  const Moments      &m,
                  const PlateQuantity quantity)
  {
    switch (quantity)
      {
        case PlateQuantity::mx:
          return m.mx;
        case PlateQuantity::my:
          return m.my;
        case PlateQuantity::mxy:
          return m.mxy;
        case PlateQuantity::principal_moment:
          // hypot: no overflow for any finite moments
          return 0.5 * (m.mx + m.my) + std::hypot(0.5 * (m.mx - m.my), m.mxy);
        case PlateQuantity::principal_stress_bottom:
          return plate.fibre_stresses(m).principal_bottom;
        case PlateQuantity::principal_stress_top:
          return plate.fibre_stresses(m).principal_top;
        default:
          return std::numeric_limits<double>::quiet_NaN();
      }
  }

  double
  plate_quantity(const MindlinPlate                                 &plate,
                 const Vector<double>                               &solution,
                 const PlateQuantity                                 quantity,
                 const typename DoFHandler<2>::active_cell_iterator &cell,
                 const Point<2> &reference_point)
  {
    CellField field(plate, solution, quantity);
    field.reinit(cell);
    return field.value(reference_point);
  }

  FieldExtremum
  field_maximum(const MindlinPlate      &plate,
                const Vector<double>    &solution,
                const PlateQuantity      quantity,
                const types::material_id slab)
  {
    return find_extrema(plate, solution, quantity, false, true, slab).maximum;
  }

  FieldExtremum
  field_minimum(const MindlinPlate   &plate,
                const Vector<double> &solution,
                const PlateQuantity   quantity)
  {
    return find_extrema(plate, solution, quantity, true, false).minimum;
  }

  FieldExtrema
  field_extrema(const MindlinPlate   &plate,
                const Vector<double> &solution,
                const PlateQuantity   quantity)
  {
    return find_extrema(plate, solution, quantity, true, true);
  }

  namespace
  {
    /** A convergence.txt column of a peak, with its change. */
    ConvergenceColumn
    peak_column(const std::string &name, const std::string &key)
    {
      return {name,
              "`" + key + "`",
              [key](const ResultRecord &r, double &v) {
                v = r.number(key);
                return true;
              },
              6,
              true,
              true};
    }

    const bool declared = declare_results(
      "cycles",
      25,
      {{{"max_w", "min_w"},
        "length",
        "peaks of the deflection field w over the plate ([Peaks](#peaks); "
        "downward positive; `min_w` < 0 means a part lifts upward)"},
       {{"max_q", "min_q"},
        "force/length²",
        "peaks of the pressure field q, the nodal pressures interpolated "
        "with the w shape functions (compression positive; `min_q` < 0 is "
        "tension, possible when bonded or with element exclusion; with "
        "exact tensionless contact it can dip slightly below 0 between a "
        "lifted and a loaded node although every nodal value is ≥ 0)"},
       {{"max_Mx", "min_Mx", "max_My", "min_My"},
        "force·length/length",
        "peaks of the moment fields M_x, M_y over the plate, each cell's own "
        "polynomial up to its edges (the moments jump between cells)"},
       {{"max_principal_moment"},
        "force·length/length",
        "peak of the larger principal moment M₁ = (M_x + M_y)/2 + "
        "√(((M_x − M_y)/2)² + M_xy²)"},
       {{"max_principal_stress_bottom", "max_principal_stress_top"},
        "force/length²",
        "peaks of the largest principal stress of the bottom and of the top "
        "fibre, tension positive "
        "([formulation.md](formulation.md#stresses))"},
       {{"max_w_at",
         "min_w_at",
         "max_q_at",
         "min_q_at",
         "max_Mx_at",
         "min_Mx_at",
         "max_My_at",
         "min_My_at",
         "max_principal_moment_at",
         "max_principal_stress_bottom_at",
         "max_principal_stress_top_at"},
        "length",
        "`[x, y]`: where each peak above is (on the computed part of a "
        "symmetric scene)",
        ResultKind::location}},
      {peak_column("max w", "max_w"),
       peak_column("max Mx", "max_Mx"),
       peak_column("max q", "max_q")});
  } // namespace

  void
  add_peak_results(const MindlinPlate   &plate,
                   const Vector<double> &solution,
                   const Vector<double> &pressure_field,
                   ResultRecord         &record)
  {
    (void)declared;
    // The extremes of the fields, not of samples, so a probe's value does
    // not lie beyond them; q is the nodal pressure field in the w-space,
    // so its peaks bound the nodal values.
    const auto set = [&record](const std::string   &key,
                               const FieldExtremum &peak) {
      record.set(key, peak.value);
      record.set(key + "_at", peak.location);
    };
    for (const auto &[name, field, quantity] :
         {std::make_tuple("w", &solution, PlateQuantity::w),
          std::make_tuple("q", &pressure_field, PlateQuantity::w),
          std::make_tuple("Mx", &solution, PlateQuantity::mx),
          std::make_tuple("My", &solution, PlateQuantity::my)})
      {
        const FieldExtrema peaks = field_extrema(plate, *field, quantity);
        set(std::string("max_") + name, peaks.maximum);
        set(std::string("min_") + name, peaks.minimum);
      }
    for (const auto &[key, quantity] :
         {std::make_pair("max_principal_moment",
                         PlateQuantity::principal_moment),
          std::make_pair("max_principal_stress_bottom",
                         PlateQuantity::principal_stress_bottom),
          std::make_pair("max_principal_stress_top",
                         PlateQuantity::principal_stress_top)})
      set(key, field_maximum(plate, solution, quantity));
  }
} // namespace PlateOnHalfspace
