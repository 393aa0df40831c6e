// Boost 1.74's JSON parser includes <boost/bind.hpp>, which prints a
// deprecation note at every build unless told to keep the placeholders
// global, as the parser expects.
#define BOOST_BIND_GLOBAL_PLACEHOLDERS

#include <deal.II/base/exceptions.h>
#include <deal.II/base/parameter_handler.h>
#include <deal.II/base/utilities.h>

#include <boost/property_tree/json_parser.hpp>
#include <boost/property_tree/ptree.hpp>
#include <boost/property_tree/xml_parser.hpp>

#include <plate_on_halfspace/base/number_list.h>
#include <plate_on_halfspace/scene/input_checks.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iomanip>
#include <map>
#include <regex>
#include <set>
#include <sstream>

namespace PlateOnHalfspace
{
  namespace
  {
    std::string
    trimmed(const std::string &text)
    {
      const auto begin = text.find_first_not_of(" \t\r");
      if (begin == std::string::npos)
        return "";
      const auto end = text.find_last_not_of(" \t\r");
      return text.substr(begin, end - begin + 1);
    }

    /** The line without its comment, trimmed. */
    std::string
    content_of(const std::string &line)
    {
      return trimmed(line.substr(0, line.find('#')));
    }

    /** Every declared subsection path and its entries. */
    std::map<std::string, std::set<std::string>>
    declared_names()
    {
      ParameterHandler prm;
      SceneParameters::declare_parameters(prm);
      std::ostringstream listing;
      prm.print_parameters(listing, ParameterHandler::ShortPRM);
      std::map<std::string, std::set<std::string>> names;
      std::vector<std::string>                     path;
      std::istringstream                           lines(listing.str());
      for (std::string line; std::getline(lines, line);)
        {
          const std::string content = content_of(line);
          const auto        joined  = [&]() {
            std::string p;
            for (const auto &s : path)
              p += s + "/";
            return p;
          };
          if (content.rfind("subsection ", 0) == 0)
            {
              names[joined()].insert(trimmed(content.substr(11)));
              path.push_back(trimmed(content.substr(11)));
            }
          else if (content == "end" && !path.empty())
            path.pop_back();
          else if (content.rfind("set ", 0) == 0)
            names[joined()].insert(
              trimmed(content.substr(4, content.find('=') - 4)));
        }
      return names;
    }

    unsigned int
    edit_distance(const std::string &a, const std::string &b)
    {
      std::vector<unsigned int> row(b.size() + 1);
      for (unsigned int j = 0; j <= b.size(); ++j)
        row[j] = j;
      for (unsigned int i = 1; i <= a.size(); ++i)
        {
          unsigned int diagonal = row[0];
          row[0]                = i;
          for (unsigned int j = 1; j <= b.size(); ++j)
            {
              const unsigned int above = row[j];
              row[j]                   = std::min(
                {row[j] + 1,
                                   row[j - 1] + 1,
                                   diagonal + (std::tolower(a[i - 1]) == std::tolower(b[j - 1]) ?
                                                 0u :
                                                 1u)});
              diagonal = above;
            }
        }
      return row[b.size()];
    }

    /** " Did you mean <X>?" for the nearest of @p candidates, or "". */
    std::string
    suggestion(const std::string &name, const std::set<std::string> &candidates)
    {
      std::string  best;
      unsigned int best_distance = 4; // more than 3 edits: no suggestion
      for (const std::string &c : candidates)
        {
          const unsigned int d = edit_distance(name, c);
          if (d < best_distance)
            {
              best_distance = d;
              best          = c;
            }
        }
      return best.empty() ? "" : " Did you mean <" + best + ">?";
    }

    std::string
    list_of(const std::set<std::string> &names)
    {
      std::string list;
      for (const std::string &n : names)
        list += (list.empty() ? "" : ", ") + n;
      return list;
    }

    std::string
    section_name(const std::string &path)
    {
      return path.empty() ? "the top level" :
                            "subsection " + path.substr(0, path.size() - 1);
    }

