/**
 * The contact's results of a cycle (doc/outputs.md, "summary.json"): its
 * iterations, the area and the nodes in contact, equilibrium, the
 * conditions' residuals and the solver's condition estimates.
 */
#ifndef plate_on_halfspace_contact_contact_results_h
#define plate_on_halfspace_contact_contact_results_h

namespace PlateOnHalfspace
{
  struct ContactState;
  struct FoundationSpace;
  class FoundationOperator;
  class ResultRecord;

  /** Sets the contact's keys of a cycle's @p record from the solved
   *  @p contact; sums over the computed part count for the whole plate. */
  void
  add_contact_results(const FoundationSpace    &space,
                      const FoundationOperator &foundation,
                      const ContactState       &contact,
                      ResultRecord             &record);
} // namespace PlateOnHalfspace

#endif
