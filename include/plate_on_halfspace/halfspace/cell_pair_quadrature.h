/**
 * Integrals of the Boussinesq kernel 1/|x - y| against pairs of shape
 * functions over pairs of plate cells: the building block of the Galerkin
 * half-space operator (doc/formulation.md, "Default variant").
 */
#ifndef plate_on_halfspace_halfspace_cell_pair_quadrature_h
#define plate_on_halfspace_halfspace_cell_pair_quadrature_h

#include <deal.II/base/quadrature_lib.h>

#include <deal.II/lac/full_matrix.h>

#include <plate_on_halfspace/plate/foundation_space.h>
#include <plate_on_halfspace/soil/soil_model.h>

#include <array>
#include <map>
#include <mutex>
#include <vector>

namespace PlateOnHalfspace
{
  /**
   * A cell against its own mirror image (a symmetric scene,
   * mirror_symmetry.h): @p block (i, k) couples node @p rows[i] with node
   * @p columns[k], the same nodes in another order. The integral is
   * symmetric in the two nodes, the quadrature only nearly: average each
   * entry with its transpose, so that A stays exactly symmetric
   * (CellPairSummation decides when, cell_pair_summation.h).
   */
  void
  symmetrise_self_image_block(const std::vector<unsigned int> &rows,
                              const std::vector<unsigned int> &columns,
                              FullMatrix<double>              &block);

  /**
   * For every cell of a list of FoundationSpace cells (a space's cells,
   * and for a symmetric scene their mirror images): its foundation nodes and
   * the node shape functions psi_a = sum_i T_ai phi_i (the Q2 functions phi
   * after the serendipity and hanging-node constraints), tabulated on Gauss
   * rules of several orders. integrate_inverse_distance() picks the rule from
   * the pair's separation:
   *  - coincident and touching cells (sharing a vertex or part of an edge):
   *    outer Gauss rule of the singular order on K; for each outer point x
   *    the inner integral over L uses QSplit(QDuffy) split at x's reference
   *    point in L (clamped onto L when x lies outside), whose Duffy collapse
   *    cancels the 1/r singularity on any straight-sided quadrilateral.
   *    These are integrated in the Q2 basis once per configuration up to
   *    translation and scale (configuration()), so a mesh of congruent
   *    cells integrates a handful of them;
   *  - separated pairs: tensor Gauss rules of 2 to 6 points per direction,
   *    the fewest that SurfaceKernel::separated_points() allows at the
   *    pair's separation in cell diameters. Where a cell's edge exceeds
   *    1.5 times the gap between the two (graded or elongated
   *    neighbours), each cell is cut into pieces graded towards the other
   *    and each pair of pieces takes the rule of its own separation
   *    (integrate_composite()). The rules
   *    scale with the cells, so a pair's relative error does not grow with
   *    refinement (doc/formulation.md, "Cell-pair quadrature").
   */
  class CellPairIntegrator
  {
  public:
    /**
     * Prepares the cells marked in @p prepared, all of them where it is
     * empty: their nodes and their shape functions' expansions (a cell's
     * Gauss tables are made when a pair first needs them). Only prepared
     * cells may be passed to the other functions (singular_pair() takes
     * any). A caller that meets few of the cells saves the rest: the
     * split kernel's near field meets only the mirror images next to the
     * mirror planes.
     */
    CellPairIntegrator(const std::vector<FoundationSpace::Cell> &cells,
                       const unsigned int                        singular_order,
                       const std::vector<bool>                  &prepared = {});

    /** Foundation nodes of cell @p c (the rows of its node shape functions). */
    const std::vector<unsigned int> &
    nodes(const unsigned int c) const
    {
      Assert(!cell_data[c].nodes.empty(),
             ExcMessage("CellPairIntegrator: cell not prepared"));
      return cell_data[c].nodes;
    }

    /**
     * Whether integrate_inverse_distance() treats cells @p k and @p l as a
     * singular pair (the same cell, or touching): the expensive pairs,
     * which a caller may want to integrate once and keep.
     */
    bool
    singular_pair(const unsigned int k, const unsigned int l) const
    {
      // Cells whose centres lie further apart than their diameters added
      // cannot touch: most pairs are decided without the vertex tests.
      return k == l || (cell_data[k].centre.distance(cell_data[l].centre) <=
                          cell_data[k].diameter + cell_data[l].diameter &&
                        touching(k, l));
    }

    /**
     * Integrate the singular pairs (k, l) of @p pairs into the cache of
     * configurations, in parallel, each new configuration from its first
     * pair in the list (so the result does not depend on the threads).
     * Callers that integrate pairs concurrently call this first. Shows its
     * progress (ProgressReport, "Singular cell pairs"). With a smooth
     * @p remainder (a layered soil's), its blocks of those pairs too
     * (smooth_q2_block()).
     */
    void
    integrate_singular_pairs(
      const std::vector<std::pair<unsigned int, unsigned int>> &pairs,
      const SmoothRadialFunction *remainder = nullptr) const;

