/**
 * What both contact solvers share of the primal-dual active set method
 * (doc/formulation.md, "Tensionless contact"; deal.II step-41): whether a
 * contact set can carry the plate, the one message for a plate that it
 * cannot, the measures of the contact conditions, and the set update.
 */
#ifndef plate_on_halfspace_contact_active_set_h
#define plate_on_halfspace_contact_active_set_h

#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/interface.h>
#include <plate_on_halfspace/plate/foundation_space.h>

#include <ostream>
#include <set>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /**
   * The message of every refusal of a contact set that cannot carry the
   * plate, with what the user can change: giving the plate its weight
   * only for a weightless plate (set_plate_weightless()).
   */
  std::string
  plate_is_mechanism_message();

  /**
   * Whether the scene's plate has no weight (Plate/Unit weight = 0), for
   * plate_is_mechanism_message(); create_contact_solver() sets it from the
   * scene. Until then the message assumes a weightless plate.
   */
  void
  set_plate_weightless(const bool weightless);

  /**
   * Whether the nodes flagged in @p in_contact can carry a plate: at least
   * three of them (with their mirror images), not on one line
   * (doc/formulation.md: fewer than three non-collinear supporting points make
   * the plate a mechanism).
   */
  bool
  contact_set_supports_plate(const FoundationSpace   &space,
                             const std::vector<bool> &in_contact);

  /**
   * Whether @p state's contact set carries the plate only through nodes
   * without pressure: its nodes whose pressure coefficient exceeds 1e-6 of
   * the largest no longer carry the plate on their own (contact_set_
   * supports_plate()). The plate then balances on a line of nodes (a knife
   * edge), and the contact conditions hold for a range of tilts about it.
   */
  bool
  carried_on_knife_edge(const FoundationSpace &space,
                        const ContactState    &state);

  /**
   * Fill complementarity_violation, tensile_nodes and max_penetration of
   * @p state from its q and gap (which must be set), with @p plate_settlement
   * = B w giving the gap's scale and @p supported the nodes under the
   * foundation (the only ones whose gap is constrained).
   */
  void
  evaluate_contact_conditions(const Vector<double>    &plate_settlement,
                              const std::vector<bool> &supported,
                              ContactState            &state);

  /**
   * The first contact set of an active set: the @p supported nodes,
   * restricted to @p seed (e.g. the previous cycle's set) if that has the
   * right size and can carry the plate.
   */
  std::vector<bool>
  initial_contact_set(const FoundationSpace   &space,
                      const std::vector<bool> &supported,
                      const std::vector<bool> &seed);

  /**
   * The set update of the primal-dual active set method (doc/formulation.md,
   * "Tensionless contact"; deal.II step-41): C = {i : q_i + c g_i > 0}.
   * On C the gap is zero and off C the pressure is, so the test reads
   * q_i < 0 on C and g_i < 0 (penetration) off C; c only balances the units.
   * If a full step returns to a set seen before (a cycle), it falls back to
   * Murty's least-index rule, one status change per step, which terminates
   * for the SPD Galerkin problem. Every step keeps a set that carries the
   * plate (contact_set_supports_plate()): a full step that would leave a
   * mechanism takes every entry, then the exits in order while the rest
   * still carries the plate; a single pivot is the least index whose change
   * keeps the set carrying. Where no such change is left (every violation
   * is a tensile node whose exit would leave a mechanism, and no node
   * penetrates), the tensile node is exchanged for the node whose gap the
   * rigid motion freed by its exit closes first: the pivot of a simplex
   * step on the plate's rigid motions (doc/formulation.md, "Tensionless
   * contact"). Shared by the direct and the iterative contact solvers so
   * that both walk the same sequence of sets.
   */
  class ActiveSetUpdate
  {
  public:
    /**
     * Start from initial_contact_set(@p supported, @p initial_contact).
     * @p test_coupling is B of the gaps' tests (FoundationOperator::
     * test_coupling()): a rigid motion m changes the gaps by -B m.
     */
    ActiveSetUpdate(const FoundationSpace      &space,
                    const std::vector<bool>    &supported,
                    const std::vector<bool>    &initial_contact,
                    const SparseMatrix<double> &test_coupling);

    /** The current contact set. */
    const std::vector<bool> &
    contact_set() const
    {
      return active;
    }

    /**
     * One step after a solve on the current set with solution (@p q,
     * @p gap): count the violated conditions (signs below @p q_tolerance
     * and @p g_tolerance are rounding), log iteration @p iteration at
     * @p verbosity > 0, and return true if none is violated (converged).
     * Otherwise move to the next set: the full step, or one status change
     * once a cycle has switched on single pivots, kept to a set that
     * carries the plate (see the class documentation). Throws ExcMessage
     * if no change keeps the plate carried (a load at the edge of a
     * weightless plate).
     */
    bool
    step(const Vector<double> &q,
         const Vector<double> &gap,
         const double          q_tolerance,
         const double          g_tolerance,
         const unsigned int    iteration,
         const unsigned int    verbosity,
         std::ostream         &log);

    /**
     * The sets seen so far were judged by solves of a coarser accuracy
     * than the next ones: returning to one of them is a correction, not a
     * cycle. Forget them (and leave single pivots).
     */
    void
    forget_visited_sets();

  private:
    /** Size of the current contact set. */
    unsigned int
    n_contact_nodes() const;

    /**
     * Count the violated conditions of (@p q, @p gap) on the current set
     * and prepare the full step. Returns the number of changes.
     */
    unsigned int
    find_violations(const Vector<double> &q,
                    const Vector<double> &gap,
                    const double          q_tolerance,
                    const double          g_tolerance);

    /**
     * Record the current set; if the full step find_violations() prepared
     * returns to a set seen before (a cycle), switch to single pivots and
     * return true.
     */
    bool
    detect_cycle();

    /** Move to the next set (see step()), from the solution (@p q,
     *  @p gap) that find_violations() judged. */
    void
    advance(const Vector<double> &q, const Vector<double> &gap);

    /**
     * The set with a tensile node of the current one exchanged for the
     * node that the rigid motion freed by its exit brings into contact
     * first, judged from (@p q, @p gap) (see the class documentation); the
     * current set if there is none.
     */
    std::vector<bool>
    exchange_tensile_node(const Vector<double> &q,
                          const Vector<double> &gap) const;

    const FoundationSpace      &space;
    const SparseMatrix<double> &test_coupling;
    std::vector<bool>           supported;
    std::vector<bool>           active;
    std::vector<bool>           next;
    std::vector<unsigned int>   changes; ///< violated entries, least first
    std::set<std::vector<bool>> visited;
    bool                        single_pivot_mode = false;
  };

} // namespace PlateOnHalfspace

#endif
