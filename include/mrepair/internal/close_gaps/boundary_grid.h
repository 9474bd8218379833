// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_CLOSE_GAPS_BOUNDARY_GRID_H
#define MREPAIR_INTERNAL_CLOSE_GAPS_BOUNDARY_GRID_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

namespace mrepair {
namespace internal {

// A hashed uniform grid of segments (boundary edges), keyed by an opaque
// 64-bit edge key. It only grows: edges that change are inserted again and
// the caller validates candidates (lazy deletion), which keeps each update
// O(length / cell) without bookkeeping of where an edge was registered.
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

  void init(const P& origin, double cell)
  {
    origin_ = origin;
    cell_ = cell;
    inv_ = 1.0 / cell;
    cells_.clear();
  }
  double cell() const { return cell_; }

  // registers `key` in every cell the segment [a,b] may touch: the segment is
  // cut in pieces no longer than a cell and each piece's box is covered.
  void insert(std::uint64_t key, const P& a, const P& b)
  {
    double len = std::sqrt(sq(b[0] - a[0]) + sq(b[1] - a[1]) + sq(b[2] - a[2]));
    std::size_t n = std::max<std::size_t>(1, static_cast<std::size_t>(std::ceil(len * inv_)));
    n = std::min<std::size_t>(n, 1u << 16);  // absurdly long edges: cap the work
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
            std::vector<Item>& c = cells_[pack(x, y, z)];
            if (c.empty() || c.back().key != key || c.back().a != a || c.back().b != b)
              c.push_back(Item{key, a, b});
          }
    }
  }

  // calls f(item) for the items registered in cells within `r` of p (with repeats).
  template <class F>
  void query(const P& p, double r, F&& f) const
  {
    query_box(p, p, r, f);
  }
  // calls f(item) for the items registered in cells meeting the box [a,b] (any
  // two corners) grown by `r` (with repeats).
  template <class F>
  void query_box(const P& a, const P& b, double r, F&& f) const
  {
    std::array<long, 3> lo, hi;
    for (int d = 0; d < 3; ++d) {
      lo[d] = index(std::min(a[d], b[d]) - r, d);
      hi[d] = index(std::max(a[d], b[d]) + r, d);
    }
    for (long x = lo[0]; x <= hi[0]; ++x)
      for (long y = lo[1]; y <= hi[1]; ++y)
        for (long z = lo[2]; z <= hi[2]; ++z) {
          auto it = cells_.find(pack(x, y, z));
          if (it == cells_.end()) continue;
          for (const Item& k : it->second) f(k);
        }
  }

private:
  static double sq(double x) { return x * x; }
  long index(double x, int d) const { return static_cast<long>(std::floor((x - origin_[d]) * inv_)); }
  static std::uint64_t pack(long x, long y, long z)
  {
    const std::uint64_t m = (1u << 21) - 1;
    return ((std::uint64_t(x) & m) << 42) | ((std::uint64_t(y) & m) << 21) | (std::uint64_t(z) & m);
  }

  P origin_{{0, 0, 0}};
  double cell_ = 1, inv_ = 1;
  std::unordered_map<std::uint64_t, std::vector<Item>> cells_;
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLOSE_GAPS_BOUNDARY_GRID_H
