#include <deal.II/base/exceptions.h>
#include <deal.II/base/utilities.h>

#include <plate_on_halfspace/scene/input_checks.h>
#include <plate_on_halfspace/scene/parameters.h>

#include <sys/stat.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <limits>
#include <optional>
#include <sstream>
#include <utility>
#include <vector>

namespace PlateOnHalfspace
{
  namespace
  {
    void
    require(const bool condition, const std::string &message)
    {
      AssertThrow(condition, ExcMessage(message));
    }

  } // namespace

  void
  SceneParameters::declare_parameters(ParameterHandler &prm)
  {
    prm.declare_entry("Output directory",
                      "output",
                      Patterns::Anything(),
                      "Directory for summary.json, profiles, VTU and "
                      "convergence.txt (created if missing).");
    Parameters::Plate::declare_parameters(prm);
    Parameters::Joints::declare_parameters(prm);
    Parameters::Foundation::declare_parameters(prm);
    Parameters::FoundationOperator::declare_parameters(prm);
    Parameters::Temperature::declare_parameters(prm);
    Parameters::Loads::declare_parameters(prm);
    Parameters::Discretization::declare_parameters(prm);
    Parameters::Contact::declare_parameters(prm);
    Parameters::Adaptivity::declare_parameters(prm);
    Parameters::Output::declare_parameters(prm);
    Parameters::Verification::declare_parameters(prm);
  }

  namespace
  {
    /**
     * Why @p parameters cannot use the hierarchical half-space operator
     * (the message of the first condition it breaks), or "" if it can:
     * Storage = hierarchical is refused with this message, and Storage =
     * auto stays dense.
     */
    std::string
    hierarchical_storage_obstacle(const SceneParameters &parameters,
                                  const std::string &storage = "hierarchical")
    {
      if (parameters.contact.solver == Parameters::Contact::Solver::direct)
        return "Foundation operator/Storage = " + storage +
               " needs Contact/"
               "Solver = iterative or auto (the direct solver forms the "
               "dense block the compressed storage avoids).";
      if (parameters.discretization.flexibility !=
          Parameters::Discretization::Flexibility::galerkin)
        return "Foundation operator/Storage = " + storage +
               " needs the "
               "symmetric half-space operator, Discretization/Flexibility "
               "= galerkin.";
      if (parameters.foundation.tensionless &&
          parameters.contact.method != Parameters::Contact::Method::active_set)
        return "Foundation operator/Storage = " + storage +
               " needs Contact/"
               "Method = active set (element exclusion rebuilds the "
               "operator).";
      return "";
    }
  } // namespace

