#include "illum/trace/ray_tree_record.hpp"

#include <algorithm>

#include "illum/core/error.hpp"

namespace illum {

const char* to_string(RayKind kind) {
  switch (kind) {
    case RayKind::primary:
      return "primary";
    case RayKind::reflection:
      return "reflection";
    case RayKind::refraction:
      return "refraction";
    case RayKind::shadow:
      return "shadow";
  }
  return "?";
}

void RayCounts::count(RayKind kind) {
  switch (kind) {
    case RayKind::primary:
      ++primary;
      break;
    case RayKind::reflection:
      ++reflection;
      break;
    case RayKind::refraction:
      ++refraction;
      break;
    case RayKind::shadow:
      ++shadow;
      break;
  }
}

RayCounts& RayCounts::operator+=(const RayCounts& o) {
  primary += o.primary;
  reflection += o.reflection;
  refraction += o.refraction;
  shadow += o.shadow;
  return *this;
}

std::string RayCounts::summary() const {
  return "primary " + std::to_string(primary) + ", shadow " + std::to_string(shadow) + ", reflection " +
         std::to_string(reflection) + ", refraction " + std::to_string(refraction) + " (total " +
         std::to_string(total()) + ")";
}

TraceStats& TraceStats::operator+=(const TraceStats& o) {
  rays += o.rays;
  work += o.work;
  return *this;
}

int RayTree::add(const RayTreeNode& node) {
  const int index = static_cast<int>(nodes.size());
  require(node.parent == no_node || (node.parent >= 0 && node.parent < index),
          "RayTree::add: the parent must be an earlier node");
  nodes.push_back(node);
  if (node.parent != no_node) nodes[static_cast<std::size_t>(node.parent)].children.push_back(index);
  return index;
}

std::size_t RayTree::count(RayKind kind) const {
  return static_cast<std::size_t>(
      std::count_if(nodes.begin(), nodes.end(), [&](const RayTreeNode& n) { return n.kind == kind; }));
}

int RayTree::depth() const {
  int d = 0;
  for (const RayTreeNode& n : nodes) d = std::max(d, n.depth);
  return d;
}

int record_ray(RayTree* tree, RayKind kind, const Ray& ray, int depth, const Color& weight, int parent,
               const SurfaceHit* hit) {
  if (!tree) return no_node;
  RayTreeNode n{.kind = kind,
                .parent = parent,
                .depth = depth,
                .origin = ray.origin,
                .direction = ray.direction,
                .range = ray.range,
                .weight = weight};
  if (hit) {
    n.hit = true, n.primitive = hit->primitive, n.material = hit->material, n.t = hit->t;
    n.point = hit->point, n.front_face = hit->front_face;
  } else if (kind == RayKind::shadow) {
    n.point = ray.at(ray.range.hi);
  }
  return tree->add(n);
}

int record_shadow_ray(RayTree* tree, const Ray& ray, int parent, std::uint32_t light) {
  if (!tree) return no_node;
  const int depth = parent == no_node ? 0 : tree->nodes[static_cast<std::size_t>(parent)].depth;
  const Color weight = parent == no_node ? Color(1.0) : tree->nodes[static_cast<std::size_t>(parent)].weight;
  const int n = record_ray(tree, RayKind::shadow, ray, depth, weight, parent, nullptr);
  tree->nodes[static_cast<std::size_t>(n)].light = light;
  return n;
}

void record_blocker(RayTree* tree, int node, const SurfaceHit& blocker, const Color& transmission) {
  if (!tree || node == no_node) return;
  RayTreeNode& n = tree->nodes[static_cast<std::size_t>(node)];
  n.hit = true, n.primitive = blocker.primitive, n.material = blocker.material, n.t = blocker.t;
  n.point = blocker.point, n.front_face = blocker.front_face, n.local = transmission;
}

void record_total_internal_reflection(RayTree* tree, int node) {
  if (tree && node != no_node) tree->nodes[static_cast<std::size_t>(node)].total_internal_reflection = true;
}

void record_result(RayTree* tree, int node, const Color& local, const Color& color) {
  if (!tree || node == no_node) return;
  tree->nodes[static_cast<std::size_t>(node)].local = local;
  tree->nodes[static_cast<std::size_t>(node)].color = color;
}

}  // namespace illum
