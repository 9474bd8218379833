// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_CLOSE_GAPS_BOUNDARY_GRID_H
#define MREPAIR_INTERNAL_CLOSE_GAPS_BOUNDARY_GRID_H

#include <mrepair/internal/spatial_grid.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace mrepair {
namespace internal {

// A hashed uniform grid of segments (boundary edges), keyed by an opaque
// 64-bit edge key. It only grows: edges that change are inserted again and
// the caller validates candidates (lazy deletion), which keeps each update
// O(length / cell) without bookkeeping of where an edge was registered.
//
// Flat storage: the grid's Cell_table (internal/spatial_grid.h) maps a cell
// to the head of a chain of items in one pool (no allocation per cell; the
// gap closing inserts and queries a few cells per contraction, so hashing is
// the hot path).
class Segment_grid
{
public:
  using P = std::array<double, 3>;
  // an entry keeps the segment as registered, so that a query measures
  // distances without touching the mesh; callers re-check the few winners.
  struct Item
  {
    std::uint64_t key;
    P a, b;
  };

  // `expected`: number of cells expected (sizes the table; it grows anyway).
  void init(const P& origin, double cell, std::size_t expected = 0)
  {
    origin_ = origin;
    // a cell of 0, NaN or infinity would make every index the same or undefined
    cell_ = cell > 0 && std::isfinite(cell) ? cell : 1.0;
    inv_ = 1.0 / cell_;
    if (!std::isfinite(inv_)) inv_ = std::numeric_limits<double>::max();
    items_.clear();
    next_.clear();
    long_items_.clear();
    table_.reset(std::max<std::size_t>(expected, 32));
  }
  double cell() const { return cell_; }
  std::size_t size() const { return items_.size(); }

  // registers `key` in every cell the segment [a,b] may touch: the segment is
  // cut in pieces no longer than a cell and each piece's box is covered. A
  // segment longer than max_pieces cells (coordinates from 1e-9 to 1e9 in
  // one small soup: billions of cells) goes to a list every query reads.
  void insert(std::uint64_t key, const P& a, const P& b)
  {
    const double len = std::sqrt(sq(b[0] - a[0]) + sq(b[1] - a[1]) + sq(b[2] - a[2]));
    const double pieces = std::ceil(len * inv_);
    if (!(pieces <= double(max_pieces))) {  // NaN too
      long_items_.push_back(Item{key, a, b});
      return;
    }
    const std::size_t n = std::max<std::size_t>(1, static_cast<std::size_t>(pieces));
    for (std::size_t i = 0; i < n; ++i) {
      double t0 = double(i) / n, t1 = double(i + 1) / n;
      std::array<long, 3> lo, hi;
      for (int d = 0; d < 3; ++d) {
        double x0 = a[d] + t0 * (b[d] - a[d]), x1 = a[d] + t1 * (b[d] - a[d]);
        lo[d] = index(std::min(x0, x1), d);
        hi[d] = index(std::max(x0, x1), d);
      }
      for (long x = lo[0]; x <= hi[0]; ++x)
        for (long y = lo[1]; y <= hi[1]; ++y)
          for (long z = lo[2]; z <= hi[2]; ++z) {
            std::uint32_t& head = table_.at(pack_cell(x, y, z));
            if (head != npos) {
              const Item& h = items_[head];
              if (h.key == key && h.a == a && h.b == b) continue;  // pieces share cells
            }
            items_.push_back(Item{key, a, b});
            next_.push_back(head);
            head = std::uint32_t(items_.size() - 1);
          }
    }
  }