  void
  SceneParameters::parse_parameters(ParameterHandler &prm)
  {
    output_directory = prm.get("Output directory");
    require(!output_directory.empty(), "Output directory must not be empty.");
    // Every entry that names a file or directory, before anything uses it:
    // a NUL would end the name early in the system calls
    // (doc/errors-and-limits.md).
    {
      const std::string problem =
        control_character_in_path("Output directory", output_directory);
      require(problem.empty(), problem);
      prm.enter_subsection("Plate");
      const std::string mesh_file = prm.get("Mesh file");
      prm.leave_subsection();
      const std::string mesh_problem =
        control_character_in_path("Plate/Mesh file", mesh_file);
      require(mesh_problem.empty(), mesh_problem);
    }
    plate.parse_parameters(prm);
    joints.parse_parameters(prm);
    foundation.parse_parameters(prm);
    foundation_operator.parse_parameters(prm);
    temperature.parse_parameters(prm);
    loads.parse_parameters(prm);
    discretization.parse_parameters(prm);
    contact.parse_parameters(prm);
    adaptivity.parse_parameters(prm);
    output.parse_parameters(prm);
    verification.parse_parameters(prm);

    if (plate.shape == Parameters::Plate::Shape::slabs)
      joints.check(plate);
    for (const Parameters::Check &check : verification.checks)
      require(check.quantity.rfind("goal.", 0) != 0 ||
                adaptivity.goal.functional,
              "Verification/Checks: <" + check.quantity +
                "> needs Adaptivity/Goal (the quantity whose value and error "
                "each cycle reports).");
    if (discretization.flexibility ==
        Parameters::Discretization::Flexibility::collocation)
      require(plate.shape != Parameters::Plate::Shape::slabs,
              "Discretization/Flexibility = collocation needs one slab: "
              "the nodes facing each other across a joint would collocate "
              "the same settlement twice; use galerkin for Plate/Shape = "
              "slabs.");
    if (discretization.flexibility ==
        Parameters::Discretization::Flexibility::collocation)
      require(plate.shape != Parameters::Plate::Shape::disk,
              "Discretization/Flexibility = collocation needs axis-aligned "
              "rectangular cells (the paper's closed-form integral); use "
              "galerkin for Plate/Shape = disk.");
    if (foundation.model == Parameters::Foundation::Model::layered)
      for (unsigned int i = 0; i < foundation.layers.size(); ++i)
        {
          // The layers against the plate, as the dense liquid's k below:
          // a layer thinner than this is lost to rounding in the
          // condensation of the layers' stiffness at the plate's
          // wavelengths (doc/soil-models.md, "The surface compliance"),
          // and a softer one does not hold the plate in any digit.
          const auto        &layer = foundation.layers[i];
          std::ostringstream which;
          which << "Foundation/Layers: layer " << i + 1 << " ("
                << layer.thickness << " thick, E = " << layer.youngs_modulus
                << ") ";
          std::ostringstream thin;
          thin << which.str() << "is thinner than 1e-9 of the plate's "
               << "thickness (" << plate.thickness
               << "): too thin to matter or to be resolved; leave it out "
                  "or merge it into a neighbouring layer.";
          require(layer.thickness >= 1e-9 * plate.thickness, thin.str());
          std::ostringstream soft;
          soft << which.str() << "is softer than 1e-15 of the plate's "
               << "Young's modulus (" << plate.youngs_modulus
               << "): such a soil does not hold the plate; check the "
                  "units of the moduli.";
          require(layer.youngs_modulus >= 1e-15 * plate.youngs_modulus,
                  soft.str());
          std::ostringstream stiff;
          stiff << which.str() << "is stiffer than 1e15 times the plate's "
                << "Young's modulus (" << plate.youngs_modulus
                << "): for the plate such a soil is rigid in every digit; "
                   "check the units of the moduli.";
          require(layer.youngs_modulus <= 1e15 * plate.youngs_modulus,
                  stiff.str());
        }
    // The mirror of the layers' bound above: the contact pressures of a
    // soil this much stiffer than the plate are rounding (the direct
    // solver names the floor from far below it: contact/direct_solver.cc).
    // (and of the half-space under the layers)
    if (foundation.model == Parameters::Foundation::Model::half_space ||
        (foundation.model == Parameters::Foundation::Model::layered &&
         !foundation.rigid_base))
      {
        std::ostringstream stiff;
        stiff << "Foundation/Young's modulus (" << foundation.youngs_modulus
              << ") is stiffer than 1e15 times Plate/Young's modulus ("
              << plate.youngs_modulus
              << "): for the plate such a soil is rigid in every digit; "
                 "check the units of the moduli.";
        require(foundation.youngs_modulus <= 1e15 * plate.youngs_modulus,
                stiff.str());
      }
    if (foundation.model == Parameters::Foundation::Model::dense_liquid)
      {
        // Below this the soil no longer holds the plate in any digit that
        // the flexibility 1/k and its products can carry (tests/unit/
        // temperature_curling's k -> 0 limit uses k t / E = 8e-12).
        const double smallest = 1e-15 * plate.youngs_modulus / plate.thickness;
        std::ostringstream limit;
        limit << smallest << " for this plate (got "
              << foundation.subgrade_modulus << ")";
        require(foundation.subgrade_modulus >= smallest,
                "Foundation/Modulus of subgrade reaction must be at least "
                "1e-15 E/t = " +
                  limit.str() + ": a softer soil does not hold the plate.");
        // Above the mirror bound the plate's stiffness is lost in the
        // soil's in every digit (k = 1e300 overflowed the conjugate
        // gradients into "non-positive curvature", naming no entry).
        const double largest = 1e15 * plate.youngs_modulus / plate.thickness;
        std::ostringstream upper;
        upper << largest << " for this plate (got "
              << foundation.subgrade_modulus << ")";
        require(foundation.subgrade_modulus <= largest,
                "Foundation/Modulus of subgrade reaction must be at most "
                "1e15 E/t = " +
                  upper.str() +
                  ": a stiffer soil is rigid in every digit the plate's "
                  "stiffness can carry; a smaller k gives the same answer.");
        // The dense liquid is a sparse operator: nothing may densify it,
        // and the paper's element exclusion and collocation belong to the
        // half-space (doc/formulation.md, "Dense-liquid foundation").
        require(foundation_operator.storage ==
                  Parameters::FoundationOperator::Storage::automatic,
                "Foundation operator/Storage applies to the half-space; "
                "with Foundation/Model = dense liquid leave it auto (the "
                "dense liquid is stored sparse).");
        require(contact.solver != Parameters::Contact::Solver::direct,
                "Contact/Solver = direct condenses the plate onto a dense "
                "foundation block; with Foundation/Model = dense liquid use "
                "iterative or auto.");
        require(!foundation.tensionless ||
                  contact.method == Parameters::Contact::Method::active_set,
                "Contact/Method = element exclusion is the paper's method "
                "for the half-space; with Foundation/Model = dense liquid "
                "use active set.");
        require(discretization.flexibility ==
                  Parameters::Discretization::Flexibility::galerkin,
                "Discretization/Flexibility = collocation is the paper's "
                "half-space operator; with Foundation/Model = dense liquid "
                "use galerkin.");
      }
    // The generated meshes' cells, (length / subdivisions) per direction
    // and slab: beyond 1e6 : 1 the geometry is lost in rounding (a slab of
    // 1e-300 stopped inside deal.II); the half-space's cell-pair rules
    // hold to about 300 : 1 and say so when A fails.
    if (plate.shape == Parameters::Plate::Shape::rectangle ||
        plate.shape == Parameters::Plate::Shape::slabs)
      {
        const bool slabs = plate.shape == Parameters::Plate::Shape::slabs;
        const std::vector<double> xs = slabs ?
                                         plate.slab_lengths_x :
                                         std::vector<double>{plate.length_x},
                                  ys = slabs ?
                                         plate.slab_lengths_y :
                                         std::vector<double>{plate.length_y};
        double elongation            = 1;
        for (const double lx : xs)
          for (const double ly : ys)
            {
              const double ratio = (lx / discretization.subdivisions_x) /
                                   (ly / discretization.subdivisions_y);
              elongation = std::max({elongation, ratio, 1. / ratio});
            }
        std::ostringstream value;
        value << elongation;
        require(elongation <= 1e6,
                std::string(slabs ? "Plate/Slab lengths x and y" :
                                    "Plate/Length x and y") +
                  " with Discretization/Subdivisions x and y give cells " +
                  value.str() +
                  " times longer than wide; at most 1e6 is accepted (and "
                  "the half-space's cell-pair quadrature holds to about "
                  "300): choose the subdivisions so that the cells are "
                  "nearer square.");
      }
    // tests/unit/plate_zero_energy_modes: lagrange with selective shear
    // integration has a spurious zero-energy deflection mode that only the
    // foundation restrains. A tensionless foundation lets go where the
    // mode opens a gap, and the answer is then that mode (deflections of
    // 1e9 m under a 100 kN load, exit 0): doc/errors-and-limits.md.
    require(!(foundation.tensionless &&
              discretization.element ==
                Parameters::Discretization::Element::lagrange &&
              discretization.shear_integration ==
                Parameters::Discretization::ShearIntegration::selective),
            "Discretization/Element = lagrange with Shear integration = "
            "selective (what auto gives lagrange) has a spurious zero-energy "
            "deflection mode that only the foundation restrains, and a "
            "tensionless foundation "
            "(Foundation/Contact = tensionless) releases it where the plate "
            "lifts off. Use Element = heterosis (the default, free of "
            "spurious modes), lagrange with Shear integration = full, or "
            "Foundation/Contact = bonded.");
    if (foundation.model == Parameters::Foundation::Model::layered)
      require(discretization.flexibility ==
                Parameters::Discretization::Flexibility::galerkin,
              "Discretization/Flexibility = collocation is the paper's "
              "closed-form operator of the homogeneous half-space; with "
              "Foundation/Model = layered use galerkin.");
    if (foundation_operator.storage ==
        Parameters::FoundationOperator::Storage::hierarchical)
      {
        const std::string obstacle = hierarchical_storage_obstacle(*this);
        require(obstacle.empty(), obstacle);
      }
    if (foundation_operator.storage ==
        Parameters::FoundationOperator::Storage::fft)
      {
        const std::string obstacle =
          hierarchical_storage_obstacle(*this, "fft");
        require(obstacle.empty(), obstacle);
        require(foundation.model == Parameters::Foundation::Model::half_space,
                "Foundation operator/Storage = fft holds the homogeneous "
                "half-space only (Foundation/Model = half-space); a layered "
                "soil or the dense liquid needs Storage = auto, dense or "
                "hierarchical.");
      }
    if (adaptivity.goal.functional)
      {
        // doc/formulation.md, "Goal-oriented refinement": the dual problem
        // is the primal one only for a symmetric operator, and the dual
        // weights are reconstructed on patches of 2 x 2 cells.
        require(discretization.flexibility ==
                  Parameters::Discretization::Flexibility::galerkin,
                "Adaptivity/Goal needs the symmetric half-space operator, "
                "Discretization/Flexibility = galerkin (the error estimate "
                "solves the adjoint problem with the same operator).");
        // The estimate reconstructs the dual solution on patches of 2 x 2
        // cells of a refined mesh: a goal on the coarse mesh refines it
        // once, which the log says (refinement_note).
        if (discretization.initial_refinements == 0)
          {
            discretization.initial_refinements = 1;
            refinement_note =
              "Adaptivity/Goal: the coarse mesh is refined once "
              "(Discretization/Initial refinements = 1, not 0), since the "
              "error estimate reconstructs the dual solution on patches "
              "of 2 x 2 cells of a refined mesh.";
          }
      }
    if (contact.solver == Parameters::Contact::Solver::iterative)
      {
        require(discretization.flexibility ==
                  Parameters::Discretization::Flexibility::galerkin,
                "Contact/Solver = iterative needs the symmetric half-space "
                "operator, Discretization/Flexibility = galerkin.");
        require(!foundation.tensionless ||
                  contact.method == Parameters::Contact::Method::active_set,
                "Contact/Solver = iterative needs Contact/Method = active "
                "set (element exclusion rebuilds the operator).");
      }
  }

