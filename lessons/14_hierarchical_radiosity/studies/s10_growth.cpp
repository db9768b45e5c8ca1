// §10 Links against n².
//
// The runs of §8's ε_F sweep (BF refinement off), whose elements grow as ε_F
// shrinks: their leaves n, their links, and the n² form factors of a uniform
// mesh of n patches; the least-squares slope of log(links) against log(n).
#include <iostream>
#include <vector>

#include "illum/core/log_log_fit.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson14 {

void s10_growth(OutputFolder& out, const KnobStudy& study) {
  Table table({"epsilon_f", "leaves", "links", "n²", "links per leaf", "n² / links"});
  std::vector<double> n, links;
  for (const KnobRun& r : study.runs) {
    if (r.knob != "epsilon_f") continue;
    const double leaves = static_cast<double>(r.leaves), l = static_cast<double>(r.links);
    n.push_back(leaves);
    links.push_back(l);
    table.add_row(cells(r.epsilon_f, static_cast<std::int64_t>(r.leaves), static_cast<std::int64_t>(r.links),
                        leaves * leaves, l / leaves, leaves * leaves / l));
  }
  out.table(table, "growth", "Leaves, links and n² as epsilon_F shrinks (BF refinement off)");
  Table fit({"runs", "leaves from", "leaves to", "exponent of links against leaves"});
  const double slope = log_log_slope(n, links);
  fit.add_row(cells(static_cast<std::int64_t>(n.size()), n.front(), n.back(), slope));
  out.table(fit, "growth_fit", "Least-squares slope of log(links) against log(leaves)");
  out.plot(
      {.title = "Links and n^2 against the leaves",
       .x_label = "leaves n",
       .y_label = "interactions",
       .log_x = true,
       .log_y = true,
       .curves =
           {{.table = "growth.csv", .x = "leaves", .y = "links", .title = "links"},
            {.table = "growth.csv", .x = "leaves", .y = "n²", .title = "n^2 (a uniform mesh of n patches)"}}},
      "growth",
      "Links of hierarchical radiosity and n² of a uniform mesh with as many patches as it has leaves");
  std::cout << "Links grow as n^" << fixed(slope, 2) << " of the leaves\n";
}

}  // namespace illum::lesson14
