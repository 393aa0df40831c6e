/**
 * The direct contact solver (doc/formulation.md, "Tensionless contact"):
 * the plate condensed onto the foundation nodes (K̄, P̄; the paper's
 * (P18)-(P19)) and, on each contact set C, the dense coupled problem
 *   (K̄ + S) w = P̄,   S = (M T)_{:,C} F_CC^{-1} B_{C,:},
 *   q_C = F_CC^{-1} (B w)_C,  q = 0 off C,
 * factorised by LAPACK (Cholesky for a symmetric F, else LU). It serves
 * every half-space operator (it reads F_CC through copy_block()) and both
 * contact methods, the paper's element exclusion included; memory and time
 * grow like n^2 and n^3 in the foundation nodes.
 */
#ifndef plate_on_halfspace_contact_direct_solver_h
#define plate_on_halfspace_contact_direct_solver_h

#include <deal.II/lac/full_matrix.h>
#include <deal.II/lac/lapack_full_matrix.h>
#include <deal.II/lac/vector.h>

#include <plate_on_halfspace/contact/contact_iteration.h>

#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** See the file documentation. */
  class DirectContactSolver : public ContactIteration
  {
  public:
    DirectContactSolver(const Parameters::Contact &contact,
                        const bool                 tensionless,
                        const unsigned int         verbosity,
                        std::ostream              &log);

  protected:
    void
    prepare(MindlinPlate       &plate,
            FoundationOperator &foundation,
            ContactState       &state) override;

    void
    prepare_load(const Vector<double> &load) override;

    Vector<double>
    solve_on_set(const std::vector<bool> &contact_set,
                 const double             tolerance,
                 ContactState            &state) override;

  private:
    /** Factorise F_CC of the supported nodes of @p contact_set. */
    void
    factorise_contact_block(const std::vector<bool> &contact_set,
                            ContactState            &state);

    /** q_C = F_CC^{-1} (B w)_C and q = 0 off C. */
    void
    pressures(const Vector<double> &w, Vector<double> &q) const;

    /** matrix += (M T)_{:,C} F_CC^{-1} B_{C,:}: the foundation stiffness. */
    void
    add_foundation_stiffness(LAPACKFullMatrix<double> &matrix) const;

    /**
     * Refuse pressures that rounding leaves less accurate than
     * accepted_rounding_floor, measured by one step of iterative refinement
     * (a soil far stiffer than the plate over a cell; see the
     * implementation).
     */
    void
    check_accepted_solution(const ContactState &state) const override;

    /**
     * The rigid-body motion R a that restores R^T S (w + R a) = R^T f for
     * the forces @p f (correct_rigid_body_equilibrium()'s correction).
     */
    Vector<double>
    rigid_correction(const Vector<double> &w, const Vector<double> &f) const;

    /**
     * Restore vertical force and moment equilibrium within the rigid-body
     * kernel of the free plate (see the implementation for why).
     */
    void
    correct_rigid_body_equilibrium(ContactState &state) const;

    /** @p w as amplitudes of rigid_motions (a least-squares fit) and the
     *  rest, the bending part. */
    void
    split(const Vector<double> &w,
          Vector<double>       &amplitudes,
          Vector<double>       &bending) const;

    /**
     * One step of iterative refinement of the solve on the current set:
     * the correction of w = R a + @p bending from the residual
     * P̄ - K̄ w - S w with the pressures @p q of w (see the
     * implementation).
     */
    Vector<double>
    refinement_step(const Vector<double> &bending,
                    const Vector<double> &q) const;

    /** Refine w held as @p amplitudes and @p bending, and state.w and
     *  state.q with them, while the steps shrink (a plate much stiffer
     *  than the soil; see the implementation). */
    void
    refine_bending(Vector<double> &amplitudes,
                   Vector<double> &bending,
                   ContactState   &state) const;

    /** At most this many steps of refine_bending(). */
    static constexpr unsigned int max_refinement_steps = 4;

    /** The whole plate's solution from w = R @p amplitudes + @p bending at
     *  the foundation nodes (see the implementation). */
    void
    expand(const Vector<double> &amplitudes,
           const Vector<double> &bending,
           Vector<double>       &solution) const;

    LAPACKFullMatrix<double> plate_stiffness; ///< K̄
    Vector<double>           load;            ///< P of the current solve
    Vector<double>           plate_load;      ///< P̄
    /** The rigid-body motions of the free plate at the foundation nodes. */
    std::vector<Vector<double>> rigid_motions;
    /** The same motions over all of the plate's DoFs. */
    std::vector<Vector<double>> plate_rigid_motions;
    /** The inverse of the motions' Gram matrix at the foundation nodes. */
    FullMatrix<double>        rigid_gram_inverse;
    std::vector<unsigned int> contact_index;  ///< the nodes of C
    LAPACKFullMatrix<double>  contact_factor; ///< factor of F_CC
    LAPACKFullMatrix<double>  coupled;        ///< factor of K̄ + S
    /** The contact set of contact_factor and coupled, and their 1/κ₁. */
    std::vector<bool> factorised_set;
    double            coupled_rcond = 1, block_rcond = 1;
    bool              factorised_once = false;
  };
} // namespace PlateOnHalfspace

#endif