  Parameters::FoundationOperator::Storage
  SceneParameters::foundation_storage(
    const unsigned int n_foundation_nodes) const
  {
    using Storage = Parameters::FoundationOperator::Storage;
    if (foundation.model == Parameters::Foundation::Model::dense_liquid)
      return Storage::sparse;
    if (foundation_operator.storage != Storage::automatic)
      return foundation_operator.storage;
    const bool allowed = hierarchical_storage_obstacle(*this).empty();
    if (!allowed || n_foundation_nodes < foundation_operator.hierarchical_from)
      return Storage::dense;
    // doc/performance.md, "Which storage auto picks": the split kernel is
    // the faster compressed operator, on one process and on several, where
    // its preconditioner's iterations do not grow with the processes; it
    // holds the homogeneous half-space only.
    return foundation.model == Parameters::Foundation::Model::half_space ?
             Storage::fft :
             Storage::hierarchical;
  }

  Parameters::Contact::Solver
  SceneParameters::contact_solver(const unsigned int n_foundation_nodes) const
  {
    using Solver = Parameters::Contact::Solver;
    if (contact.solver != Solver::automatic)
      return contact.solver;
    return foundation_storage(n_foundation_nodes) ==
               Parameters::FoundationOperator::Storage::dense ?
             Solver::direct :
             Solver::iterative;
  }

