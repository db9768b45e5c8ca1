#include "illum/accel/bvh.hpp"

#include <algorithm>
#include <numeric>

#include "illum/accel/bvh_traversal.hpp"
#include "illum/core/error.hpp"

namespace illum {
namespace {

struct Builder {
  const std::vector<Aabb>& boxes;
  const std::vector<Point3>& centroids;
  std::vector<std::uint32_t>& order;
  std::vector<BvhNode>& nodes;
  BvhSettings settings;
  int depth = 0;

  struct Bin {
    Aabb box;
    std::uint32_t count = 0;
  };

  // Builds the subtree of order[begin, end) into nodes[index] and what follows it.
  void build(std::uint32_t index, std::uint32_t begin, std::uint32_t end, int level) {
    depth = std::max(depth, level);
    Aabb box, centroid_box;
    for (std::uint32_t k = begin; k < end; ++k) {
      box.grow(boxes[order[k]]);
      centroid_box.grow(centroids[order[k]]);
    }
    nodes[index].box = box;
    const std::uint32_t n = end - begin;
    if (n <= static_cast<std::uint32_t>(settings.leaf_size)) {
      nodes[index].first = begin;
      nodes[index].count = n;
      return;
    }
    const std::uint32_t mid = split(begin, end, centroid_box, level);
    const std::uint32_t left = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    build(left, begin, mid, level + 1);
    const std::uint32_t right = static_cast<std::uint32_t>(nodes.size());
    nodes.emplace_back();
    build(right, mid, end, level + 1);
    nodes[index].first = right;
    nodes[index].count = 0;
  }

  struct Plane {
    double cost = infinity;
    int plane = 1;  // bins [0, plane) go left
  };

  int bin_of(std::uint32_t t, int axis, const Aabb& centroid_box) const {
    const double lo = centroid_box.lo[axis], extent = centroid_box.extent()[axis];
    const int b = static_cast<int>(settings.bins * ((centroids[t][axis] - lo) / extent));
    return std::clamp(b, 0, settings.bins - 1);
  }

  // The cheapest of the bins − 1 planes across `axis` (which must have a positive extent).
  Plane best_plane(std::uint32_t begin, std::uint32_t end, int axis, const Aabb& centroid_box) const {
    const int bin_count = settings.bins;
    std::vector<Bin> bins(bin_count);
    for (std::uint32_t k = begin; k < end; ++k) {
      Bin& bin = bins[bin_of(order[k], axis, centroid_box)];
      bin.box.grow(boxes[order[k]]);
      ++bin.count;
    }
    // Sweep from the right for the right-hand areas, then from the left for the cost.
    std::vector<double> right_cost(bin_count, 0.0);
    Aabb acc;
    std::uint32_t acc_n = 0;
    for (int b = bin_count - 1; b > 0; --b) {
      acc.grow(bins[b].box);
      acc_n += bins[b].count;
      right_cost[b] = acc.surface_area() * acc_n;
    }
    acc = Aabb{};
    acc_n = 0;
    Plane best;
    for (int b = 1; b < bin_count; ++b) {
      acc.grow(bins[b - 1].box);
      acc_n += bins[b - 1].count;
      const double cost = acc.surface_area() * acc_n + right_cost[b];
      if (acc_n > 0 && acc_n < end - begin && cost < best.cost) best = Plane{cost, b};
    }
    return best;
  }

  // The SAH split of order[begin, end): the index where the right half starts.
  // Every axis along which the centroids spread is binned, and the cheapest
  // plane of the three wins (binning the longest axis alone misses good
  // splits of thin, tilted clusters).
  std::uint32_t split(std::uint32_t begin, std::uint32_t end, const Aabb& centroid_box, int level) {
    const int longest = centroid_box.longest_axis();
    const std::uint32_t median = begin + (end - begin) / 2;
    const auto split_by_count = [&](int axis) {
      std::nth_element(
          order.begin() + begin, order.begin() + median, order.begin() + end,
          [&](std::uint32_t x, std::uint32_t y) { return centroids[x][axis] < centroids[y][axis]; });
      return median;
    };
    // All centroids equal, or a tree so deep the traversal stack is at risk: split by count.
    if (!(centroid_box.extent()[longest] > 0.0) || level > bvh_max_depth - 40) return split_by_count(longest);
    int axis = longest;
    Plane best;
    for (int a = 0; a < 3; ++a) {
      if (!(centroid_box.extent()[a] > 0.0)) continue;
      const Plane p = best_plane(begin, end, a, centroid_box);
      if (p.cost < best.cost) best = p, axis = a;
    }
    const auto middle = std::partition(order.begin() + begin, order.begin() + end, [&](std::uint32_t t) {
      return bin_of(t, axis, centroid_box) < best.plane;
    });
    const auto mid = static_cast<std::uint32_t>(middle - order.begin());
    if (mid == begin || mid == end) return split_by_count(longest);  // every centroid in one bin (rounding)
    return mid;
  }
};

}  // namespace

Bvh::Bvh(const TriangleSet& set, const BvhSettings& settings) {
  require(!set.triangles.empty(), "Bvh: no triangles");
  require(settings.leaf_size >= 1 && settings.leaf_size <= 255, "Bvh: leaf_size must be in 1..255");
  require(settings.bins >= 2 && settings.bins <= 256, "Bvh: bins must be in 2..256");
  const std::size_t n = set.triangles.size();
  require(n < (std::size_t{1} << 31), "Bvh: too many triangles");
  std::vector<Aabb> boxes(n);
  std::vector<Point3> centroids(n);
  for (std::size_t i = 0; i < n; ++i) {
    boxes[i] = bounds_of(set.triangles[i]);
    centroids[i] = boxes[i].center();
  }
  std::vector<std::uint32_t> order(n);
  std::iota(order.begin(), order.end(), 0u);
  nodes_.reserve(2 * n / settings.leaf_size + 1);
  nodes_.emplace_back();
  Builder builder{boxes, centroids, order, nodes_, settings};
  builder.build(0, 0, static_cast<std::uint32_t>(n), 0);
  depth_ = builder.depth;
  nodes_.shrink_to_fit();
  triangles_.reserve(n);
  ids_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    triangles_.push_back(set.triangles[order[k]]);
    ids_[k] = order[k];
  }
}

std::optional<AccelHit> Bvh::intersect(const Ray& ray, TraversalCounters& counters) const {
  return bvh_closest_hit(BvhView{nodes_, triangles_, ids_}, ray, counters);
}

bool Bvh::occluded(const Ray& ray, TraversalCounters& counters) const {
  return bvh_any_hit(BvhView{nodes_, triangles_, ids_}, ray, counters);
}

std::size_t Bvh::memory_bytes() const {
  return nodes_.size() * sizeof(BvhNode) + ids_.size() * sizeof(std::uint32_t);
}

}  // namespace illum