    /**
     * block(a,b) = ∫_{cell k} ∫_{cell l} psi_a(x) psi_b(y) / |x - y| dy dx,
     * a over the nodes of k, b over those of l.
     */
    void
    integrate_inverse_distance(const unsigned int  k,
                               const unsigned int  l,
                               FullMatrix<double> &block) const;

    /**
     * The same, but only the entries (a, b) with @p rows[a] and
     * @p columns[b] are wanted (the others are left zero or hold the
     * integral): a hierarchical matrix's compression asks for single rows
     * and columns, and a separated pair then costs little more than its
     * kernel evaluations. Empty masks mean all.
     */
    void
    integrate_inverse_distance(const unsigned int       k,
                               const unsigned int       l,
                               FullMatrix<double>      &block,
                               const std::vector<bool> &rows,
                               const std::vector<bool> &columns) const;

    /**
     * block(a,b) = ∫_{cell k} ∫_{cell l} psi_a(x) psi_b(y) K(|x - y|) dy dx
     * for the kernel K(r) = alpha / r + R(r) of a soil (SurfaceKernel),
     * only the entries of @p rows and @p columns (empty: all). Singular
     * pairs take alpha times their 1/r rules and R by integrate_smooth();
     * separated pairs integrate the whole kernel on Gauss rules of
     * SurfaceKernel::separated_points() at @p accuracy relative to the
     * entry, composite where a cell is wider than the gap between the two
     * (integrate_composite()) (at least 3 points per direction with a
     * remainder, which varies over the top layer's thickness at any distance;
     * doc/soil-models.md, "How the storages use it"). A kernel much
     * smaller than alpha / r at the pair's distance may ask less.
     */
    void
    integrate_kernel(
      const unsigned int       k,
      const unsigned int       l,
      const SurfaceKernel     &kernel,
      FullMatrix<double>      &block,
      const std::vector<bool> &rows,
      const std::vector<bool> &columns,
      const double accuracy = SurfaceKernel::separated_accuracy) const;

    /**
     * The node shape functions of cell @p c on @p rule (reference points):
     * the physical points, and JxW times psi_a at point q in
     * @p weighted_values[q * nodes(c).size() + a].
     */
    void
    tabulate(const unsigned int     c,
             const Quadrature<2>   &rule,
             std::vector<Point<2>> &points,
             std::vector<double>   &weighted_values) const;

  private:
    /**
     * Node shape functions of one cell on one Gauss rule, stored flat so
     * that the kernel loops vectorise.
     */
    struct Table
    {
      std::vector<double> x, y;    ///< physical points
      std::vector<double> weights; ///< JxW
      /** JxW_q psi_a(x_q) at [q * n_functions + a]. */
      std::vector<double> weighted_values;
      unsigned int        n_functions = 0;
    };

    /**
     * The inner rule of a singular pair for one split point, with the Q2
     * shape values at its points and at the split point.
     */
    struct SingularRule
    {
      SingularRule(const Point<2> &split, const QDuffy &duffy);
      std::vector<Point<2>>              points;
      std::vector<double>                weights;
      std::vector<std::array<double, 9>> phi;
      std::array<double, 9>              at_split;
    };

    struct CellData
    {
      std::vector<unsigned int> nodes;
      FullMatrix<double>        node_from_q2; ///< T, n_nodes x 9
      Point<2>                  centre;
      double                    diameter;
      /** The first n_stored_rules rules' tables, made at their first use
       *  (stored_tables()). */
      mutable std::vector<Table> tables;
      mutable std::once_flag     tables_made;
    };

    /** Cell @p c's tables on the first n_stored_rules rules; made by the
     *  first caller, whichever thread it runs on. */
    const std::vector<Table> &
    stored_tables(const unsigned int c) const;

    /** The node shape functions of cell @p c on @p rule. */
    Table
    make_table(const unsigned int c, const Quadrature<2> &rule) const;

    /** psi(p) of cell @p c at the reference point @p p. */
    void
    node_shape_values(const unsigned int   c,
                      const Point<2>      &p,
                      std::vector<double> &values) const;

    bool
    touching(const unsigned int k, const unsigned int l) const;

    /**
     * The separated pair (k, l) where a cell's edge exceeds 1.5 times the
     * gap between the two: each cell cut into pieces (sub-rectangles of its
     * reference square) graded towards the other cell, until no piece's
     * edge exceeds 1.5 times its own gap to it or the cell has max_pieces
     * pieces, and every pair of pieces on the Gauss rule of its own
     * separation, added to @p block. Returns false, @p block untouched,
     * where no edge exceeds 1.5 times the gap: there the pair's own rule
     * holds (doc/formulation.md, "Graded and elongated pairs").
     */
    bool
    integrate_composite(const unsigned int       k,
                        const unsigned int       l,
                        const SurfaceKernel     &kernel,
                        FullMatrix<double>      &block,
                        const std::vector<bool> &rows,
                        const std::vector<bool> &columns,
                        const double             accuracy) const;