  namespace
  {
    /** The largest parameter file read (the shipped scenes are < 10 KiB). */
    constexpr std::uintmax_t largest_parameter_file = 64u << 20;
    /** How deep includes may nest, and how many one scene may follow. */
    constexpr unsigned int deepest_include = 32;
    constexpr unsigned int most_includes   = 1000;

    std::string
    trimmed(const std::string &text)
    {
      const auto not_space = [](const char c) {
        return !std::isspace(static_cast<unsigned char>(c));
      };
      const auto begin = std::find_if(text.begin(), text.end(), not_space);
      const auto end   = std::find_if(text.rbegin(), text.rend(), not_space);
      return begin < end.base() ? std::string(begin, end.base()) : "";
    }

    /**
     * "" if @p text is a text parameter file, else the reason it is not:
     * a byte-order mark of UTF-16 or UTF-32, the NUL bytes of UTF-16 or
     * UTF-32 text without a mark (in every second or every three of four
     * bytes of its first 4 KiB), or a quarter or more of those bytes
     * control characters other than white space (a binary file). deal.II
     * would read such a file line by line and quote the NULs in its
     * message, cut short on the terminal.
     */
    std::string
    encoding_problem(const std::string &text)
    {
      const auto starts_with = [&](const std::string &mark) {
        return text.compare(0, mark.size(), mark) == 0;
      };
      using namespace std::string_literals;
      if (starts_with("\x00\x00\xFE\xFF"s) || starts_with("\xFF\xFE\x00\x00"s))
        return "UTF-32 encoded";
      if (starts_with("\xFE\xFF"s) || starts_with("\xFF\xFE"s))
        return "UTF-16 encoded";
      const std::size_t sample = std::min<std::size_t>(text.size(), 4096);
      // NULs at each position modulo 4, and all control bytes
      std::array<std::size_t, 4> nuls{};
      std::size_t                controls = 0;
      for (std::size_t i = 0; i < sample; ++i)
        {
          const unsigned char c = text[i];
          nuls[i % 4] += (c == 0);
          controls += ((c < 0x20 && !std::isspace(c)) || c == 0x7F);
        }
      if (sample < 8)
        return "";
      const std::size_t slots = sample / 4; // per position, about
      const auto        most  = [&](const std::size_t n) {
        return 10 * n >= 9 * slots;
      };
      const auto few = [&](const std::size_t n) { return 10 * n <= slots; };
      // ASCII text as UTF-32 (LE or BE): three NULs in every four bytes
      if ((few(nuls[0]) && most(nuls[1]) && most(nuls[2]) && most(nuls[3])) ||
          (most(nuls[0]) && most(nuls[1]) && most(nuls[2]) && few(nuls[3])))
        return "UTF-32 encoded";
      // UTF-16 (LE or BE): NULs in the high bytes of most characters
      const std::size_t even = nuls[0] + nuls[2], odd = nuls[1] + nuls[3];
      if ((5 * odd >= 2 * 2 * slots && 20 * even <= 2 * slots) ||
          (5 * even >= 2 * 2 * slots && 20 * odd <= 2 * slots))
        return "UTF-16 encoded";
      if (4 * controls >= sample)
        return "binary: " + std::to_string(controls) + " of its first " +
               std::to_string(sample) + " bytes are control characters";
      return "";
    }

