// A Gmsh mesh in two pieces (two 2 m squares 2 m apart) on a dense liquid,
// whose contact solver is the iterative one: each piece is a body of its
// own with its own rigid-body motions (doc/parameters.md, Plate/Mesh
// file). For bonded and tensionless contact:
//  - the unloaded piece settles under its weight alone, uniformly by
//    gamma t / k (exact on any mesh);
//  - the loaded piece's largest deflection is that of the same square
//    meshed alone.

#include <plate_on_halfspace/plate_on_halfspace_problem.h>

#include <fstream>
#include <sstream>

#include "../tests.h"

#include "../test_tools.h"

using namespace PlateOnHalfspace;

namespace
{
  /** Squares of side 2 with lower left corners @p corners, 4 x 4 cells
   *  each, as a Gmsh 2.2 file @p name. */
  void
  write_squares(const std::string &name, const std::vector<Point<2>> &corners)
  {
    std::vector<Point<2>>                nodes;
    std::vector<std::array<unsigned, 4>> cells;
    const unsigned int                   n = 4;
    for (const Point<2> &corner : corners)
      {
        const unsigned int first = nodes.size() + 1;
        for (unsigned int j = 0; j <= n; ++j)
          for (unsigned int i = 0; i <= n; ++i)
            nodes.push_back(corner + Point<2>(0.5 * i, 0.5 * j));
        for (unsigned int j = 0; j < n; ++j)
          for (unsigned int i = 0; i < n; ++i)
            {
              const unsigned int a = first + j * (n + 1) + i;
              cells.push_back({{a, a + 1, a + n + 2, a + n + 1}});
            }
      }
    std::ofstream out(name);
    out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n"
        << nodes.size() << "\n";
    for (unsigned int k = 0; k < nodes.size(); ++k)
      out << k + 1 << " " << nodes[k][0] << " " << nodes[k][1] << " 0\n";
    out << "$EndNodes\n$Elements\n" << cells.size() << "\n";
    for (unsigned int k = 0; k < cells.size(); ++k)
      out << k + 1 << " 3 2 1 1 " << cells[k][0] << " " << cells[k][1] << " "
          << cells[k][2] << " " << cells[k][3] << "\n";
    out << "$EndElements\n";
  }

  std::string
  scene(const std::string &mesh, const std::string &contact)
  {
    return "set Output directory = results\n"
           "subsection Plate\n set Shape = mesh file\n set Mesh file = " +
           mesh +
           "\n set Thickness = 0.25\n set Young's modulus = 3e7\n"
           " set Unit weight = 24\nend\n"
           "subsection Foundation\n set Model = dense liquid\n"
           " set Modulus of subgrade reaction = 5e4\n set Contact = " +
           contact +
           "\nend\n"
           "subsection Loads\n set Circular patches = 2,0,0.3,700\nend\n"
           "subsection Discretization\n set Symmetry = none\nend\n"
           "subsection Output\n set Verbosity = 0\n set VTU = false\nend\n";
  }
} // namespace

int
main()
{
  initlog();
  write_squares("two.msh", {Point<2>(-3, -1), Point<2>(1, -1)});
  write_squares("one.msh", {Point<2>(1, -1)});
  for (const std::string contact : {"bonded", "tensionless"})
    {
      const auto two = TestTools::run_scene_text(scene("two.msh", contact));
      const auto one = TestTools::run_scene_text(scene("one.msh", contact));
      check(contact + ": w of the unloaded piece at (-2, 0) [m]",
            two->values_at(Point<2>(-2, 0)).w,
            24 * 0.25 / 5e4,
            1e-8);
      check(contact + ": w of the unloaded piece at (-3, 1) [m]",
            two->values_at(Point<2>(-3, 1)).w,
            24 * 0.25 / 5e4,
            1e-8);
      check(contact + ": max w, two pieces against the loaded one alone",
            two->summaries().back().number("max_w"),
            one->summaries().back().number("max_w"),
            1e-8);
    }
}