    /**
     * The entries (@p subsections false) or the subsections of the
     * declared section @p path ("Plate/") among @p names.
     */
    std::set<std::string>
    declared_in(const std::map<std::string, std::set<std::string>> &names,
                const std::string                                  &path,
                const bool                                          subsections)
    {
      std::set<std::string> found;
      const auto            section = names.find(path);
      if (section != names.end())
        for (const std::string &n : section->second)
          if ((names.count(path + n + "/") > 0) == subsections)
            found.insert(n);
      return found;
    }

    /** The refusal of the undeclared entry @p name in section @p path. */
    std::string
    no_such_entry(const std::map<std::string, std::set<std::string>> &names,
                  const std::string                                  &path,
                  const std::string                                  &name,
                  const std::string                                  &place)
    {
      const std::set<std::string> entries = declared_in(names, path, false);
      return path + name + ": there is no such entry in " + section_name(path) +
             "." + suggestion(name, entries) +
             " Its entries: " + list_of(entries) + "." + place;
    }

    /** The refusal of the undeclared subsection @p name in @p path. */
    std::string
    no_such_subsection(
      const std::map<std::string, std::set<std::string>> &names,
      const std::string                                  &path,
      const std::string                                  &name,
      const std::string                                  &place)
    {
      const std::set<std::string> sections = declared_in(names, path, true);
      return "subsection <" + name + "> does not exist in " +
             section_name(path) + "." + suggestion(name, sections) +
             " The subsections: " + list_of(sections) + "." + place;
    }

    /**
     * A name as deal.II writes it in JSON and XML, its characters other
     * than letters and digits as _XX (hexadecimal), in plain text; the
     * declared names hold no '_'.
     */
    std::string
    demangled(const std::string &name)
    {
      std::string plain;
      for (std::size_t i = 0; i < name.size(); ++i)
        if (name[i] == '_' && i + 2 < name.size() &&
            std::isxdigit(static_cast<unsigned char>(name[i + 1])) &&
            std::isxdigit(static_cast<unsigned char>(name[i + 2])))
          {
            plain +=
              static_cast<char>(std::stoi(name.substr(i + 1, 2), nullptr, 16));
            i += 2;
          }
        else
          plain += name[i];
      return plain;
    }

    /** Every declared entry's path ("Plate/Thickness") and pattern. */
    std::map<std::string, std::string>
    declared_patterns()
    {
      ParameterHandler prm;
      SceneParameters::declare_parameters(prm);
      std::stringstream listing;
      prm.print_parameters(listing, ParameterHandler::JSON);
      boost::property_tree::ptree tree;
      boost::property_tree::read_json(listing, tree);
      std::map<std::string, std::string> patterns;
      std::function<void(const boost::property_tree::ptree &,
                         const std::string &)>
        collect = [&](const boost::property_tree::ptree &node,
                      const std::string                 &path) {
          for (const auto &[key, child] : node)
            {
              const std::string name = path + demangled(key);
              if (child.get_child_optional("value"))
                patterns[name] =
                  child.get<std::string>("pattern_description", "");
              else
                collect(child, name + "/");
            }
        };
      collect(tree, "");
      return patterns;
    }

    /**
     * describe_pattern() of the declared entry @p path ("Plate/Thickness")
     * with the pattern @p description. deal.II's Patterns::Double has no
     * exclusive bound: an entry whose allowed values are > 0
     * (doc/parameters.md) is declared as Double(0), its 0 refused after
     * parsing ("Plate/Thickness must be > 0 (got 0)."); its message for a
     * value outside the pattern names the open bound as well
     * (Parameters::entries_excluding_lower_bound()).
     */
    std::string
    describe_entry_pattern(const std::string &path,
                           const std::string &description)
    {
      std::string                     words = describe_pattern(description);
      const std::vector<std::string> &open =
        Parameters::entries_excluding_lower_bound();
      if (std::find(open.begin(), open.end(), path) == open.end())
        return words;
      // "a number >= 0" -> "a number > 0", "in [0, 1]" -> "in (0, 1]"
      for (const auto &[closed, opened] :
           {std::pair<std::string, std::string>{" >= ", " > "},
            {" in [", " in ("}})
        if (const auto at = words.find(closed); at != std::string::npos)
          return words.replace(at, closed.size(), opened);
      return words;
    }
  } // namespace