    /** Throws unless @p text, the contents of @p filename, is a text
     *  parameter file (encoding_problem()). */
    void
    require_text_file(const std::string &text, const std::string &filename)
    {
      const std::string encoding = encoding_problem(text);
      require(encoding.empty(),
              filename + " is not a text parameter file (it looks " + encoding +
                "); save it as UTF-8 or ASCII.");
    }

    /**
     * A ParameterHandler that reads every file, the scene and each file it
     * includes, with checks deal.II does not make (doc/errors-and-limits.md,
     * "Include files, encodings and control characters"). deal.II 9.4 follows
     * "include NAME" by opening NAME as written (relative to the working
     * directory) and calling the virtual parse_input(stream, NAME) on it, so
     * this override sees every file deal.II reads, exactly as it resolves it:
     * - a file that includes itself, directly or through others, would
     *   recurse until the stack overflows: refused, naming the chain
     *   (files are compared by device and inode, so links and other
     *   spellings of a name count as the same file);
     * - includes nested deeper than 32 or more than 1000 in all (a
     *   "diamond" of includes grows exponentially) are refused;
     * - an include that names no regular file (a directory, a FIFO, a
     *   device, which opening could block on or never end) or holds a
     *   control character is refused before deal.II opens it;
     * - a UTF-16, UTF-32 or binary file is refused in one line; a UTF-8
     *   byte-order mark is dropped (it is text).
     */
    class SceneFileReader : public ParameterHandler
    {
    public:
      explicit SceneFileReader(const bool first_is_a_file)
        : first_is_a_file(first_is_a_file)
      {}

