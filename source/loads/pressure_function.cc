#include <deal.II/base/function_parser.h>
#include <deal.II/base/numbers.h>
#include <deal.II/base/quadrature_lib.h>
#include <deal.II/base/utilities.h>

#include <plate_on_halfspace/base/number_list.h>
#include <plate_on_halfspace/base/quadrilateral_geometry.h>
#include <plate_on_halfspace/loads/load.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <iostream>
#include <map>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    const std::string entry = "Loads/Pressure function";

    /** Its entries (declare_parameters()), parsed. */
    struct PressureFunctionSettings
    {
      enum class Region
      {
        plate,
        rectangle,
        disk
      };
      /** The expression in x and y; empty: no pressure function. */
      std::string                   expression;
      std::map<std::string, double> constants;
      Region                        region = Region::plate;
      /** Region = rectangle: [lower, upper]; disk: centre and radius. */
      Point<2> lower, upper, centre;
      double   radius = 0;
      /** Gauss points per direction on each cell (or piece of a cell). */
      unsigned int points = 6;

      static void
      declare_parameters(ParameterHandler &prm);
      void
      parse_parameters(ParameterHandler &prm);
    };

    std::string
    number(const double value)
    {
      std::ostringstream s;
      s << value;
      return s.str();
    }

    /** @p text as a message quotes it: at most 100 characters. */
    std::string
    quoted(const std::string &text)
    {
      return "<" + (text.size() <= 100 ? text : text.substr(0, 100) + "...") +
             ">";
    }

    /**
     * Why @p expression is not one expression muparser would evaluate as
     * written, or "": a comma outside parentheses separates several
     * results (muparser returns the last), and a lone = assigns to a
     * variable.
     */
    std::string
    not_one_expression(const std::string &expression)
    {
      int depth = 0;
      for (std::size_t i = 0; i < expression.size(); ++i)
        {
          const char c = expression[i];
          depth += (c == '(') - (c == ')');
          if (c == ',' && depth == 0)
            return "a comma outside parentheses would separate several "
                   "expressions";
          if (c == ';')
            return "a ; would separate several expressions";
          const char before = i > 0 ? expression[i - 1] : ' ';
          const char after =
            i + 1 < expression.size() ? expression[i + 1] : ' ';
          if (c == '=' && before != '=' && before != '<' && before != '>' &&
              before != '!' && after != '=')
            return "a single = would assign to a variable (compare with ==)";
        }
      // rand() draws anew at every evaluation: the load vector, the
      // checks and the goal estimate would each see another pressure
      const auto part_of_name = [&](const std::size_t i) {
        return i < expression.size() &&
               (std::isalnum(static_cast<unsigned char>(expression[i])) ||
                expression[i] == '_');
      };
      for (std::size_t at = expression.find("rand"); at != std::string::npos;
           at             = expression.find("rand", at + 1))
        if ((at == 0 || !part_of_name(at - 1)) && !part_of_name(at + 4))
          return "rand() gives another pressure at every evaluation (use "
                             "rand_seed(seed), which repeats)";
      return "";
    }

    /** The parsed expression; throws a message naming the entries. */
    std::shared_ptr<FunctionParser<2>>
    parsed_function(const PressureFunctionSettings &settings)
    {
      const std::string misuse = not_one_expression(settings.expression);
      AssertThrow(misuse.empty(),
                  ExcMessage(entry + ": " + quoted(settings.expression) +
                             " is not one expression in x and y: " + misuse +
                             "."));
      // pi as deal.II's ParsedFunction knows it (no constant may take
      // its name)
      std::map<std::string, double> constants = settings.constants;
      constants["pi"]                         = numbers::PI;
      auto function = std::make_shared<FunctionParser<2>>(1);
      // deal.II prints muparser's own report on std::cerr before it
      // throws: keep it out of the terminal, the message below says it
      std::ostringstream report;
      std::streambuf    *terminal = std::cerr.rdbuf(report.rdbuf());
      std::string        reason;
      try
        {
          function->initialize("x,y", settings.expression, constants);
          // muparser parses on the first evaluation
          function->value(Point<2>());
        }
      catch (const ExceptionBase &e)
        {
          std::ostringstream info;
          e.print_info(info);
          reason = info.str();
        }
      catch (const std::exception &e)
        {
          reason = e.what();
        }
      catch (...)
        {
          // muparser's own errors are no std::exception
          reason = "muparser refused it";
        }
      std::cerr.rdbuf(terminal);
      std::replace(reason.begin(), reason.end(), '\n', ' ');
      // deal.II's column counts from the start of its own buffer; muparser's
      // position, which follows, counts in the expression
      const std::string said = "The parser said: ";
      if (reason.find(said) != std::string::npos)
        reason = reason.substr(reason.find(said) + said.size());
      AssertThrow(reason.empty(),
                  ExcMessage(entry + ": cannot evaluate " +
                             quoted(settings.expression) +
                             " as a function of x and y (with "
                             "Loads/Function constants): " +
                             Utilities::trim(reason).substr(0, 200)));
      return function;
    }

    /** The pressure p(x, y) over the plate or a region of it. */
    class PressureFunctionLoad : public Load
    {
    public:
      explicit PressureFunctionLoad(const PressureFunctionSettings &settings)
        : settings(settings)
        , function(parsed_function(settings))
        , region_shape(
            settings.region == PressureFunctionSettings::Region::rectangle ?
              create_rectangular_patch(settings.lower,
                                       settings.upper,
                                       1.,
                                       entry) :
            settings.region == PressureFunctionSettings::Region::disk ?
              create_circular_patch(settings.centre,
                                    settings.radius,
                                    1.,
                                    entry) :
              nullptr)
      {}

      std::string
      label() const override
      {
        return entry;
      }

      CellLoad
      on_cell(const BilinearQuadrilateral &cell,
              const unsigned int           extra_points) const override
      {
        using Region            = PressureFunctionSettings::Region;
        const unsigned int n_1d = settings.points + extra_points;
        Quadrature<2>      rule;
        switch (settings.region)
          {
            case Region::plate:
              rule = quadrature_on_cell(cell, n_1d);
              break;
            case Region::rectangle:
              rule = quadrature_on_rectangle_part(cell,
                                                  settings.lower,
                                                  settings.upper,
                                                  n_1d);
              break;
            case Region::disk:
              rule = quadrature_on_disk_part(cell,
                                             settings.centre,
                                             settings.radius,
                                             n_1d);
              break;
          }
        std::vector<double> pressure(rule.size());
        for (unsigned int q = 0; q < rule.size(); ++q)
          {
            const Point<2> x = cell.map(rule.point(q));
            pressure[q]      = function->value(x);
            AssertThrow(std::isfinite(pressure[q]),
                        ExcMessage(
                          entry + ": " + quoted(settings.expression) + " is " +
                          (std::isnan(pressure[q]) ?
                             std::string("not a number") :
                             number(pressure[q])) +
                          " at (" + number(x[0]) + ", " + number(x[1]) +
                          ") on the plate; the pressure must be "
                          "finite wherever it applies."));
          }
        return {std::move(rule), std::move(pressure)};
      }

      double
      jump_on(const std::array<Point<2>, 4> &vertices,
              const double                   area) const override
      {
        // Over the whole plate it is smooth: the residual's jumps see its
        // variation. A region's edge crossing the cell is a unit patch's
        // jump times the pressure at the cell's centre.
        if (!region_shape)
          return 0;
        const double edge = region_shape->jump_on(vertices, area);
        if (edge == 0)
          return 0;
        const Point<2> centre =
          0.25 * (vertices[0] + vertices[1] + vertices[2] + vertices[3]);
        return std::abs(function->value(centre)) * edge;
      }

      std::optional<double>
      region_area() const override
      {
        return region_shape ? region_shape->region_area() :
                              std::optional<double>();
      }

      std::optional<double>
      region_width() const override
      {
        return region_shape ? region_shape->region_width() :
                              std::optional<double>();
      }

      bool
      standing() const override
      {
        return settings.region == PressureFunctionSettings::Region::plate;
      }

      std::shared_ptr<const Load>
      mirror_image(const unsigned int) const override
      {
        // whether an expression is mirror symmetric is not decided by
        // sampling it: a scene with one is solved whole
        return nullptr;
      }

      bool
      same_as(const Load &other, const double) const override
      {
        return &other == this;
      }

      std::shared_ptr<const Load>
      on_computed_part(const std::array<bool, 2> &, const double) const override
      {
        return std::make_shared<PressureFunctionLoad>(*this);
      }

    private:
      PressureFunctionSettings           settings;
      std::shared_ptr<FunctionParser<2>> function;
      /** The region as a patch of unit pressure (null: the whole plate):
       *  its edge, for Kelly, and its area. */
      std::shared_ptr<const Load> region_shape;
    };
  } // namespace

  void
  PressureFunctionSettings::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Pressure function",
                      "",
                      Patterns::Anything(),
                      "A pressure that varies over the plate, downward "
                      "positive [force/length^2]: a deal.II FunctionParser "
                      "expression in x and y (e.g. 5*(y+1)^2, or "
                      "p0*(1 - x/a) with Function constants), over the whole "
                      "plate or over Pressure function region. Empty: none.");
    prm.declare_entry("Function constants",
                      "",
                      Patterns::Anything(),
                      "Named constants of Pressure function: name=value, ... "
                      "(e.g. p0=5, a=2); names are letters, digits and _, "
                      "starting with a letter, at most 100 characters, "
                      "neither x nor y nor pi nor one of muparser's "
                      "functions (pi is known).");
    prm.declare_entry("Pressure function region",
                      "",
                      Patterns::Anything(),
                      "Where Pressure function applies: empty for the whole "
                      "plate, x1,y1,x2,y2 for a rectangle (x1<x2, y1<y2) or "
                      "xc,yc,radius for a disk (radius > 0).");
    prm.declare_entry("Pressure function points",
                      "6",
                      Patterns::Integer(1, 30),
                      "Gauss points per direction with which Pressure "
                      "function is integrated on each cell (or each piece "
                      "of a cell a region's edge cuts), 1 to 30; "
                      "summary.json's load_integration_error compares the "
                      "applied load with 3 points more on each quarter of "
                      "each cell.");
  }

  void
  PressureFunctionSettings::parse_parameters(ParameterHandler &prm)
  {
    expression = Utilities::trim(prm.get("Pressure function"));
    constants.clear();
    const std::string constants_text = prm.get("Function constants");
    AssertThrow(constants_text.find(';') == std::string::npos,
                ExcMessage("Entry <Loads/Function constants>: separate the "
                           "constants by commas (name=value, name=value), "
                           "not by ; (got " +
                           quoted(constants_text) + ")."));
    const auto items = split_without_empty(constants_text, ',');
    AssertThrow(items,
                ExcMessage("Entry <Loads/Function constants>: " +
                           quoted(constants_text) +
                           " has an empty constant (nothing between two "
                           "commas, or after the last)."));
    // muparser's and deal.II's functions, which a constant would hide
    static const std::vector<std::string> functions = {
      "sin",  "cos",   "tan",   "asin",      "acos",  "atan",  "sinh", "cosh",
      "tanh", "asinh", "acosh", "atanh",     "log2",  "log10", "log",  "ln",
      "exp",  "sqrt",  "sign",  "rint",      "abs",   "min",   "max",  "sum",
      "avg",  "if",    "int",   "ceil",      "floor", "cot",   "csc",  "sec",
      "pow",  "erfc",  "rand",  "rand_seed", "atan2", "fmod",  "pi"};
    for (const std::string &item : *items)
      {
        const auto equals = item.find('=');
        AssertThrow(equals != std::string::npos,
                    ExcMessage("Entry <Loads/Function constants>: the item <" +
                               item + "> must read name=value."));
        const std::string name = Utilities::trim(item.substr(0, equals));
        const bool        identifier =
          !name.empty() && std::isalpha(static_cast<unsigned char>(name[0])) &&
          std::all_of(name.begin(), name.end(), [](const char c) {
            return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
          });
        AssertThrow(identifier && name != "x" && name != "y" &&
                      std::find(functions.begin(), functions.end(), name) ==
                        functions.end(),
                    ExcMessage(
                      "Entry <Loads/Function constants>: " + quoted(name) +
                      " is not a constant's name (letters, digits "
                      "and _, starting with a letter, neither x nor "
                      "y nor pi nor a function of muparser)."));
        AssertThrow(name.size() <= 100,
                    ExcMessage(
                      "Entry <Loads/Function constants>: " + quoted(name) +
                      " is longer than muparser's 100 characters."));
        AssertThrow(constants.count(name) == 0,
                    ExcMessage("Entry <Loads/Function constants>: <" + name +
                               "> is given twice."));
        const auto value = parse_number_list(item.substr(equals + 1),
                                             1,
                                             "Loads/Function constants",
                                             "value");
        AssertThrow(value.size() == 1,
                    ExcMessage("Entry <Loads/Function constants>: <" + name +
                               "> has no value."));
        constants[name] = value[0][0];
      }
    const std::string region_text = prm.get("Pressure function region");
    const auto        region_numbers =
      parse_number_list(region_text, 0, "Loads/Pressure function region", "");
    AssertThrow(region_numbers.size() <= 1,
                ExcMessage("Entry <Loads/Pressure function region>: one "
                           "region, x1,y1,x2,y2 or xc,yc,radius (got " +
                           std::to_string(region_numbers.size()) + ")."));
    region = Region::plate;
    if (region_numbers.size() == 1)
      {
        const auto &v = region_numbers[0];
        AssertThrow(v.size() == 4 || v.size() == 3,
                    ExcMessage("Entry <Loads/Pressure function region>: <" +
                               region_text +
                               "> must be x1,y1,x2,y2 (a rectangle) or "
                               "xc,yc,radius (a disk)."));
        if (v.size() == 4)
          {
            AssertThrow(v[0] < v[2] && v[1] < v[3],
                        ExcMessage("Entry <Loads/Pressure function region>: "
                                   "the rectangle x1,y1,x2,y2 needs x1 < x2 "
                                   "and y1 < y2."));
            region = Region::rectangle;
            lower  = Point<2>(v[0], v[1]);
            upper  = Point<2>(v[2], v[3]);
          }
        else
          {
            AssertThrow(v[2] > 0,
                        ExcMessage("Entry <Loads/Pressure function region>: "
                                   "the disk's radius must be > 0 (got " +
                                   number(v[2]) + ")."));
            region = Region::disk;
            centre = Point<2>(v[0], v[1]);
            radius = v[2];
          }
      }
    // in [1, 30]: the entry's pattern
    points =
      static_cast<unsigned int>(prm.get_integer("Pressure function points"));
    AssertThrow(!expression.empty() ||
                  (constants.empty() && region == Region::plate),
                ExcMessage("Loads/Function constants and Pressure function "
                           "region need Loads/Pressure function."));
  }

  namespace
  {
    const bool registered = register_load_kind(
      {"pressure function",
       &PressureFunctionSettings::declare_parameters,
       [](ParameterHandler &prm) {
         PressureFunctionSettings settings;
         settings.parse_parameters(prm);
         LoadList loads;
         if (!settings.expression.empty())
           loads.push_back(std::make_shared<PressureFunctionLoad>(settings));
         return loads;
       }});
  } // namespace
} // namespace PlateOnHalfspace