  std::string
  subsection_path_at_line(const std::string &text,
                          const unsigned int line_number)
  {
    std::vector<std::string> path;
    std::istringstream       lines(text);
    std::string              line;
    for (unsigned int n = 1; n < line_number && std::getline(lines, line); ++n)
      {
        const std::string content = content_of(line);
        if (content.rfind("subsection ", 0) == 0)
          path.push_back(trimmed(content.substr(11)));
        else if (content == "end" && !path.empty())
          path.pop_back();
      }
    std::string joined;
    for (const std::string &s : path)
      joined += s + "/";
    return joined;
  }

  std::string
  describe_pattern(const std::string &description)
  {
    std::smatch match;
    const auto  bound = [](const std::string &b) {
      return (b == "MAX_DOUBLE" || b == "2147483647")   ? std::string("inf") :
              (b == "-MAX_DOUBLE" || b == "-2147483648") ? std::string("-inf") :
                                                           b;
    };
    const auto range = [&](const std::string &kind,
                           const std::string &low,
                           const std::string &high) {
      const std::string l = bound(low), h = bound(high);
      if (l == "-inf" && h == "inf")
        return "a finite " + kind;
      if (h == "inf")
        return "a " + kind + " >= " + l;
      return "a " + kind + " in [" + l + ", " + h + "]";
    };
    if (std::regex_search(description,
                          match,
                          std::regex("Double (\\S+)\\.\\.\\.(\\S+)")))
      return range("number", match[1], match[2]);
    if (std::regex_search(description,
                          match,
                          std::regex("Integer range (\\S+)\\.\\.\\.(\\S+)")))
      return range("whole number", match[1], match[2]);
    if (std::regex_search(description,
                          match,
                          std::regex("Selection ([^\\]]*)\\]")))
      {
        std::string options = trimmed(match[1]);
        std::string words;
        for (const std::string &o : Utilities::split_string_list(options, '|'))
          words += (words.empty() ? "" : " | ") + o;
        return "one of: " + words;
      }
    if (description.find("Bool") != std::string::npos)
      return "true or false";
    return description;
  }

  std::string
  one_line_message(const std::exception &error)
  {
    std::string info;
    if (const auto *deal_error = dynamic_cast<const ExceptionBase *>(&error))
      {
        std::ostringstream s;
        deal_error->print_info(s);
        info = s.str();
      }
    else
      info = error.what();
    std::string flat;
    for (const char c : info)
      if (std::isspace(static_cast<unsigned char>(c)))
        {
          if (!flat.empty() && flat.back() != ' ')
            flat += ' ';
        }
      else
        flat += c;
    return trimmed(flat);
  }

  namespace
  {
    /**
     * The length of the valid UTF-8 sequence at @p i of @p text (1 to 4),
     * or 0 if the bytes there are not one (overlong forms, surrogates and
     * code points above U+10FFFF included).
     */
    unsigned int
    utf8_sequence_length(const std::string &text, const std::size_t i)
    {
      const auto byte = [&](const std::size_t k) {
        return static_cast<unsigned char>(text[k]);
      };
      const unsigned char first = byte(i);
      if (first < 0x80)
        return 1;
      unsigned int length = 0;
      unsigned int lowest = 0;
      if (first >= 0xC2 && first <= 0xDF)
        length = 2, lowest = 0x80;
      else if (first >= 0xE0 && first <= 0xEF)
        length = 3, lowest = 0x800;
      else if (first >= 0xF0 && first <= 0xF4)
        length = 4, lowest = 0x10000;
      else
        return 0;
      if (i + length > text.size())
        return 0;
      unsigned int code = first & (0x7F >> length);
      for (unsigned int k = 1; k < length; ++k)
        {
          if ((byte(i + k) & 0xC0) != 0x80)
            return 0;
          code = (code << 6) | (byte(i + k) & 0x3F);
        }
      if (code < lowest || code > 0x10FFFF ||
          (code >= 0xD800 && code <= 0xDFFF))
        return 0;
      return length;
    }

