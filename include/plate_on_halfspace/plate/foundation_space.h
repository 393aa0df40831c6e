/**
 * The discrete contact surface shared by the plate and the half-space: the
 * foundation nodes (the unconstrained w-DOFs of the plate, doc/formulation.md
 * "Adaptive refinement") and, for every plate cell, how its nine Q2 w-shape
 * functions expand into foundation nodes once the serendipity and
 * hanging-node constraints are applied.
 *
 * This is the only thing the half-space operators know about the plate, so a
 * different operator (compressed, distributed) needs nothing else.
 */
#ifndef plate_on_halfspace_plate_foundation_space_h
#define plate_on_halfspace_plate_foundation_space_h

#include <deal.II/base/index_set.h>
#include <deal.II/base/mpi.h>
#include <deal.II/base/point.h>

#include <deal.II/lac/sparse_matrix.h>
#include <deal.II/lac/sparsity_pattern.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/base/quadrilateral_geometry.h>
#include <plate_on_halfspace/scene/mirror_symmetry.h>

#include <array>
#include <utility>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * Values of the nine biquadratic Lagrange shape functions of deal.II's
   * FE_Q<2>(2) at a reference point, in FE_Q's local numbering (vertices
   * 0-3, edge midpoints 4-7 on the faces x=0, x=1, y=0, y=1, centre 8).
   */
  std::array<double, 9>
  q2_shape_values(const Point<2> &p);

  /** Their gradients on the reference square, in the same numbering. */
  std::array<Tensor<1, 2>, 9>
  q2_shape_gradients(const Point<2> &p);

  /** The foundation nodes and the cell-to-node expansion (see file doc). */
  struct FoundationSpace
  {
    /** One term node * weight of the expansion of a cell shape function. */
    using Term = std::pair<unsigned int, double>;

    /** One plate cell seen from the foundation. */
    struct Cell
    {
      BilinearQuadrilateral geometry;
      /** Expansion of the 9 local w-shape functions into foundation nodes. */
      std::array<std::vector<Term>, 9> expansion;

      /** The foundation nodes of the cell, each once, in order of first
       *  appearance in the expansion. */
      std::vector<unsigned int>
      nodes() const;

      /** The values at the cell's nine Q2 nodes (FE_Q<2>(2) numbering) of
       *  the field with the nodal values @p nodal_values. */
      std::array<double, 9>
      local_values(const Vector<double> &nodal_values) const;
    };

    /** Location of each foundation node (x, y). */
    std::vector<Point<2>> node_locations;
    /** All active plate cells, in the DoFHandler's active cell order. */
    std::vector<Cell> cells;
    /**
     * The mirror planes of the scene: the cells are the computed part of
     * the plate, and the half-space also carries the mirror images of its
     * pressure (mirror_symmetry.h).
     */
    MirrorSymmetry symmetry;

    /**
     * The ranks the plate's mesh is shared by (MPI_COMM_SELF for one
     * process), and the nodes this rank owns: those whose w-DoF it owns
     * (doc/parallel.md). A foundation operator that splits its rows
     * computes these; every other vector stays whole on every rank.
     */
    MPI_Comm communicator = MPI_COMM_SELF;
    IndexSet owned_nodes;

    /**
     * The plate's rigid-body motions (generalized_inverse.h) at the
     * foundation nodes, orthonormal: a contact set must hold each of them
     * (contact_set_supports_plate()). A grid of slabs has more than three
     * when its joints let slabs move on their own.
     */
    std::vector<Vector<double>> rigid_motions;

    /**
     * The mirror images of the cells, for each reflection of
     * symmetry.reflections() in turn (cells.size() each), with the same
     * foundation nodes: the image of cell c under reflection r is element
     * r * cells.size() + c. The vertices and local shape functions are
     * renumbered so that the image is again counterclockwise and its node
     * shape functions are those of c at the mirrored point.
     */
    std::vector<Cell>
    mirror_image_cells() const;

    /**
     * For each node (or empty: none), the mirror planes it lies on along a
     * joint that is not tied (bit 0: x = 0, bit 1: y = 0). The joint's
     * other slab is the image, whose node at the same place is another
     * node of the whole plate (SlabGrid::mark_joint_faces()).
     */
    std::vector<unsigned char> joint_planes;

    /** The points of the whole plate that node @p i stands for: its
     *  location and its distinct mirror images (MirrorSymmetry::images(),
     *  with a node on a joint in a mirror plane imaged across it). */
    std::vector<Point<2>>
    node_images(const unsigned int i) const
    {
      return symmetry.images(node_locations[i],
                             joint_planes.empty() ? 0 : joint_planes[i]);
    }

    unsigned int
    n_nodes() const
    {
      return node_locations.size();
    }

    /** The area of the cells (the computed part). */
    double
    area() const;

    /**
     * Assemble the consistent mass matrix M_ij = ∫ φ_i φ_j (the paper's E,
     * (P11)-(P15)) over the cells with @p cell_in_foundation set (all if
     * empty), into @p sparsity and @p matrix (3x3 Gauss, exact for
     * parallelogram cells and for bilinear ones).
     */
    void
    assemble_mass_matrix(const std::vector<bool> &cell_in_foundation,
                         SparsityPattern         &sparsity,
                         SparseMatrix<double>    &matrix) const;

    /**
     * Assemble L_ij = ∫ ∇φ_i · ∇φ_j over all cells (natural boundary
     * conditions) into @p matrix on @p sparsity, the pattern of
     * assemble_mass_matrix() with every cell: the fractional preconditioner
     * of halfspace/fractional_laplace_inverse.h.
     */
    void
    assemble_laplace_matrix(const SparsityPattern &sparsity,
                            SparseMatrix<double>  &matrix) const;

    /**
     * The pressure basis of the contact conditions (doc/formulation.md,
     * "Tensionless contact"): q_h = sum_i qt_i psit_i with nodal values
     * q = T qt. A serendipity corner function has a negative integral
     * (-1/12 of a square cell), so nodal conditions q_i >= 0 let a
     * non-negative set of nodal pressures carry a net tension, and a
     * tensionless plate then stays in contact where it should lift off.
     * The basis psit_c = psi_c + alpha (psi_m1 + psi_m2 + ...) for a vertex
     * node c (the mid-side nodes m of the edges that end at c) and
     * psit_m = (1 - 2 alpha) psi_m for a mid-side node (Popp, Gee, Wall &
     * Wohlmuth's transformation of quadratic serendipity multipliers,
     * alpha = 1/5) spans the same space and has positive integrals:
     * -1/3 + 8 alpha/3 of a cell's area at an interior vertex of a uniform
     * mesh, -1/12 + 2 alpha/3 at a plate corner. T maps qt >= 0 to q >= 0.
     * Returns false (and leaves @p transform empty) when the space has no
     * serendipity cells (the 9-node Lagrange functions have positive
     * integrals already); otherwise fills @p transform (n x n) with T.
     */
    bool
    positive_pressure_transform(SparsityPattern      &sparsity,
                                SparseMatrix<double> &transform) const;
  };
} // namespace PlateOnHalfspace

#endif
