#include <deal.II/base/exceptions.h>

#include <plate_on_halfspace/base/result_record.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    struct ProducerDeclaration
    {
      double                         position;
      std::vector<ResultDeclaration> rows;
      std::vector<ConvergenceColumn> columns;
    };

    /** Declarations by table; each table's producers in their order. */
    std::map<std::string, std::vector<ProducerDeclaration>> &
    registry()
    {
      static std::map<std::string, std::vector<ProducerDeclaration>> tables;
      return tables;
    }

    /** The index of @p key among @p table's declared keys, or -1, and
     *  its kind. */
    int
    declared_index(const std::string &table,
                   const std::string &key,
                   ResultKind        *kind = nullptr)
    {
      // the registry in place: every set() asks, so nothing is copied
      const auto found = registry().find(table);
      if (found == registry().end())
        return -1;
      int index = 0;
      for (const ProducerDeclaration &producer : found->second)
        for (const ResultDeclaration &row : producer.rows)
          for (const std::string &k : row.keys)
            {
              if (k == key)
                {
                  if (kind != nullptr)
                    *kind = row.kind;
                  return index;
                }
              ++index;
            }
      return -1;
    }

    /** Each kind as an object, for ResultRecord::slot(). */
    namespace kinds
    {
      const ResultKind number = ResultKind::number, count = ResultKind::count,
                       flag = ResultKind::flag, text = ResultKind::text,
                       location = ResultKind::location, list = ResultKind::list,
                       object = ResultKind::object, array = ResultKind::array;
    } // namespace kinds

    /** A nested table's name: "cycles" and "probes" give "cycles.probes". */
    std::string
    nested_table(const std::string &table, const std::string &key)
    {
      return table.empty() ? key : table + "." + key;
    }
  } // namespace

  bool
  declare_results(const std::string                    &table,
                  const double                          position,
                  const std::vector<ResultDeclaration> &rows,
                  const std::vector<ConvergenceColumn> &columns)
  {
    auto &producers = registry()[table];
    producers.push_back({position, rows, columns});
    std::stable_sort(producers.begin(),
                     producers.end(),
                     [](const auto &a, const auto &b) {
                       return a.position < b.position;
                     });
    return true;
  }

  std::vector<ResultDeclaration>
  declared_results(const std::string &table)
  {
    std::vector<ResultDeclaration> rows;
    const auto                     found = registry().find(table);
    if (found != registry().end())
      for (const ProducerDeclaration &producer : found->second)
        rows.insert(rows.end(), producer.rows.begin(), producer.rows.end());
    return rows;
  }

  std::vector<std::string>
  declared_tables()
  {
    // "" first, then "cycles", then its nested tables: the map's order of
    // names, as a parent's name is a prefix of its children's
    std::vector<std::string> tables;
    for (const auto &[table, producers] : registry())
      tables.push_back(table);
    return tables;
  }

  std::vector<ConvergenceColumn>
  declared_convergence_columns()
  {
    // in the producers' order over all tables
    std::vector<std::pair<double, ConvergenceColumn>> ordered;
    for (const auto &[table, producers] : registry())
      for (const ProducerDeclaration &producer : producers)
        for (const ConvergenceColumn &column : producer.columns)
          ordered.emplace_back(producer.position, column);
    std::stable_sort(ordered.begin(),
                     ordered.end(),
                     [](const auto &a, const auto &b) {
                       return a.first < b.first;
                     });
    std::vector<ConvergenceColumn> columns;
    for (const auto &[position, column] : ordered)
      columns.push_back(column);
    return columns;
  }

  std::string
  results_markdown_table(const std::string &table)
  {
    std::ostringstream text;
    text << "| key | unit | meaning |\n|---|---|---|\n";
    for (const ResultDeclaration &row : declared_results(table))
      {
        text << "| ";
        for (unsigned int k = 0; k < row.keys.size(); ++k)
          text << (k > 0 ? ", " : "") << '`' << row.keys[k] << '`';
        text << " | " << row.unit << " | " << row.meaning << " |\n";
      }
    return text.str();
  }

  std::string
  convergence_markdown_table()
  {
    std::ostringstream text;
    text << "| column | meaning |\n|---|---|\n";
    for (const ConvergenceColumn &column : declared_convergence_columns())
      text << "| `" << column.name << "`"
           << (column.with_change ? ", `change " + column.name + "`" : "")
           << " | " << column.meaning
           << (column.with_change ?
                 "; and its relative change from the previous cycle (`-` on "
                 "the first)" :
                 "")
           << " |\n";
    return text.str();
  }

  std::string
  results_help_text()
  {
    // the markdown as plain text: a table cell's escaped bar as a bar
    const auto plain = [](std::string meaning) {
      for (auto at = meaning.find("\\|"); at != std::string::npos;
           at      = meaning.find("\\|", at))
        meaning.erase(at, 1);
      return meaning;
    };
    std::ostringstream text;
    text << "Keys of summary.json (doc/outputs.md), by object:\n";
    for (const std::string &table : declared_tables())
      {
        text << "\n" << (table.empty() ? "(top level)" : table) << ":\n";
        for (const ResultDeclaration &row : declared_results(table))
          {
            text << "  ";
            for (unsigned int k = 0; k < row.keys.size(); ++k)
              text << (k > 0 ? ", " : "") << row.keys[k];
            text << " [" << row.unit << "]: " << plain(row.meaning) << "\n";
          }
      }
    text << "\nColumns of convergence.txt:\n";
    for (const ConvergenceColumn &column : declared_convergence_columns())
      text << "  " << column.name
           << (column.with_change ? " (and change " + column.name + ")" : "")
           << ": " << plain(column.meaning) << "\n";
    return text.str();
  }

  std::vector<std::string>
  checkable_result_keys()
  {
    // a cycle's numbers and counts and its goal's; a declared number may
    // still be null on the last cycle (a goal's dwr without an adjoint
    // problem), which run_checks() reports as a failed check
    std::vector<std::string> keys;
    for (const auto &[table, prefix] :
         {std::pair<std::string, std::string>{"cycles", ""},
          std::pair<std::string, std::string>{"cycles.goal", "goal."}})
      for (const ResultDeclaration &row : declared_results(table))
        if (row.kind == ResultKind::number || row.kind == ResultKind::count)
          for (const std::string &key : row.keys)
            keys.push_back(prefix + key);
    return keys;
  }

  ResultRecord::ResultRecord(const std::string &table)
    : table_name(table)
  {}

  ResultRecord::Value &
  ResultRecord::slot(const std::string &key, const ResultKind *kind)
  {
    ResultKind declared;
    AssertThrow(declared_index(table_name, key, &declared) >= 0,
                ExcMessage("Internal error: the result key <" + key + "> of <" +
                           table_name +
                           "> is not declared (declare_results())."));
    AssertThrow(kind == nullptr || *kind == declared,
                ExcMessage("Internal error: the result key <" + key + "> of <" +
                           table_name +
                           "> is set to another kind of value than "
                           "declared."));
    for (auto &[k, v] : values)
      if (k == key)
        return v;
    values.emplace_back(key, Null());
    return values.back().second;
  }

  const ResultRecord::Value *
  ResultRecord::find(const std::string &key) const
  {
    for (const auto &[k, v] : values)
      if (k == key)
        return &v;
    return nullptr;
  }

  void
  ResultRecord::set(const std::string &key, const double value)
  {
    slot(key, &kinds::number) = value;
  }

  void
  ResultRecord::set_count(const std::string       &key,
                          const unsigned long long value)
  {
    slot(key, &kinds::count) = value;
  }

  void
  ResultRecord::set(const std::string &key, const bool value)
  {
    slot(key, &kinds::flag) = value;
  }

  void
  ResultRecord::set(const std::string &key, const std::string &value)
  {
    slot(key, &kinds::text) = value;
  }

  void
  ResultRecord::set(const std::string &key, const char *value)
  {
    slot(key, &kinds::text) = std::string(value);
  }

  void
  ResultRecord::set(const std::string &key, const Point<2> &value)
  {
    slot(key, &kinds::location) = Numbers{value[0], value[1]};
  }

  void
  ResultRecord::set(const std::string &key, const Numbers &value)
  {
    slot(key, &kinds::list) = value;
  }

  void
  ResultRecord::set(const std::string &key, const Counts &value)
  {
    slot(key, &kinds::list) = value;
  }

  void
  ResultRecord::set_or_null(const std::string &key, const double value)
  {
    Value &v = slot(key, &kinds::number);
    if (std::isfinite(value))
      v = value;
    else
      v = Null();
  }

  void
  ResultRecord::set_null(const std::string &key)
  {
    slot(key, nullptr) = Null();
  }

  ResultRecord &
  ResultRecord::set_object(const std::string &key)
  {
    Nested object;
    object.is_array = false;
    object.records.emplace_back(nested_table(table_name, key));
    Value &v = slot(key, &kinds::object);
    v        = std::move(object);
    return std::get<Nested>(v).records.front();
  }

  ResultRecord &
  ResultRecord::add_item(const std::string &key)
  {
    Value &v = slot(key, &kinds::array);
    if (!std::holds_alternative<Nested>(v))
      v = Nested();
    auto &records = std::get<Nested>(v).records;
    records.emplace_back(nested_table(table_name, key));
    return records.back();
  }

  void
  ResultRecord::set_empty_array(const std::string &key)
  {
    slot(key, &kinds::array) = Nested();
  }

  bool
  ResultRecord::has(const std::string &key) const
  {
    return find(key) != nullptr;
  }

  const ResultRecord::Value &
  ResultRecord::value(const std::string &key) const
  {
    const Value *v = find(key);
    AssertThrow(v != nullptr,
                ExcMessage("Internal error: the result <" + key + "> of <" +
                           table_name + "> has not been set."));
    return *v;
  }

  bool
  ResultRecord::is_number(const std::string &key) const
  {
    const Value *v = find(key);
    return v != nullptr && (std::holds_alternative<double>(*v) ||
                            std::holds_alternative<unsigned long long>(*v));
  }

  double
  ResultRecord::number(const std::string &key) const
  {
    const Value &v = value(key);
    if (const auto *c = std::get_if<unsigned long long>(&v))
      return static_cast<double>(*c);
    AssertThrow(std::holds_alternative<double>(v),
                ExcMessage("Internal error: the result <" + key + "> of <" +
                           table_name + "> is not a number."));
    return std::get<double>(v);
  }

  unsigned long long
  ResultRecord::count(const std::string &key) const
  {
    const Value &v = value(key);
    AssertThrow(std::holds_alternative<unsigned long long>(v),
                ExcMessage("Internal error: the result <" + key + "> of <" +
                           table_name + "> is not a count."));
    return std::get<unsigned long long>(v);
  }

  bool
  ResultRecord::flag(const std::string &key) const
  {
    return std::get<bool>(value(key));
  }

  const std::string &
  ResultRecord::text(const std::string &key) const
  {
    return std::get<std::string>(value(key));
  }

  Point<2>
  ResultRecord::point(const std::string &key) const
  {
    const Numbers &p = std::get<Numbers>(value(key));
    return Point<2>(p[0], p[1]);
  }

  const ResultRecord &
  ResultRecord::object(const std::string &key) const
  {
    const Nested &n = std::get<Nested>(value(key));
    AssertThrow(!n.is_array && n.records.size() == 1,
                ExcMessage("Internal error: the result <" + key + "> of <" +
                           table_name + "> is not an object."));
    return n.records.front();
  }

  const std::vector<ResultRecord> &
  ResultRecord::items(const std::string &key) const
  {
    static const std::vector<ResultRecord> none;
    const Value                           *v = find(key);
    if (v == nullptr || !std::holds_alternative<Nested>(*v))
      return none;
    return std::get<Nested>(*v).records;
  }

  std::vector<std::string>
  ResultRecord::keys() const
  {
    std::vector<std::pair<int, std::string>> ordered;
    for (const auto &[k, v] : values)
      ordered.emplace_back(declared_index(table_name, k), k);
    std::sort(ordered.begin(), ordered.end());
    std::vector<std::string> set;
    for (const auto &[index, k] : ordered)
      set.push_back(k);
    return set;
  }

  void
  ResultRecord::for_each_number(
    const std::function<void(const std::string &path, const double value)>
      &visit) const
  {
    for (const std::string &key : keys())
      {
        const Value &v = value(key);
        if (const auto *d = std::get_if<double>(&v))
          visit(key, *d);
        else if (const auto *p = std::get_if<Numbers>(&v))
          for (unsigned int i = 0; i < p->size(); ++i)
            visit(key + "[" + std::to_string(i) + "]", (*p)[i]);
        else if (const auto *n = std::get_if<Nested>(&v))
          for (unsigned int i = 0; i < n->records.size(); ++i)
            n->records[i].for_each_number([&](const std::string &path,
                                              const double       value) {
              visit(key + (n->is_array ? "[" + std::to_string(i) + "]." : ".") +
                      path,
                    value);
            });
      }
  }
} // namespace PlateOnHalfspace