      using ParameterHandler::parse_input;

      void
      parse_input(std::istream      &input,
                  const std::string &filename,
                  const std::string &last_line,
                  const bool         skip_undefined) override
      {
        const bool is_include = !open_files.empty();
        if (is_include)
          {
            ++n_includes;
            require(n_includes <= most_includes,
                    "include: the scene follows more than " +
                      std::to_string(most_includes) + " include statements (" +
                      open_files.front().name +
                      " includes files that include the same files again); "
                      "include each file once.");
            require(open_files.size() < deepest_include,
                    "include: the includes nest more than " +
                      std::to_string(deepest_include) +
                      " deep: " + chain(filename) + ".");
          }
        OpenFile file{filename, {}};
        if (is_include || first_is_a_file)
          {
            struct stat status;
            if (::stat(filename.c_str(), &status) == 0)
              file.identity = std::make_pair(status.st_dev, status.st_ino);
          }
        if (file.identity)
          for (const OpenFile &open : open_files)
            require(open.identity != file.identity,
                    "include cycle: " + chain(filename) +
                      " (a file must not include itself, directly or "
                      "through other files).");

        std::string text;
        char        buffer[1 << 16];
        while (text.size() <= largest_parameter_file &&
               input.read(buffer, sizeof(buffer)).gcount() > 0)
          text.append(buffer, input.gcount());
        require(text.size() <= largest_parameter_file,
                filename + " is larger than 64 MiB: not a parameter file.");
        require_text_file(text, filename);
        if (text.compare(0, 3, "\xEF\xBB\xBF") == 0)
          text.erase(0, 3); // the UTF-8 byte-order mark
        check_include_statements(text, filename);

        open_files.push_back(file);
        try
          {
            std::istringstream stream(text);
            ParameterHandler::parse_input(stream,
                                          filename,
                                          last_line,
                                          skip_undefined);
          }
        catch (...)
          {
            open_files.pop_back();
            throw;
          }
        open_files.pop_back();
      }

    private:
      struct OpenFile
      {
        std::string                            name;
        std::optional<std::pair<dev_t, ino_t>> identity;
      };

      /** "a.prm includes b.prm includes NEXT". */
      std::string
      chain(const std::string &next) const
      {
        std::string names;
        for (const OpenFile &open : open_files)
          names += open.name + " includes ";
        return names + next;
      }

