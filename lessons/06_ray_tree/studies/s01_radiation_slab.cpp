// §1 The radiation model: the transport equation on a slab of constant K_t.
//
// dI/ds = −K_t I + K_a I_e marched along a ray through a slab by Euler and
// midpoint steps (trace/participating_medium.hpp), against the closed form
// I₀e^(−K_t d) + (K_a I_e/K_t)(1 − e^(−K_t d)): the error falls as the steps grow.
#include <cmath>
#include <string>
#include <utility>

#include "illum/trace/participating_medium.hpp"
#include "studies.hpp"
#include "support/lesson_support.hpp"

namespace illum::lesson06 {

void s01_radiation_slab(OutputFolder& out, const Settings& settings) {
  const bool quick = settings.quick;
  const Slab absorbing{.extinction = 0.8, .emission = 0.0, .thickness = 2.5};
  const Slab glowing{.extinction = 0.8, .emission = 0.6, .thickness = 2.5};
  const double incoming = 1.0;
  Table table({"medium", "method", "steps", "marched", "closed_form", "relative_error"});
  for (const auto& [name, slab] : {std::pair{"absorbing", absorbing}, std::pair{"glowing", glowing}})
    for (MarchMethod method : {MarchMethod::euler, MarchMethod::midpoint})
      for (int steps = 1; steps <= (quick ? 64 : 4096); steps *= 4) {
        const double marched = march_through_slab(slab, incoming, steps, method);
        const double exact = slab_closed_form(slab, incoming);
        table.add_row({std::string(name), std::string(to_string(method)), std::int64_t{steps}, marched, exact,
                       std::abs(marched - exact) / exact});
      }
  out.table(
      table, "radiation_slab",
      "A ray through a slab, K_t = 0.8, d = 2.5: marching dI/ds = −K_t I + K_a I_e against the closed "
      "form I₀e^(−K_t d) + (K_a I_e/K_t)(1 − e^(−K_t d)); 'absorbing' has emission and in-scattering off",
      4);
  PlotSpec spec{.title = "Transport along a ray through a slab: marching error",
                .x_label = "steps",
                .y_label = "relative error of I(d)",
                .log_x = true,
                .log_y = true};
  for (const char* medium : {"absorbing", "glowing"})
    for (const char* method : {"euler", "midpoint"})
      spec.curves.push_back({.table = "radiation_slab.csv",
                             .x = "steps",
                             .y = "relative_error",
                             .where = {{"medium", medium}, {"method", method}},
                             .title = std::string(medium) + ", " + method});
  out.plot(spec, "radiation_slab", "Marching the transport equation converges to Beer–Lambert's law");
}

}  // namespace illum::lesson06
