/**
 * Messages for a person: deal.II's ParameterHandler reports a bad line by
 * its number and the bare entry name; the user needs the section/entry and
 * the allowed values (doc/parameters.md, "Commands"). Also the warnings for
 * scenes that run but whose answer is known to be poor (shear locking,
 * spurious modes: tests/unit/thin_plate_limit, plate_zero_energy_modes).
 */
#ifndef plate_on_halfspace_scene_input_checks_h
#define plate_on_halfspace_scene_input_checks_h

#include <plate_on_halfspace/scene/parameters.h>

#include <exception>
#include <string>
#include <vector>

namespace PlateOnHalfspace
{
  /**
   * The subsection path ("Plate/", "" at the top level) in force at line
   * @p line_number (1-based) of the parameter text @p text, following its
   * "subsection NAME" and "end" lines.
   */
  std::string
  subsection_path_at_line(const std::string &text,
                          const unsigned int line_number);

  /**
   * A deal.II pattern description ("[Double 0...MAX_DOUBLE (inclusive)]")
   * in words ("a number >= 0").
   */
  std::string
  describe_pattern(const std::string &pattern_description);

  /**
   * The message of @p error on one line with single spaces: a deal.II
   * exception's additional information (its ExcMessage text), otherwise
   * what().
   */
  std::string
  one_line_message(const std::exception &error);

  /**
   * @p text as it may be printed to a terminal: every control character
   * (C0, DEL) and every byte that is not part of valid UTF-8 written as
   * \xNN, every C1 control (U+0080 ... U+009F) as \uNNNN. A value from
   * the scene or a file name quoted in a message can then never send an
   * escape sequence to the terminal (doc/errors-and-limits.md, "How a
   * refusal looks"). main.cc prints every Error and Warning through it.
   */
  std::string
  printable(const std::string &text);

  /**
   * "" if the value @p value of the path entry @p entry ("Output
   * directory", "Plate/Mesh file") holds no control character, otherwise
   * the message refusing it. The system calls end a name at a NUL, so a
   * NUL would make the program act on another path than the one it
   * checks (doc/errors-and-limits.md).
   */
  std::string
  control_character_in_path(const std::string &entry, const std::string &value);

  /**
   * The message for an error that ParameterHandler::parse_input() threw
   * while reading @p text (the contents of the file @p file_name; files
   * named in the error that are not @p file_name, i.e. included ones, are
   * read from disk): "Section/Entry: ..." with the allowed values, the
   * nearest declared name for a misspelt one, and the file and line.
   */
  std::string
  explain_parameter_file_error(const std::exception &error,
                               const std::string    &text,
                               const std::string    &file_name);

  /**
   * "" if every entry of the parsed @p prm whose value is a single number
   * can be held as a double, otherwise the message naming the first that
   * cannot ("Foundation/Young's modulus: ..."). deal.II accepts a subnormal
   * or underflowing value (2e-310, 1e-400) as matching a Double pattern
   * but then cannot convert it, and its message names neither the section
   * nor the range (doc/errors-and-limits.md, "Numbers").
   */
  std::string
  unrepresentable_number_entry(const dealii::ParameterHandler &prm);

  /**
   * "" if a plate @p width wide (its narrowest extent: a side, a slab, a
   * disk's diameter, a mesh's bounding box) and @p thickness thick is at
   * least 1/100 as wide as thick, otherwise the refusal: @p plate names
   * the entry and the plate ("Plate/Radius: the plate"), @p lengths what
   * the user should check ("the lengths"). A plate far thicker than wide
   * is a units slip, and its thickness swamps the cells' coordinates in
   * rounding; a rigid block is a plate about as thick as wide.
   */
  std::string
  plate_width_problem(const double       width,
                      const double       thickness,
                      const std::string &plate,
                      const std::string &lengths);

  /**
   * "" if the JSON or XML scene @p file_name, holding @p text (deal.II
   * reads both besides .prm, by the name's extension), is well formed and every
   * entry in it is declared and allowed, otherwise the message for the first
   * problem, in the .prm messages' words ("Plate/Thickness: the value <-1> is
   * not allowed; it must be a number >= 0."). deal.II's own messages for such
   * files name neither the entry nor the section. A name ending neither in
   * .prm, .json nor .xml gets the message that asks to rename the file.
   */
  std::string
  structured_scene_problem(const std::string &text,
                           const std::string &file_name);

  /**
   * Warnings for a valid scene whose element choice is known to give a
   * poor answer for it: shear locking (cells much larger than the
   * thickness, tests/unit/thin_plate_limit) and the communicable spurious
   * mode of lagrange/selective (tests/unit/plate_zero_energy_modes). Each
   * names the entries and what to choose instead.
   */
  std::vector<std::string>
  scene_warnings(const SceneParameters &parameters);
} // namespace PlateOnHalfspace

#endif
