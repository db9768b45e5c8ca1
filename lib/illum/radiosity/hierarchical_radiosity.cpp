#include "illum/radiosity/hierarchical_radiosity.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <vector>

#include "illum/core/error.hpp"
#include "illum/radiosity/form_factor_analytic.hpp"

namespace illum {
namespace {

void check(const RefineSettings& s) {
  require(s.epsilon_f > 0 && s.epsilon_bf > 0,
          "hierarchical radiosity: epsilon_f and epsilon_bf must be > 0");
  require(s.min_area > 0 && std::isfinite(s.min_area),
          "hierarchical radiosity: min_area must be > 0 and finite");
  require(s.sample_points >= 1 && s.sample_points <= 8,
          "hierarchical radiosity: sample_points must be 1 … 8");
}

// Push-pull below element e, which receives `down` from its ancestors; returns its B.
Color push_pull_below(ElementHierarchy& h, int e, const Color& down) {
  HierarchyElement& element = h[e];
  if (element.first_child < 0) return element.radiosity = element.patch.emission + element.gathered + down;
  const Color pushed = down + element.gathered;
  const int first = element.first_child;
  Color sum(0.0);
  double area = 0;
  for (int c = first; c < first + 4; ++c) {
    sum += h[c].patch.area * push_pull_below(h, c, pushed);
    area += h[c].patch.area;
  }
  return h[e].radiosity = sum / area;
}

// The larger of the two is split (the source when A_s > A_r), if its area is above min_area.
LinkAction split_larger(const Patch& receiver, const Patch& source, const RefineSettings& settings) {
  if (source.area > receiver.area)
    return source.area > settings.min_area ? LinkAction::split_source : LinkAction::link;
  return receiver.area > settings.min_area ? LinkAction::split_receiver : LinkAction::link;
}

// What refine and refine_links do with the oracle's answer for `link`.
void split_or_link(ElementHierarchy& h, const Link& link, LinkAction action, const RefineSettings& settings,
                   const SegmentVisible& visible) {
  if (action == LinkAction::link) h.links.push_back(link);
  if (action == LinkAction::split_receiver) {
    const int first = subdivide(h, link.receiver);
    for (int c = first; c < first + 4; ++c) refine(h, c, link.source, settings, visible);
  }
  if (action == LinkAction::split_source) {
    const int first = subdivide(h, link.source);
    for (int c = first; c < first + 4; ++c) refine(h, link.receiver, c, settings, visible);
  }
}

}  // namespace

double form_factor_estimate(const Patch& receiver, const Patch& source) {
  const double r2 = length_squared(source.centroid - receiver.centroid);
  return source.area / (std::numbers::pi * r2 + source.area);
}

double link_form_factor(const Patch& receiver, const Patch& source, int points_per_side,
                        const SegmentVisible& visible) {
  require(points_per_side >= 1 && points_per_side <= 8, "link_form_factor: points_per_side must be 1 … 8");
  const std::vector<Point3> from = sample_points(receiver, points_per_side);
  const std::vector<Point3> to = sample_points(source, points_per_side);
  double sum = 0;
  for (const Point3& x : from) {
    const double f = point_polygon_form_factor(x, receiver.normal, source);  // lesson 09, exact unoccluded
    if (!(f > 0)) continue;
    std::size_t clear = 0;
    for (const Point3& y : to) clear += visible(x, y) ? 1 : 0;
    sum += f * static_cast<double>(clear) / static_cast<double>(to.size());
  }
  return sum / static_cast<double>(from.size());
}

LinkAction form_factor_oracle(const Patch& receiver, const Patch& source, const RefineSettings& settings) {
  check(settings);
  const double f = std::max(form_factor_estimate(receiver, source), form_factor_estimate(source, receiver));
  return f > settings.epsilon_f ? split_larger(receiver, source, settings) : LinkAction::link;
}

LinkAction brightness_oracle(const Patch& receiver, const Patch& source, double form_factor,
                             const Color& source_radiosity, const RefineSettings& settings) {
  check(settings);
  if (!(form_factor > 0)) return LinkAction::drop;
  const double brought = max_channel(receiver.reflectance * source_radiosity) * form_factor;
  return brought > settings.epsilon_bf ? split_larger(receiver, source, settings) : LinkAction::link;
}

void refine(ElementHierarchy& h, int receiver, int source, const RefineSettings& settings,
            const SegmentVisible& visible) {
  const auto n = static_cast<int>(h.elements.size());
  require(receiver >= 0 && receiver < n && source >= 0 && source < n && receiver != source,
          "refine: the receiver and the source must be two elements of the hierarchy");
  if (faces_away(h[receiver].patch, h[source].patch)) return;
  LinkAction action = form_factor_oracle(h[receiver].patch, h[source].patch, settings);
  double f = 0;
  if (action == LinkAction::link) {
    f = link_form_factor(h[receiver].patch, h[source].patch, settings.sample_points, visible);
    action = brightness_oracle(h[receiver].patch, h[source].patch, f, h[source].radiosity, settings);
  }
  split_or_link(h, {receiver, source, f}, action, settings, visible);
}

void gather(ElementHierarchy& h) {
  for (HierarchyElement& e : h.elements) e.gathered = Color(0.0);
  for (const Link& l : h.links) {
    HierarchyElement& r = h[l.receiver];
    r.gathered += r.patch.reflectance * h[l.source].radiosity * l.form_factor;
  }
}

void push_pull(ElementHierarchy& h) {
  for (std::size_t root = 0; root < h.roots; ++root) push_pull_below(h, static_cast<int>(root), Color(0.0));
}

SolveReport solve_links(ElementHierarchy& h, double tolerance, int max_iterations) {
  require(tolerance > 0 && max_iterations >= 1, "solve_links: tolerance must be > 0 and max_iterations ≥ 1");
  SolveReport report;
  std::vector<Color> before(h.elements.size());
  double previous = 0;
  while (report.iterations < max_iterations) {
    for (std::size_t e = 0; e < h.elements.size(); ++e) before[e] = h.elements[e].radiosity;
    gather(h);
    push_pull(h);
    ++report.iterations;
    double change = 0, scale = 0;
    for (std::size_t e = 0; e < h.elements.size(); ++e) {
      change = std::max(change, max_channel(glm::abs(h.elements[e].radiosity - before[e])));
      scale = std::max(scale, max_channel(h.elements[e].radiosity));
    }
    report.change = change;
    if (change == 0) return report.converged = true, report;
    if (report.iterations >= 2) {
      const double q = change / previous;  // the contraction per sweep, estimated
      if (q < 1 && change * q / (1 - q) <= tolerance * scale) return report.converged = true, report;
    }
    previous = change;
  }
  return report;
}

std::size_t refine_links(ElementHierarchy& h, const RefineSettings& settings, const SegmentVisible& visible) {
  std::vector<Link> old;
  old.swap(h.links);
  std::size_t replaced = 0;
  for (const Link& l : old) {
    const LinkAction action = brightness_oracle(h[l.receiver].patch, h[l.source].patch, l.form_factor,
                                                h[l.source].radiosity, settings);
    replaced += action == LinkAction::split_receiver || action == LinkAction::split_source ? 1 : 0;
    split_or_link(h, l, action, settings, visible);
  }
  return replaced;
}

}  // namespace illum
