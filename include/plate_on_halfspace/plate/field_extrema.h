/**
 * Peaks of the plate's finite element fields: the largest and the smallest
 * value of w, of a pressure field in the w-space, of the moments and of the
 * larger principal moment over the plate, each with where it is
 * (doc/outputs.md, "Peaks").
 *
 * Each field is a polynomial on every cell (the moments are discontinuous
 * between cells), so a peak is searched cell by cell up to the cell's
 * boundary: every cell is sampled on a 5 x 5 lattice of reference points
 * (its vertices, edge points, the nodes of the Q2 element and interior
 * points). In the cells that can hold the peak (the 8 best and every cell
 * whose lattice value plus an estimate of how far the field can rise
 * between lattice points reaches the best, 64 cells at most) a compass
 * search in reference coordinates, kept in [0,1]^2, climbs from the best
 * lattice point until its step is below 1e-7 of the cell size, and a few
 * projected Newton steps (derivatives by differences) then locate a smooth
 * peak, inside the cell or on an edge, to the accuracy of the gradient. The
 * lattice uses shape values computed once, so a sweep costs a few
 * multiply-adds per lattice point (benchmarks/field_extrema.cc).
 */
#ifndef plate_on_halfspace_plate_field_extrema_h
#define plate_on_halfspace_plate_field_extrema_h

#include <deal.II/base/point.h>

#include <deal.II/dofs/dof_handler.h>

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/plate/mindlin_plate.h>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * A quantity of the plate's solution at a point (doc/formulation.md sign
   * conventions): the deflection w (downward positive), the moments per
   * unit width Mx, My, Mxy (Mx > 0 sagging, as MindlinPlate::moments()),
   * the larger principal moment
   * M1 = (Mx + My)/2 + sqrt(((Mx - My)/2)^2 + Mxy^2), and the largest
   * principal stress of the bottom and of the top fibre
   * (MindlinPlate::fibre_stresses(), tension positive).
   */
  enum class PlateQuantity
  {
    w,
    mx,
    my,
    mxy,
    principal_moment,
    principal_stress_bottom,
    principal_stress_top
  };

  /**
   * The value of @p quantity of @p solution (a full DoF vector of
   * plate.get_dof_handler(), constraints distributed) at the reference point
   * @p reference_point of @p cell. For PlateQuantity::w it is component 0,
   * so a pressure field stored in the w-space (as the driver's
   * pressure_field) gives q. The moments are those of MindlinPlate::moments()
   * (rotation gradients through the cell's bilinear map, with the thermal
   * moment), the stresses those of MindlinPlate::fibre_stresses().
   */
  double
  plate_quantity(const MindlinPlate                                 &plate,
                 const Vector<double>                               &solution,
                 const PlateQuantity                                 quantity,
                 const typename DoFHandler<2>::active_cell_iterator &cell,
                 const Point<2> &reference_point);

  /**
   * The value of @p quantity, one of the moments or stresses, for the
   * bending moments @p m (MindlinPlate::moments(), thermal moment
   * included): what plate_quantity() gives from the moments at its point.
   */
  double
  moment_quantity(const MindlinPlate &plate,
                  const Moments      &m,
                  const PlateQuantity quantity);

  /** A peak of a field and where it is. */
  struct FieldExtremum
  {
    /** The value, plate_quantity() at (cell, reference_point). */
    double value = 0;
    /** The physical point (on the computed part of a symmetric scene). */
    Point<2> location;
    /** The cell where it was found. */
    typename DoFHandler<2>::active_cell_iterator cell;
    /** The reference point in that cell, in [0,1]^2. */
    Point<2> reference_point;
  };

  /**
   * The largest value of the finite element field @p quantity of
   * @p solution over the plate (the computed part of a symmetric scene)
   * with its location. The value is the field's maximum to rounding; it
   * is not below a value at a lattice point (e.g. at a node) by more than
   * rounding and the tie rule allow: when several places reach the maximum
   * within 1e-9 of the field's magnitude (the largest |value| on the
   * lattice; mirror-equal peaks of a symmetric plate, a peak on a vertex
   * shared by several cells), the one with the smallest x, then the
   * smallest y, is reported, so that rounding does not move the location,
   * and its value may lie that little below the largest. A smooth peak is
   * located to far below 1e-6 of the cell size; where the field is flat
   * to second order (a ridge, a plateau) the location is any point of the
   * flat part. A field without a finite value gives a NaN value. With
   * @p slab, only that slab's cells (material id, plate/slab_grid.h) are
   * searched.
   */
  FieldExtremum
  field_maximum(const MindlinPlate      &plate,
                const Vector<double>    &solution,
                const PlateQuantity      quantity,
                const types::material_id slab = numbers::invalid_material_id);

  /** The smallest value, as field_maximum(). */
  FieldExtremum
  field_minimum(const MindlinPlate   &plate,
                const Vector<double> &solution,
                const PlateQuantity   quantity);

  /** Both peaks of one field. */
  struct FieldExtrema
  {
    FieldExtremum minimum, maximum;
  };

  /**
   * field_minimum() and field_maximum() of the same field in one sweep over
   * the cells (the results are the same as theirs).
   */
  FieldExtrema
  field_extrema(const MindlinPlate   &plate,
                const Vector<double> &solution,
                const PlateQuantity   quantity);

  class ResultRecord;

  /**
   * The peaks of a cycle (doc/outputs.md, "Peaks"): of w, of q
   * (@p pressure_field: the nodal pressures interpolated in the w-space),
   * of Mx, My, the larger principal moment and the fibres' principal
   * stresses, each with its location, as keys of @p record.
   */
  void
  add_peak_results(const MindlinPlate   &plate,
                   const Vector<double> &solution,
                   const Vector<double> &pressure_field,
                   ResultRecord         &record);
} // namespace PlateOnHalfspace

#endif