    /** The most pieces integrate_composite() cuts one cell into. */
    static constexpr unsigned int max_pieces = 64;

    /** The separated pair's block of @p kernel on the tables' rule. */
    void
    integrate_regular(const Table             &outer,
                      const Table             &inner,
                      FullMatrix<double>      &block,
                      const std::vector<bool> &rows,
                      const std::vector<bool> &columns,
                      const SurfaceKernel     &kernel) const;

    /**
     * The singular pair (k, l) in the Q2 basis of the two cells (9 x 9,
     * symmetrised over the order of the cells), from the cache of
     * congruent configurations or integrated and cached.
     */
    const FullMatrix<double> &
    singular_q2_block(const unsigned int k, const unsigned int l) const;

    /** The symmetrised Q2 block of (k, l) over k's diameter cubed. */
    FullMatrix<double>
    normalised_singular_q2_block(const unsigned int k,
                                 const unsigned int l) const;

    /** One order of the singular rule: outer Gauss on k, inner Duffy on l
     *  (9 x 9, Q2 basis). */
    void
    integrate_singular(const unsigned int  k,
                       const unsigned int  l,
                       FullMatrix<double> &q2_block) const;

    /**
     * The configuration of the pair (k, l) up to translation and scale:
     * the vertices of both cells relative to k's first vertex over k's
     * diameter, rounded to 1e-9. Congruent pairs (a uniform mesh's
     * neighbours, an adaptive mesh's scaled copies, mirror images) share
     * one key and one integral, which scales with the diameter cubed.
     */
    std::array<long long, 16>
    configuration(const unsigned int k, const unsigned int l) const;

    /** configuration() and k's diameter over @p R's length scale, rounded
     *  to 1e-9: R is invariant under translation only. */
    std::array<long long, 17>
    smooth_configuration(const unsigned int          k,
                         const unsigned int          l,
                         const SmoothRadialFunction &R) const;

    /**
     * ∫_{cell k} ∫_{cell l} phi_i(x) phi_j(y) R(|x - y|) dy dx in the Q2
     * basis (9 x 9) for a smooth @p R (a layered soil's remainder, soil/
     * layered_soil.h; the split-kernel storage's far field): tensor Gauss
     * rules of 3 + 3 H / (l + d) points per direction, H the larger
     * diameter, d the cells' separation and l R's length scale. A rule of
     * that order resolves a function analytic in a strip of half-width l
     * to about 1e-9 over a cell. Above 12 points the rule is composite:
     * the cell cut into c x c copies of a rule of 3 + 3 H / (c (l + d))
     * points, at most 12, so the cost grows like (H / l)^4; at most 8
     * copies (96 points per direction, cells up to about 30 l wide).
     */
    FullMatrix<double>
    integrate_smooth(const unsigned int          k,
                     const unsigned int          l,
                     const SmoothRadialFunction &R) const;

    /** integrate_smooth() by smooth_configuration(), cached. */
    const FullMatrix<double> &
    smooth_q2_block(const unsigned int          k,
                    const unsigned int          l,
                    const SmoothRadialFunction &R) const;

    const std::vector<FoundationSpace::Cell> &cells;
    const unsigned int                        singular_order;
    /** Gauss rules of 2 ... 6 points per direction, then the graded
     *  outer rule of the singular pairs. */
    const std::array<Quadrature<2>, 6> rules;
    /** How many of the rules each cell keeps tabulated (2 ... 4 points). */
    static constexpr unsigned int n_stored_rules = 3;
    std::vector<CellData>         cell_data;
    /** The Duffy rule on the reference triangle, singular at vertex 0. */
    const QDuffy duffy;
    /** Inner rules of coincident pairs, one per outer point. */
    std::vector<SingularRule> coincident_rules;
    /** The Q2 shape values at the points of the graded outer rule. */
    std::vector<std::array<double, 9>> graded_phi;
    /**
     * Singular Q2 blocks by configuration() over the diameter cubed. A
     * cache of what is integrated, filled from concurrent callers.
     */
    mutable std::map<std::array<long long, 16>, FullMatrix<double>>
      singular_cache;
    /** The R blocks of singular pairs by smooth_configuration(), for the
     *  one R this integrator is used with; under the same mutex. */
    mutable std::map<std::array<long long, 17>, FullMatrix<double>>
                                        smooth_cache;
    mutable const SmoothRadialFunction *smooth_cache_function = nullptr;
    mutable std::mutex                  singular_cache_mutex;
  };
} // namespace PlateOnHalfspace

#endif
