// §6 Progressive refinement: the notes' three-patch example.
//
// The notes' three patches shot six times by choose_shooter and shoot (the
// exercise), printed in the notes' layout with the limit from solve_direct
// (radiosity/three_patch_example.hpp); the grading tests compare the rows
// with the notes' table value by value.
#include <iostream>
#include <string>

#include "illum/radiosity/three_patch_example.hpp"
#include "studies.hpp"

namespace illum::lesson11 {

void s06_three_patch(OutputFolder& out) {
  const std::string table_text = three_patch_table_text();
  std::cout << "Three-patch progressive refinement (lesson 11, section 6; errata: the three-patch example)\n"
            << table_text << '\n';
  out.text("three_patch_table.txt", table_text,
           "The notes' three-patch progressive example: shooter, B and unshot radiosity after each shot, "
           "then the limit");
}

}  // namespace illum::lesson11
