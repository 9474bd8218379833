// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_POINT_GRID_H
#define MREPAIR_INTERNAL_POINT_GRID_H

// A static uniform grid of points for fixed-radius neighbour searches: the
// (cell, id) entries sorted once, and a hash from each occupied cell to its
// run of entries. With a cell no smaller than the search radius, every point
// within the radius of p lies in one of the 27 cells around the cell of p.
// Enumeration is deterministic: cells in (dx, dy, dz) order, ids ascending.

#include <mrepair/internal/utility.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <unordered_map>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {

template <typename Id>
class Point_grid
{
public:
  using Cell = std::array<std::int64_t, 3>;
  struct Entry
  {
    Cell c;
    Id id;
  };

  /// registers `ids`, the point of id `i` being `point(i)` (a `Vec3`), in cells of size `cell`.
  template <typename PointOf>
  Point_grid(double cell, const std::vector<Id>& ids, const PointOf& point) : cell_(cell)
  {
    entries_.resize(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) entries_[i] = {cell_of(point(ids[i])), ids[i]};
    std::sort(entries_.begin(), entries_.end(),
              [](const Entry& a, const Entry& b) { return a.c < b.c || (a.c == b.c && a.id < b.id); });
    range_.reserve(entries_.size());
    for (std::size_t i = 0; i < entries_.size();) {
      std::size_t j = i;
      while (j < entries_.size() && entries_[j].c == entries_[i].c) ++j;
      range_.emplace(entries_[i].c, std::make_pair(i, j));
      i = j;
    }
  }

  Cell cell_of(const Vec3& p) const
  {
    Cell c;
    for (int k = 0; k < 3; ++k) c[k] = static_cast<std::int64_t>(std::floor(p[k] / cell_));
    return c;
  }

  /// the entries, sorted by cell, then id.
  const std::vector<Entry>& entries() const { return entries_; }

  /// calls f(id) for every id registered in the 27 cells around cell `c`.
  template <typename F>
  void for_each_near(const Cell& c, const F& f) const
  {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          auto it = range_.find({c[0] + dx, c[1] + dy, c[2] + dz});
          if (it == range_.end()) continue;
          for (std::size_t j = it->second.first; j < it->second.second; ++j) f(entries_[j].id);
        }
  }
  /// calls f(id) for every id registered in the 27 cells around the cell of `p`.
  template <typename F>
  void for_each_near(const Vec3& p, const F& f) const
  {
    for_each_near(cell_of(p), f);
  }

private:
  struct Hash
  {
    std::size_t operator()(const Cell& c) const
    {
      std::uint64_t h = std::uint64_t(c[0]) * 0x9E3779B97F4A7C15ull;
      h ^= std::uint64_t(c[1]) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
      h ^= std::uint64_t(c[2]) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
      return std::size_t(h);
    }
  };

  double cell_;
  std::vector<Entry> entries_;
  std::unordered_map<Cell, std::pair<std::size_t, std::size_t>, Hash> range_;
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_POINT_GRID_H
