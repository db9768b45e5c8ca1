#pragma once
// The pieces of a ray that lie inside a solid, lesson 04 ("Intersección con
// Modelos Sólidos").
//
// A ray P(s) = P0 + sω crosses a solid in a sorted list of parameter
// intervals ("spans") [s_in, s_out], one per passage through the solid. Each
// end remembers the surface that made it and that surface's outward normal,
// so that whatever Boolean operations combine the lists later, the nearest
// surviving end still knows how to shade itself.
//
// Spans are computed along the whole line (s may be negative, even ±∞ for an
// unbounded half-space); only the final choice of the hit looks at the ray's
// range. That is what makes rays that start inside a solid come out right.
#include <array>
#include <cmath>
#include <stdexcept>

#include "illum/core/vec.hpp"

namespace illum {

// One end of a span: where the ray crosses a surface of the solid.
struct Boundary {
  double s;     // ray parameter of the crossing (may be ±∞ for unbounded solids)
  Vec3 normal;  // outward unit normal of the solid there
  int surface;  // the tag of the primitive whose surface made the crossing
};

// The ray is inside the solid for enter.s <= s <= exit.s.
struct Span {
  Boundary enter;
  Boundary exit;

  double length() const { return exit.s - enter.s; }
};

// A sorted list of disjoint spans with a fixed capacity, so that evaluating a
// CSG tree allocates nothing per ray. A convex primitive gives at most one
// span, and each Boolean operation gives at most as many spans as its two
// operands together, so a tree of at most `capacity` primitives never
// overflows (CsgTree checks that when it is built).
class SpanList {
 public:
  static constexpr int capacity = 64;

  SpanList() {}  // the storage stays uninitialised: only size() spans are ever read
  // Copies only the spans in use (the rest of the storage is never read).
  SpanList(const SpanList& other) : size_(other.size_) {
    for (int i = 0; i < size_; ++i) spans_[i] = other.spans_[i];
  }
  SpanList& operator=(const SpanList& other) {
    size_ = other.size_;
    for (int i = 0; i < size_; ++i) spans_[i] = other.spans_[i];
    return *this;
  }

  int size() const { return size_; }
  bool empty() const { return size_ == 0; }
  void clear() { size_ = 0; }

  const Span& operator[](int i) const { return spans_[i]; }
  Span& operator[](int i) { return spans_[i]; }
  const Span& back() const { return spans_[size_ - 1]; }

  // Appends a span. Throws std::length_error when the list is full: a
  // combination that produces more spans than its operands have is wrong.
  void push_back(const Span& span) {
    if (size_ == capacity) throw std::length_error("SpanList: more than 64 spans along one ray");
    spans_[size_++] = span;
  }
  void pop_back() {
    if (size_ > 0) --size_;
  }

  const Span* begin() const { return spans_.data(); }
  const Span* end() const { return spans_.data() + size_; }

 private:
  std::array<Span, capacity> spans_;
  int size_ = 0;
};

// True when every span has enter.s <= exit.s, no parameter is NaN, and each
// span ends strictly before the next one starts: the form every primitive
// produces and every Boolean operation must keep.
inline bool is_sorted_and_disjoint(const SpanList& spans) {
  for (int i = 0; i < spans.size(); ++i) {
    const Span& span = spans[i];
    if (!(span.enter.s <= span.exit.s)) return false;  // also false for NaN
    if (i > 0 && !(spans[i - 1].exit.s < span.enter.s)) return false;
  }
  return true;
}

}  // namespace illum