      /**
       * Refuses an "include NAME" line of @p text (the file @p filename)
       * whose NAME holds a control character or exists but is no regular
       * file, and a comment ending in a backslash followed by a line that
       * the continuation would hide. The lines are read as deal.II's
       * parse_input() and scan_line() read them: trimmed, joined at a trailing
       * backslash, the comment cut at '#', tabs made spaces.
       */
      void
      check_include_statements(const std::string &text,
                               const std::string &filename) const
      {
        std::istringstream lines(text);
        std::string        line, joined;
        unsigned int       number = 0, first_of_joined = 0;
        bool               continued = false;
        const auto         check     = [&](const std::string &logical_line) {
          std::string statement =
            logical_line.substr(0, logical_line.find('#'));
          std::replace(statement.begin(), statement.end(), '\t', ' ');
          statement = trimmed(statement);
          if (statement.rfind("include ", 0) != 0 &&
              statement.rfind("INCLUDE ", 0) != 0)
            return;
          const std::string name  = trimmed(statement.substr(7));
          const std::string where = filename + ", line " +
                                    std::to_string(first_of_joined) +
                                    ": include " + name;
          const std::string problem = control_character_in_path(where, name);
          require(problem.empty(), problem);
          std::error_code error;
          const auto      status = std::filesystem::status(name, error);
          require(!std::filesystem::exists(status) ||
                    std::filesystem::is_regular_file(status),
                  where +
                    ": not a regular file (a parameter file is expected).");
        };
        // the number of a line whose comment ends in a backslash, which
        // joins the next line to the comment
        unsigned int comment_continued_at = 0;
        while (std::getline(lines, line))
          {
            ++number;
            if (!continued)
              first_of_joined = number;
            line = trimmed(line);
            // A comment ending in a backslash swallows the next line: an
            // entry there would be dropped without a word (a Windows path
            // at the end of a comment, C:\drawings\).
            if (comment_continued_at != 0 && !line.empty() &&
                line.front() != '#')
              require(false,
                      filename + ", line " +
                        std::to_string(comment_continued_at) +
                        ": the comment ends in a backslash, which joins line " +
                        std::to_string(number) +
                        " to the comment (a trailing backslash continues a "
                        "line), so that line would be ignored: remove the "
                        "backslash or end the comment with another "
                        "character.");
            comment_continued_at = 0;
            if (!line.empty() && line.back() == '\\')
              {
                line.pop_back();
                joined += line;
                continued = true;
                if (joined.find('#') != std::string::npos)
                  comment_continued_at = number;
                continue;
              }
            joined += line;
            continued = false;
            check(joined);
            joined.clear();
          }
        if (continued)
          check(joined);
      }

      const bool            first_is_a_file;
      std::vector<OpenFile> open_files;
      unsigned int          n_includes = 0;
    };
  } // namespace

  void
  SceneParameters::read(const std::string &filename)
  {
    AssertThrow(std::filesystem::is_regular_file(filename) &&
                  std::ifstream(filename).good(),
                ExcMessage("Cannot open the parameter file <" + filename +
                           ">."));
    std::error_code      error;
    const std::uintmax_t size = std::filesystem::file_size(filename, error);
    AssertThrow(error || size <= largest_parameter_file,
                ExcMessage(filename +
                           " is larger than 64 MiB: not a parameter file."));
    std::ostringstream contents;
    contents << std::ifstream(filename).rdbuf();
    const std::string text = contents.str();
    // SceneFileReader checks a .prm file's encoding; deal.II reads a JSON
    // or XML file without calling it
    require_text_file(text, filename);
    const std::string structure_problem =
      structured_scene_problem(text, filename);
    AssertThrow(structure_problem.empty(), ExcMessage(structure_problem));
    SceneFileReader prm(true);
    declare_parameters(prm);
    // parse_input() also follows "include other.prm" lines, so tests can
    // derive from the shipped scenes. Its messages name the line, not the
    // section and the allowed values: input_checks.h adds them.
    try
      {
        prm.parse_input(filename);
      }
    catch (const std::exception &error)
      {
        AssertThrow(false,
                    ExcMessage(
                      explain_parameter_file_error(error, text, filename)));
      }
    const std::string number_problem = unrepresentable_number_entry(prm);
    AssertThrow(number_problem.empty(), ExcMessage(number_problem));
    parse_parameters(prm);
  }

  void
  SceneParameters::read_from_string(const std::string &text)
  {
    SceneFileReader prm(false);
    declare_parameters(prm);
    try
      {
        prm.parse_input_from_string(text);
      }
    catch (const std::exception &error)
      {
        // deal.II names a string "input string"
        AssertThrow(false,
                    ExcMessage(explain_parameter_file_error(error,
                                                            text,
                                                            "input string")));
      }
    const std::string number_problem = unrepresentable_number_entry(prm);
    AssertThrow(number_problem.empty(), ExcMessage(number_problem));
    parse_parameters(prm);
  }
} // namespace PlateOnHalfspace
