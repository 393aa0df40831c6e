/**
 * Results as declared records (doc/outputs.md; doc/architecture.md, "A new
 * result key"). Every producer of results (the mesh, the loads, the
 * contact, the peaks, the probes, the joints, the goal, the timing)
 * declares the keys it writes, with their unit and meaning, in its own
 * file, and sets their values in a cycle's ResultRecord. summary.json, the
 * columns of convergence.txt, the keys Verification/Checks accepts, the
 * help text of --print-results and the tables of doc/outputs.md (checked by
 * a test) all come from these declarations.
 */
#ifndef plate_on_halfspace_base_result_record_h
#define plate_on_halfspace_base_result_record_h

#include <deal.II/base/point.h>

#include <functional>
#include <string>
#include <variant>
#include <vector>

namespace PlateOnHalfspace
{
  using namespace dealii;

  /** What a result key holds. */
  enum class ResultKind
  {
    number,
    count,
    flag,
    text,
    /** [x, y] */
    location,
    /** an array of numbers or counts */
    list,
    /** a nested object (a table of its own) */
    object,
    /** an array of objects (a table of its own) */
    array
  };

  /**
   * One row of a table of result keys: keys that share a unit, a meaning
   * and a kind (doc/outputs.md prints the row as it is).
   */
  struct ResultDeclaration
  {
    /** The keys, e.g. {"max_w", "min_w"}. */
    std::vector<std::string> keys;
    /** "–" for a number without unit, a count, a flag or text. */
    std::string unit;
    /** Markdown; one paragraph. */
    std::string meaning;
    ResultKind  kind = ResultKind::number;
  };

  class ResultRecord;

  /**
   * One column of convergence.txt, a number of each cycle's record (and,
   * with @p with_change, its relative change from the previous cycle).
   */
  struct ConvergenceColumn
  {
    std::string name;
    /** Markdown; what the column shows (doc/outputs.md). */
    std::string meaning;
    /** The value; a column whose record lacks it (a goal's without a goal)
     *  is left out of that row. */
    std::function<bool(const ResultRecord &record, double &value)> value;
    unsigned int                                                   precision;
    bool scientific  = false;
    bool with_change = false;
  };

  /**
   * The keys one producer writes: @p table is the record they belong to
   * ("" the top of summary.json, "cycles" a cycle, "cycles.goal" its goal
   * object, "cycles.probes" an entry of its probes array, ...); @p position
   * orders producers within a table (and the columns of convergence.txt).
   * Called from a static initializer of the producer's file; returns true.
   */
  bool
  declare_results(const std::string                    &table,
                  const double                          position,
                  const std::vector<ResultDeclaration> &rows,
                  const std::vector<ConvergenceColumn> &columns = {});

  /** The declared rows of @p table in their order. */
  std::vector<ResultDeclaration>
  declared_results(const std::string &table);

  /** Every declared table, parents before their nested tables. */
  std::vector<std::string>
  declared_tables();

  /** The columns of convergence.txt in their order. */
  std::vector<ConvergenceColumn>
  declared_convergence_columns();

  /** @p table's rows as the markdown table of doc/outputs.md. */
  std::string
  results_markdown_table(const std::string &table);

  /** The columns of convergence.txt as the markdown table of
   *  doc/outputs.md. */
  std::string
  convergence_markdown_table();

  /** Every table's keys, units and meanings as plain text (--print-results). */
  std::string
  results_help_text();

  /** The numbers and counts of a cycle that Verification/Checks may test:
   *  "max_w", ..., and its goal's as "goal.value". */
  std::vector<std::string>
  checkable_result_keys();

  /**
   * The values of one record of results: numbers, counts, flags, text,
   * points, null, nested objects and arrays of objects. Setting a key that
   * its table does not declare, or a value of another kind than declared,
   * is an internal error, so no result reaches a file undocumented.
   */
  class ResultRecord
  {
  public:
    struct Null
    {};
    using Numbers = std::vector<double>;
    using Counts  = std::vector<unsigned long long>;
    /** A nested object (one record) or array of objects. */
    struct Nested
    {
      std::vector<ResultRecord> records;
      bool                      is_array = true;
    };
    using Value = std::variant<Null,
                               bool,
                               unsigned long long,
                               double,
                               std::string,
                               Numbers,
                               Counts,
                               Nested>;

    /** An empty record of the declared @p table. */
    explicit ResultRecord(const std::string &table = "cycles");

    const std::string &
    table() const
    {
      return table_name;
    }

    void
    set(const std::string &key, const double value);
    void
    set_count(const std::string &key, const unsigned long long value);
    void
    set(const std::string &key, const bool value);
    void
    set(const std::string &key, const std::string &value);
    void
    set(const std::string &key, const char *value);
    void
    set(const std::string &key, const Point<2> &value);
    void
    set(const std::string &key, const Numbers &value);
    void
    set(const std::string &key, const Counts &value);
    /** A number, or null if @p value is not finite (an LTE without a
     *  deflection). */
    void
    set_or_null(const std::string &key, const double value);
    void
    set_null(const std::string &key);
    /** The nested object @p key (created empty). */
    ResultRecord &
    set_object(const std::string &key);
    /** A new last entry of the array @p key (the array created empty). */
    ResultRecord &
    add_item(const std::string &key);
    /** Declares the array @p key, empty for now. */
    void
    set_empty_array(const std::string &key);

    bool
    has(const std::string &key) const;
    /** Whether @p key holds a number (or a count). */
    bool
    is_number(const std::string &key) const;
    /** A number or count; an internal error if @p key holds neither. */
    double
    number(const std::string &key) const;
    unsigned long long
    count(const std::string &key) const;
    bool
    flag(const std::string &key) const;
    const std::string &
    text(const std::string &key) const;
    Point<2>
    point(const std::string &key) const;
    const ResultRecord &
    object(const std::string &key) const;
    /** The entries of the array @p key; none if it is absent. */
    const std::vector<ResultRecord> &
    items(const std::string &key) const;
    const Value &
    value(const std::string &key) const;

    /** The keys set, in the order of the declarations. */
    std::vector<std::string>
    keys() const;

    /**
     * Every number of the record and its nested records, with its path
     * ("probes[0].w"), for checks over all of them (finite results).
     */
    void
    for_each_number(const std::function<void(const std::string &path,
                                             const double value)> &visit) const;

  private:
    std::string                                table_name;
    std::vector<std::pair<std::string, Value>> values;
    /** The value of @p key, declared of @p kind (null: set_null()). */
    Value &
    slot(const std::string &key, const ResultKind *kind);
    const Value *
    find(const std::string &key) const;
  };
} // namespace PlateOnHalfspace

#endif