    /** The code point of the valid sequence of @p length bytes at @p i. */
    unsigned int
    code_point(const std::string &text,
               const std::size_t  i,
               const unsigned int length)
    {
      unsigned int code = static_cast<unsigned char>(text[i]);
      if (length == 1)
        return code;
      code &= (0x7F >> length);
      for (unsigned int k = 1; k < length; ++k)
        code = (code << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
      return code;
    }

    bool
    is_control(const unsigned int code)
    {
      return code < 0x20 || code == 0x7F || (code >= 0x80 && code <= 0x9F);
    }
  } // namespace

  std::string
  printable(const std::string &text)
  {
    std::string        result;
    std::ostringstream escaped;
    escaped << std::hex << std::setfill('0');
    for (std::size_t i = 0; i < text.size();)
      {
        const unsigned int length = utf8_sequence_length(text, i);
        if (length == 0)
          {
            escaped.str("");
            escaped << "\\x" << std::setw(2)
                    << static_cast<unsigned int>(
                         static_cast<unsigned char>(text[i]));
            result += escaped.str();
            ++i;
            continue;
          }
        const unsigned int code = code_point(text, i, length);
        if (is_control(code))
          {
            escaped.str("");
            escaped << (code < 0x80 ? "\\x" : "\\u")
                    << std::setw(code < 0x80 ? 2 : 4) << code;
            result += escaped.str();
          }
        else
          result += text.substr(i, length);
        i += length;
      }
    return result;
  }

  std::string
  control_character_in_path(const std::string &entry, const std::string &value)
  {
    for (std::size_t i = 0; i < value.size();)
      {
        const unsigned int length = utf8_sequence_length(value, i);
        // a byte outside UTF-8 is a legal (Latin-1, say) file name byte
        const unsigned int code =
          length == 0 ? 0x100 : code_point(value, i, length);
        if (is_control(code))
          {
            std::ostringstream message;
            message << entry << ": the value contains a control character ("
                    << (code < 0x80 ? "0x" : "U+") << std::hex << std::uppercase
                    << std::setfill('0') << std::setw(code < 0x80 ? 2 : 4)
                    << code << std::dec << " at position " << i + 1
                    << "); file and directory names must not contain "
                       "control characters: retype the name.";
            return message.str();
          }
        i += std::max(length, 1u);
      }
    return "";
  }

  std::string
  explain_parameter_file_error(const std::exception &error,
                               const std::string    &text,
                               const std::string    &file_name)
  {
    const std::string flat = one_line_message(error);

    std::smatch where;
    if (!std::regex_search(flat,
                           where,
                           std::regex("^Line <(\\d+)> of file <([^>]*?)>?:")))
      return flat;
    const unsigned int line = std::stoul(where[1]);
    const std::string  file = where[2];
    std::string        source_text;
    if (file == file_name)
      source_text = text;
    else
      {
        std::ifstream      in(file);
        std::ostringstream s;
        s << in.rdbuf();
        source_text = s.str();
      }
    const std::string path  = subsection_path_at_line(source_text, line);
    const std::string place = " (" + file + ", line " + std::to_string(line) +
                              "; plate-on-halfspace --print-parameters lists "
                              "every entry)";
    const auto names = declared_names();

    std::smatch m;
    if (std::regex_search(
          flat,
          m,
          std::regex("The entry value (.*) for the entry named (.*) does not "
                     "match the given pattern: (.*)$")))
      return path + std::string(m[2]) + ": the value <" + std::string(m[1]) +
             "> is not allowed; it must be " +
             describe_entry_pattern(path + std::string(m[2]), m[3]) + "." +
             place;
    if (std::regex_search(flat,
                          m,
                          std::regex("No entry with name <(.*)> was declared")))
      {
        // "set  = 5": nothing between "set" and "=" (deal.II looks up the
        // empty name)
        if (trimmed(m[1]).empty())
          return (path.empty() ? std::string("") : section_name(path) + ": ") +
                 "the line names no entry (nothing stands between set and "
                 "=); write set NAME = VALUE with NAME one of: " +
                 list_of(declared_in(names, path, false)) + "." + place;
        return no_such_entry(names, path, m[1], place);
      }
    if (std::regex_search(
          flat, m, std::regex("no such subsection to be entered: (.*)$")))
      {
        // deal.II reports the mangled path; the last part is the name
        const std::string path_name = m[1];
        return no_such_subsection(names,
                                  path,
                                  demangled(
                                    path_name.substr(path_name.rfind('.') + 1)),
                                  place);
      }
    const std::string rest = trimmed(flat.substr(where[0].length()));
    return (path.empty() ? std::string("") : section_name(path) + ": ") +
           "cannot read the line: " + rest + place;
  }