  // calls f(item) for the items registered in cells within `r` of p (with repeats).
  template <class F>
  void query(const P& p, double r, F&& f) const
  {
    query_box(p, p, r, f);
  }
  // a nearest-item search: calls f(item) for the items of the cells within `r`
  // of p, the cell of p first, and skips the cells farther from p than
  // bound() (the caller's best distance so far). An item's nearest point to
  // p lies in a cell the item is registered in, and that cell is no farther
  // than the point, so a search for the nearest item finds the same item as
  // `query` while reading the few cells around a near partner only.
  template <class F, class Bound>
  void query_nearest_first(const P& p, double r, F&& f, Bound&& bound) const
  {
    std::array<long, 3> lo, hi, at;
    double count = 1;  // in double: far cells would overflow a product of integers
    for (int d = 0; d < 3; ++d) {
      lo[d] = index(p[d] - r, d);
      hi[d] = index(p[d] + r, d);
      at[d] = index(p[d], d);
      count *= double(hi[d]) - double(lo[d]) + 1;
    }
    constexpr long max_span = 4;
    if (!(count <= double(max_span * max_span * max_span))) {  // a radius of several cells: no pruning
      query(p, r, f);
      return;
    }
    visit_long_items(p, p, r, f);
    // squared distance from p to the slabs of each axis, shrunk by a hair so
    // that the rounding of index() cannot put a point in a cell measured beyond it
    const double slack = 1e-7 * cell_;  // index() of a coordinate 1e6 cells out is off by ~1e-10 cell
    std::array<std::array<double, max_span>, 3> gap2;
    for (int d = 0; d < 3; ++d)
      for (long c = lo[d]; c <= hi[d]; ++c) {
        const double c0 = origin_[d] + double(c) * cell_, c1 = c0 + cell_;
        const double g = std::max({0.0, c0 - p[d], p[d] - c1}) - slack;
        gap2[d][std::size_t(c - lo[d])] = g > 0 ? g * g : 0.0;
      }
    auto visit = [&](long x, long y, long z) {
      for (std::uint32_t i = table_.find(pack_cell(x, y, z)); i != npos; i = next_[i]) f(items_[i]);
    };
    // the cell of p first: a near partner found there rules out most others
    visit(at[0], at[1], at[2]);
    for (long x = lo[0]; x <= hi[0]; ++x)
      for (long y = lo[1]; y <= hi[1]; ++y)
        for (long z = lo[2]; z <= hi[2]; ++z) {
          if (x == at[0] && y == at[1] && z == at[2]) continue;
          const double b = bound();
          const double d2 = gap2[0][std::size_t(x - lo[0])] + gap2[1][std::size_t(y - lo[1])] +
                            gap2[2][std::size_t(z - lo[2])];
          if (d2 > b * b) continue;
          visit(x, y, z);
        }
  }

  // calls f(item) for the items registered in cells meeting the box [a,b] (any
  // two corners) grown by `r` (with repeats). A box of more cells than there
  // are items reads the items instead, those whose box meets it: the same
  // items within r of the box, and a bounded cost whatever r and the cell.
  template <class F>
  void query_box(const P& a, const P& b, double r, F&& f) const
  {
    std::array<long, 3> lo, hi;
    P box_lo, box_hi;
    double cells = 1;
    for (int d = 0; d < 3; ++d) {
      box_lo[d] = std::min(a[d], b[d]) - r;
      box_hi[d] = std::max(a[d], b[d]) + r;
      lo[d] = index(box_lo[d], d);
      hi[d] = index(box_hi[d], d);
      cells *= double(hi[d]) - double(lo[d]) + 1;
    }
    visit_long_items(a, b, r, f);
    if (!(cells <= double(items_.size()) + 64)) {  // NaN (a NaN radius) too
      for (const Item& it : items_)
        if (meets(it, box_lo, box_hi)) f(it);
      return;
    }
    for (long x = lo[0]; x <= hi[0]; ++x)
      for (long y = lo[1]; y <= hi[1]; ++y)
        for (long z = lo[2]; z <= hi[2]; ++z)
          for (std::uint32_t i = table_.find(pack_cell(x, y, z)); i != npos; i = next_[i]) f(items_[i]);
  }

private:
  static bool meets(const Item& it, const P& lo, const P& hi)
  {
    for (int d = 0; d < 3; ++d)
      if (std::max(it.a[d], it.b[d]) < lo[d] || std::min(it.a[d], it.b[d]) > hi[d]) return false;
    return true;
  }
  // the segments kept out of the cells whose box meets the box [a,b] grown by r
  template <class F>
  void visit_long_items(const P& a, const P& b, double r, F& f) const
  {
    if (long_items_.empty()) return;
    P lo, hi;
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(a[d], b[d]) - r;
      hi[d] = std::max(a[d], b[d]) + r;
    }
    for (const Item& it : long_items_)
      if (meets(it, lo, hi)) f(it);
  }

  static constexpr std::uint32_t npos = Cell_table::npos;
  static constexpr double max_pieces = 1024;  // cells along one registered segment
  static double sq(double x) { return x * x; }
  // clamped before the cast (a double beyond long's range is undefined
  // behaviour); pack_cell() keeps 21 bits anyway, so far cells share slots
  long index(double x, int d) const
  {
    const double c = std::floor((x - origin_[d]) * inv_);
    constexpr double limit = 4.6e18;  // below 2^62
    if (!(c > -limit)) return c < 0 ? -long(4.6e18) : 0;  // NaN: cell 0
    return c < limit ? static_cast<long>(c) : long(4.6e18);
  }
  P origin_{{0, 0, 0}};
  double cell_ = 1, inv_ = 1;
  Cell_table table_;  // cell -> newest item registered in it
  std::vector<Item> items_;
  std::vector<std::uint32_t> next_;  // chain of items in a cell, newest first
  std::vector<Item> long_items_;     // segments too long for cells: every query reads them
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLOSE_GAPS_BOUNDARY_GRID_H
