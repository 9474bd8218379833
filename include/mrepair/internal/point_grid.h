// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_POINT_GRID_H
#define MREPAIR_INTERNAL_POINT_GRID_H

// A static uniform grid of points for fixed-radius neighbour searches: the
// (cell, id) entries sorted once, and an open-addressing table from each
// occupied cell to the start of its run of entries (a slot holds that start
// and 32 bits of the cell's hash, so that probing an empty cell rarely reads
// an entry; two to four slots per occupied cell). With a cell no smaller than
// the search radius, every point within the radius of p lies in one of the 27
// cells around the cell of p. Enumeration is deterministic: cells in
// (dx, dy, dz) order, ids ascending.

#include <mrepair/internal/utility.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <limits>
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
  /// \pre `ids.size()` is below the largest `Id`.
  template <typename PointOf>
  Point_grid(double cell, const std::vector<Id>& ids, const PointOf& point) : cell_(cell)
  {
    entries_.resize(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) entries_[i] = {cell_of(point(ids[i])), ids[i]};
    std::sort(entries_.begin(), entries_.end(),
              [](const Entry& a, const Entry& b) { return a.c < b.c || (a.c == b.c && a.id < b.id); });
    std::size_t runs = 0;
    for (std::size_t i = 0; i < entries_.size(); ++i)
      if (i == 0 || entries_[i].c != entries_[i - 1].c) ++runs;
    std::size_t cap = 16;
    shift_ = 60;
    while (cap < 2 * runs) {  // load at most 1/2
      cap <<= 1;
      --shift_;
    }
    slots_.assign(cap, Slot{npos, 0});
    for (std::size_t i = 0; i < entries_.size(); ++i)
      if (i == 0 || entries_[i].c != entries_[i - 1].c) {
        const std::uint64_t k = key(entries_[i].c);
        std::size_t h = first_slot(k);
        while (slots_[h].start != npos) h = (h + 1) & (cap - 1);
        slots_[h] = Slot{static_cast<Id>(i), static_cast<std::uint32_t>(k)};
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
          const Cell cc{{c[0] + dx, c[1] + dy, c[2] + dz}};
          for (std::size_t j = find(cc); j < entries_.size() && entries_[j].c == cc; ++j)
            f(entries_[j].id);
        }
  }
  /// calls f(id) for every id registered in the 27 cells around the cell of `p`.
  template <typename F>
  void for_each_near(const Vec3& p, const F& f) const
  {
    for_each_near(cell_of(p), f);
  }

private:
  static constexpr Id npos = (std::numeric_limits<Id>::max)();

  struct Slot
  {
    Id start;           // first entry of the cell's run, or npos
    std::uint32_t tag;  // low bits of the cell's key
  };

  // a mix of the three indices, Fibonacci-hashed (the high bits place the
  // slot, the low bits are its tag)
  static std::uint64_t key(const Cell& c)
  {
    std::uint64_t h = std::uint64_t(c[0]) * 0x9E3779B97F4A7C15ull;
    h ^= std::uint64_t(c[1]) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
    h ^= std::uint64_t(c[2]) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
    return h * 0x9E3779B97F4A7C15ull;
  }
  std::size_t first_slot(std::uint64_t k) const { return static_cast<std::size_t>(k >> shift_); }
  // the start of the run of cell c, or entries_.size() when c is empty.
  std::size_t find(const Cell& c) const
  {
    const std::uint64_t k = key(c);
    const std::uint32_t tag = static_cast<std::uint32_t>(k);
    for (std::size_t h = first_slot(k);; h = (h + 1) & (slots_.size() - 1)) {
      const Slot& s = slots_[h];
      if (s.start == npos) return entries_.size();
      if (s.tag == tag && entries_[s.start].c == c) return s.start;
    }
  }

  double cell_;
  std::vector<Entry> entries_;
  std::vector<Slot> slots_;
  int shift_ = 60;
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_POINT_GRID_H