  std::string
  unrepresentable_number_entry(const ParameterHandler &prm)
  {
    // The declared Double entries, each read from @p prm by its path (a
    // listing of @p prm itself would carry the user's bytes through a
    // JSON parser that refuses invalid UTF-8).
    for (const auto &[path, pattern] : declared_patterns())
      {
        if (pattern.rfind("[Double", 0) != 0)
          continue;
        std::vector<std::string> sections =
          Utilities::split_string_list(path, '/');
        const std::string entry = sections.back();
        sections.pop_back();
        // deal.II's pattern matches a decimal number beyond the range of
        // double, but cannot convert it
        const std::string    text    = trimmed(prm.get(sections, entry));
        double               number  = 0;
        const DecimalReading reading = read_decimal_number(text, number);
        if (reading != DecimalReading::underflow &&
            reading != DecimalReading::overflow)
          continue;
        return path + ": the value <" + text +
               "> cannot be computed with (numbers must be 0 or of "
               "magnitude 1e-307 to 1e308); the entry must be " +
               describe_entry_pattern(path, pattern) +
               ". Check the units of the value.";
      }
    return "";
  }

  std::string
  plate_width_problem(const double       width,
                      const double       thickness,
                      const std::string &plate,
                      const std::string &lengths)
  {
    if (width >= 0.01 * thickness)
      return "";
    std::ostringstream message;
    message << std::setprecision(12) << plate << " is " << width << " wide but "
            << thickness
            << " thick (Plate/Thickness); it must be at least 1/100 as "
               "wide as thick (a rigid block is a plate about as thick as "
               "wide). Check the units of "
            << lengths << ".";
    return message.str();
  }

  std::string
  structured_scene_problem(const std::string &text,
                           const std::string &file_name)
  {
    std::string extension =
      std::filesystem::path(file_name).extension().string();
    std::transform(extension.begin(),
                   extension.end(),
                   extension.begin(),
                   [](unsigned char c) { return std::tolower(c); });
    // deal.II's parse_input() chooses the reader by the file's ending
    if (extension != ".json" && extension != ".xml")
      return extension == ".prm" ?
               "" :
               file_name + ": a scene file's name ends in .prm, .json or " +
                 ".xml (deal.II chooses the reader by it); this one " +
                 (extension.empty() ? std::string("has no ending") :
                                      "ends in " + extension) +
                 ". Rename it.";
    const bool json = extension == ".json";
    // Boost reads a lone value ("hello", 5) as an empty scene
    const std::size_t first =
      text.find_first_not_of(" \t\r\n",
                             text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0);
    if (json && (first == std::string::npos || text[first] != '{'))
      return file_name +
             " does not hold a JSON object: a JSON scene is one object "
             "{...} of sections and entries, e.g. {\"Plate\": "
             "{\"Thickness\": \"0.2\"}}.";
    // Boost's parsers recurse once per level: a file nested 10^5 deep
    // overflows the stack. A scene nests three levels; refuse beyond 64
    // (brackets and elements outside strings, comments and the like
    // counted roughly: enough to bound the recursion).
    {
      int  depth = 0, deepest = 0;
      bool in_string = false;
      for (std::size_t i = 0; i < text.size(); ++i)
        {
          const char c = text[i];
          if (json)
            {
              if (in_string)
                {
                  if (c == '\\')
                    ++i;
                  else if (c == '"')
                    in_string = false;
                }
              else if (c == '"')
                in_string = true;
              else if (c == '{' || c == '[')
                ++depth;
              else if (c == '}' || c == ']')
                --depth;
            }
          else if (c == '<' && i + 1 < text.size())
            depth += text[i + 1] == '/' ? -1 :
                     std::isalpha(static_cast<unsigned char>(text[i + 1])) ? 1 :
                                                                             0;
          else if (c == '/' && i + 1 < text.size() && text[i + 1] == '>')
            --depth;
          deepest = std::max(deepest, depth);
        }
      if (deepest > 64)
        return file_name + " nests its " + (json ? "objects" : "elements") +
               " " + std::to_string(deepest) +
               " deep; a scene's sections nest a few levels (at most 64 are "
               "read).";
    }
    boost::property_tree::ptree tree;
    try
      {
        std::istringstream file(text);
        if (json)
          boost::property_tree::read_json(file, tree);
        else
          boost::property_tree::read_xml(file, tree);
      }
    catch (const boost::property_tree::file_parser_error &error)
      {
        return file_name + " is not a valid " + (json ? "JSON" : "XML") +
               " scene: line " + std::to_string(error.line()) + ": " +
               error.message() + ".";
      }
    // deal.II reads neither XML comments nor attributes (it takes them
    // for entries)
    const std::function<bool(const boost::property_tree::ptree &)>
      has_comment_or_attribute = [&](const boost::property_tree::ptree &node) {
        for (const auto &[key, child] : node)
          if (key == "<xmlattr>" || key == "<xmlcomment>" ||
              has_comment_or_attribute(child))
            return true;
        return false;
      };
    if (!json && has_comment_or_attribute(tree))
      return file_name +
             ": an XML scene takes no comments (<!-- -->) and no "
             "attributes (<ParameterHandler version=\"1\">): deal.II "
             "would read them as entries; remove them.";
    if (!json)
      {
        const auto root = tree.get_child_optional("ParameterHandler");
        if (tree.size() != 1 || !root)
          return file_name +
                 ": an XML scene has the root element <ParameterHandler>, "
                 "each subsection and entry an element inside it (names "
                 "written as deal.II does, e.g. Young_27s_20modulus).";
        tree = *root;
      }
    const auto        patterns = declared_patterns();
    const auto        names    = declared_names();
    const std::string place    = " (" + file_name +
                              "; plate-on-halfspace --print-parameters "
                              "lists every entry)";
    std::function<std::string(const boost::property_tree::ptree &,
                              const std::string &)>
      first_in = [&](const boost::property_tree::ptree &node,
                     const std::string                 &path) -> std::string {
      for (const auto &[key, child] : node)
        {
          // a name that holds '/' (mangled as _2f) names no entry here
          const std::string name =
            demangled(key).find('/') == std::string::npos ? demangled(key) :
                                                            key;
          if (name.empty())
            return file_name + ": " + section_name(path) +
                   " holds a list ([...]) or an entry named \"\"; a scene "
                   "gives each entry by its name." +
                   place;
          const auto pattern = patterns.find(path + name);
          if (pattern != patterns.end())
            {
              // as deal.II reads it: untrimmed
              const auto value = child.get_child_optional("value");
              if (!value && !child.empty())
                return path + name + ": the entry has no value (give it as \"" +
                       name + "\": \"...\" or with a \"value\" field)." + place;
              const std::string text = value ? value->data() : child.data();
              // deal.II matches " 0.2 " as a Double but cannot convert it
              const bool padded =
                !text.empty() &&
                (std::isspace(static_cast<unsigned char>(text.front())) ||
                 std::isspace(static_cast<unsigned char>(text.back())));
              if (padded ||
                  !Patterns::pattern_factory(pattern->second)->match(text))
                return path + name + ": the value <" + text +
                       "> is not allowed; it must be " +
                       describe_entry_pattern(path + name, pattern->second) +
                       (padded ? " (without spaces around it)" : "") + "." +
                       place;
              continue;
            }
          if (names.count(path + name + "/") > 0)
            {
              if (child.empty())
                return path + name +
                       ": a subsection, not an entry; give its entries "
                       "inside it, or leave it out." +
                       place;
              const std::string problem = first_in(child, path + name + "/");
              if (!problem.empty())
                return problem;
              continue;
            }
          if (!child.empty() && !child.get_child_optional("value"))
            return no_such_subsection(names, path, name, place);
          return no_such_entry(names, path, name, place);
        }
      return "";
    };
    return first_in(tree, "");
  }

  std::vector<std::string>
  scene_warnings(const SceneParameters &parameters)
  {
    using D = Parameters::Discretization;
    std::vector<std::string> warnings;
    const D                 &d = parameters.discretization;
    const auto              &p = parameters.plate;

    // The largest initial cell size h; unknown before a mesh file is read.
    double       h          = 0;
    const double refinement = std::pow(0.5, d.initial_refinements);
    if (p.shape == Parameters::Plate::Shape::rectangle)
      h =
        std::max(p.length_x / d.subdivisions_x, p.length_y / d.subdivisions_y) *
        refinement;
    else if (p.shape == Parameters::Plate::Shape::disk)
      h = 0.8 * p.radius * refinement; // hyper_ball_balanced's largest cells
    else if (p.shape == Parameters::Plate::Shape::slabs)
      // Subdivisions x/y are per slab (plate/slab_grid.h)
      h = std::max(*std::max_element(p.slab_lengths_x.begin(),
                                     p.slab_lengths_x.end()) /
                     d.subdivisions_x,
                   *std::max_element(p.slab_lengths_y.begin(),
                                     p.slab_lengths_y.end()) /
                     d.subdivisions_y) *
          refinement;

    // tests/unit/thin_plate_limit: these choices lose the thin-plate limit
    // (shear locking) once cells are much larger than the thickness; the
    // error grows like (h/t)^2 and is below about 1% while h <= 10 t on a
    // mesh of 4 or more cells per span.
    const bool locks = d.element == D::Element::serendipity ||
                       (d.shear_integration == D::ShearIntegration::full &&
                        d.element != D::Element::lagrange);
    const double slenderness_limit = 10.;
    if (locks && h > slenderness_limit * p.thickness)
      {
        std::ostringstream w;
        w << "Discretization/Element = "
          << (d.element == D::Element::serendipity ? "serendipity" :
                                                     "heterosis")
          << " with Shear integration = "
          << (d.shear_integration == D::ShearIntegration::reduced ?
                "reduced" :
              d.shear_integration == D::ShearIntegration::selective ?
                "selective" :
                "full")
          << " locks in shear when the cells are much larger than the plate "
             "thickness: here about "
          << std::setprecision(3) << h / p.thickness
          << " thicknesses per cell (the deflection may be too small when "
             "this exceeds "
          << slenderness_limit
          << "). Use Element = heterosis with Shear integration = selective "
             "or auto (the default; free of locking and of spurious modes), "
             "or refine the mesh.";
        warnings.push_back(w.str());
      }
    if (d.element == D::Element::lagrange &&
        d.shear_integration == D::ShearIntegration::selective)
      warnings.push_back(
        "Discretization/Element = lagrange with Shear integration = "
        "selective has a spurious zero-energy deflection mode that only the "
        "bonded foundation restrains (tests/unit/plate_zero_energy_modes); "
        "prefer Element = heterosis with Shear integration = selective.");

    // A load patch or tyre partly off the plate is warned about by the
    // driver, on the mesh (plate/load_checks.h): only the mesh knows the
    // outline of every Plate/Shape.
    return warnings;
  }
} // namespace PlateOnHalfspace
