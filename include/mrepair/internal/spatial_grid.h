// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_SPATIAL_GRID_H
#define MREPAIR_INTERNAL_SPATIAL_GRID_H

// The uniform grid of cells behind every neighbour search of the library,
// and the queries its users need:
//
// | user                                  | items               | query                                   |
// |---------------------------------------|---------------------|-----------------------------------------|
// | soup merging, stitching (stitch_soup) | points              | ids in the 27 cells around a point      |
// | patch guard (hole filling, gaps)      | loop boxes          | ids in the cells a box spans            |
// | gap closing (Segment_grid)            | segments, growing   | items near a box, nearest cell first    |
// | self-intersections (inspect)          | face boxes          | pairs of boxes sharing a cell, each once|
//
// The parts: `Grid_box` (a box and its tests), `Grid_cell` and `Cell_range`
// (the cells a box spans, visited in (x, y, z) order), the cell keys
// (`pack_cell`: 21 bits an axis; `hash_cell`: a mix of three 64-bit indices),
// `Basic_cell_table` (open addressing from a cell key, or a 32-bit tag of
// its hash, to a 32-bit value: the start of a cell's run, or the head of its
// chain) and `Spatial_grid`, the static grid: (cell, id) entries sorted
// once, each cell's run found through the table by its tag. The gap closer's
// `Segment_grid` (close_gaps/boundary_grid.h) chains its items through the
// same table (`Cell_table`, exact keys), as it grows; the self-intersection
// counter (inspect/self_intersections.h) gathers its cells' entries by a
// parallel counting sort on the cell keys and keeps a pair in the one cell
// `owns_pair` names.
//
// Order: Spatial_grid visits cells in (dx, dy, dz) / (x, y, z) order and the
// ids of a cell ascending, so every enumeration is deterministic.

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

/// an axis-aligned box; empty until a point is added.
struct Grid_box
{
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  void add(const Vec3& p)
  {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  }
  void add(const Grid_box& b)
  {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], b.lo[d]);
      hi[d] = std::max(hi[d], b.hi[d]);
    }
  }
  bool empty() const { return !(lo[0] <= hi[0]); }
  bool meets(const Grid_box& b) const
  {
    for (int d = 0; d < 3; ++d)
      if (b.hi[d] < lo[d] || hi[d] < b.lo[d]) return false;
    return true;
  }
  bool contains(const Grid_box& b) const
  {
    for (int d = 0; d < 3; ++d)
      if (b.lo[d] < lo[d] || hi[d] < b.hi[d]) return false;
    return true;
  }
  double extent() const { return std::max(hi[0] - lo[0], std::max(hi[1] - lo[1], hi[2] - lo[2])); }
};

/// whether two boxes stored flat as (lo x, lo y, lo z, hi x, hi y, hi z) meet
/// (touching counts; a NaN side separates nothing).
template <typename T>
bool flat_boxes_meet(const T* a, const T* b)
{
  for (int d = 0; d < 3; ++d)
    if (a[d] > b[3 + d] || b[d] > a[3 + d]) return false;
  return true;
}

using Grid_cell = std::array<std::int64_t, 3>;

/// the block of cells from `lo` to `hi` (empty when a `hi` is below its `lo`).
struct Cell_range
{
  std::int64_t lo[3], hi[3];
  double count = 1;  // number of cells, in double: far cells would overflow a product of integers

  /// the cells of size 1 / `inverse_cell` that box `b` spans; none (and an
  /// infinite count) when its indices are beyond the integers.
  static Cell_range of(const Grid_box& b, double inverse_cell)
  {
    Cell_range c;
    for (int d = 0; d < 3; ++d) {
      const double lo = std::floor(b.lo[d] * inverse_cell), hi = std::floor(b.hi[d] * inverse_cell);
      if (!(std::abs(lo) < 1e18 && std::abs(hi) < 1e18)) {
        c.lo[0] = c.lo[1] = c.lo[2] = 0;
        c.hi[0] = c.hi[1] = c.hi[2] = -1;
        c.count = HUGE_VAL;
        return c;
      }
      c.lo[d] = std::int64_t(lo);
      c.hi[d] = std::int64_t(hi);
      c.count *= hi - lo + 1;
    }
    return c;
  }
  /// calls f(x, y, z) for every cell, in (x, y, z) order.
  template <typename F>
  void for_each(const F& f) const
  {
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z) f(x, y, z);
  }
};

/// a cell's key from the low 21 bits of each index (63 bits: never ~0);
/// cells 2^21 apart share a key.
inline std::uint64_t pack_cell(std::int64_t x, std::int64_t y, std::int64_t z)
{
  const std::uint64_t m = (std::uint64_t(1) << 21) - 1;
  return ((std::uint64_t(x) & m) << 42) | ((std::uint64_t(y) & m) << 21) | (std::uint64_t(z) & m);
}

/// a key mixing all bits of a cell's three indices (never ~0).
inline std::uint64_t hash_cell(const Grid_cell& c)
{
  std::uint64_t h = std::uint64_t(c[0]) * 0x9E3779B97F4A7C15ull;
  h ^= std::uint64_t(c[1]) * 0xC2B2AE3D27D4EB4Full + (h << 6) + (h >> 2);
  h ^= std::uint64_t(c[2]) * 0x165667B19E3779F9ull + (h << 6) + (h >> 2);
  h *= 0x9E3779B97F4A7C15ull;
  return h == ~std::uint64_t(0) ? h - 1 : h;
}

/// whether the cell with `key` (pack_cell) is the one where a pair of boxes
/// is kept: the cell of the lowest corner of their overlap. Every cell both
/// boxes span holds the pair; this one only keeps it. `cell(x, d)` is the
/// index of coordinate x along axis d, as the boxes were registered.
template <typename T, typename CellOf>
bool owns_pair(std::uint64_t key, const T* a, const T* b, const CellOf& cell)
{
  return pack_cell(cell(std::max(a[0], b[0]), 0), cell(std::max(a[1], b[1]), 1),
                   cell(std::max(a[2], b[2]), 2)) == key;
}

/// open addressing from cell keys (`Key`: 64 bits, or 32 bits of a
/// `hash_cell` as a tag: half the memory) to 32-bit values, at most half
/// full. A key may be entered several times (cells whose keys or tags
/// collide); `find` then tells them apart by their values. The key ~0 is
/// reserved.
template <typename Key>
class Basic_cell_table
{
public:
  static constexpr std::uint32_t npos = 0xffffffffu;
  static constexpr Key empty_key = static_cast<Key>(~Key(0));

  /// empties the table, with room for `expected` keys.
  void reset(std::size_t expected = 0)
  {
    std::size_t cap = 16;
    while (cap < 2 * expected) cap <<= 1;
    slots_.assign(cap, Slot{empty_key, npos});
    mask_ = cap - 1;
    shift_ = 64;
    for (std::size_t c = cap; c > 1; c >>= 1) --shift_;
    used_ = 0;
  }
  std::size_t size() const { return used_; }

  /// the value of `key` for which same(value) holds, or npos.
  template <typename Same>
  std::uint32_t find(Key key, const Same& same) const
  {
    for (std::size_t i = first_slot(key);; i = (i + 1) & mask_) {
      const Slot& s = slots_[i];
      if (s.key == key && same(s.value)) return s.value;
      if (s.key == empty_key) return npos;
    }
  }
  std::uint32_t find(Key key) const
  {
    return find(key, [](std::uint32_t) { return true; });
  }
  /// enters `key` again with `value`.
  void insert(Key key, std::uint32_t value)
  {
    if (2 * (used_ + 1) > slots_.size()) grow();
    std::size_t i = first_slot(key);
    while (slots_[i].key != empty_key) i = (i + 1) & mask_;
    slots_[i] = Slot{key, value};
    ++used_;
  }
  /// the value of `key`, entered as npos when missing.
  std::uint32_t& at(Key key)
  {
    if (2 * (used_ + 1) > slots_.size()) grow();
    for (std::size_t i = first_slot(key);; i = (i + 1) & mask_) {
      Slot& s = slots_[i];
      if (s.key == key) return s.value;
      if (s.key == empty_key) {
        s.key = key;
        ++used_;
        return s.value;
      }
    }
  }

private:
  struct Slot
  {
    Key key;
    std::uint32_t value;
  };
  // Fibonacci hashing: the high bits of the product place the key
  std::size_t first_slot(Key key) const
  {
    return static_cast<std::size_t>((std::uint64_t(key) * 0x9E3779B97F4A7C15ull) >> shift_);
  }
  void grow()
  {
    std::vector<Slot> old;
    old.swap(slots_);
    reset(old.size());  // twice the slots: room for old.size() keys
    for (const Slot& s : old)
      if (s.key != empty_key) {
        std::size_t i = first_slot(s.key);
        while (slots_[i].key != empty_key) i = (i + 1) & mask_;
        slots_[i] = s;
        ++used_;
      }
  }

  std::vector<Slot> slots_{std::vector<Slot>(16, Slot{empty_key, npos})};
  std::size_t mask_ = 15, used_ = 0;
  int shift_ = 60;
};
/// the table of exact 64-bit cell keys (pack_cell)
using Cell_table = Basic_cell_table<std::uint64_t>;

/// A static grid of ids, each entered in one cell (a point) or in the cells
/// of a range (a box): the (cell, id) entries sorted once by cell, then id,
/// and a table from each occupied cell's tag to the start of its run.
template <typename Id>
class Spatial_grid
{
public:
  struct Entry
  {
    Grid_cell c;
    Id id;
  };

  /// a grid of the given entries, in any order.
  /// \pre fewer entries than the largest `Id` and than 2^32 - 1.
  explicit Spatial_grid(std::vector<Entry> entries, double cell = 1) : cell_(cell), entries_(std::move(entries))
  {
    std::sort(entries_.begin(), entries_.end(),
              [](const Entry& a, const Entry& b) { return a.c < b.c || (a.c == b.c && a.id < b.id); });
    std::size_t runs = 0;
    for (std::size_t i = 0; i < entries_.size(); ++i)
      if (i == 0 || entries_[i].c != entries_[i - 1].c) ++runs;
    table_.reset(runs);
    for (std::size_t i = 0; i < entries_.size(); ++i)
      if (i == 0 || entries_[i].c != entries_[i - 1].c)
        table_.insert(tag(entries_[i].c), static_cast<std::uint32_t>(i));
  }
  /// a grid of points in cells of size `cell`, the point of id `i` being
  /// `point(i)` (a `Vec3`). With a cell no smaller than a search radius,
  /// every point within the radius of p lies in the 27 cells around p's.
  template <typename PointOf>
  Spatial_grid(double cell, const std::vector<Id>& ids, const PointOf& point)
      : Spatial_grid(point_entries(cell, ids, point), cell)
  {
  }

  /// the cell of `p` in a grid of points.
  Grid_cell cell_of(const Vec3& p) const { return cell_of(p, cell_); }

  /// the entries, sorted by cell, then id.
  const std::vector<Entry>& entries() const { return entries_; }

  /// calls f(id) for the ids of cell `c`, ascending.
  template <typename F>
  void for_each_in_cell(const Grid_cell& c, const F& f) const
  {
    for (std::size_t j = find(c); j < entries_.size() && entries_[j].c == c; ++j) f(entries_[j].id);
  }
  /// calls f(id) for every id in the 27 cells around cell `c`, cells in (dx, dy, dz) order.
  template <typename F>
  void for_each_near(const Grid_cell& c, const F& f) const
  {
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) for_each_in_cell(Grid_cell{{c[0] + dx, c[1] + dy, c[2] + dz}}, f);
  }
  /// calls f(id) for every id in the 27 cells around the cell of `p`.
  template <typename F>
  void for_each_near(const Vec3& p, const F& f) const
  {
    for_each_near(cell_of(p), f);
  }
  /// calls f(id) for the ids of every cell of `r` (an id entered in several of them once per cell).
  template <typename F>
  void for_each_in(const Cell_range& r, const F& f) const
  {
    r.for_each([&](std::int64_t x, std::int64_t y, std::int64_t z) { for_each_in_cell(Grid_cell{{x, y, z}}, f); });
  }

private:
  static Grid_cell cell_of(const Vec3& p, double cell)
  {
    Grid_cell c;
    for (int k = 0; k < 3; ++k) c[k] = static_cast<std::int64_t>(std::floor(p[k] / cell));
    return c;
  }
  template <typename PointOf>
  static std::vector<Entry> point_entries(double cell, const std::vector<Id>& ids, const PointOf& point)
  {
    std::vector<Entry> e(ids.size());
    for (std::size_t i = 0; i < ids.size(); ++i) e[i] = {cell_of(point(ids[i]), cell), ids[i]};
    return e;
  }
  // the start of the run of cell c, or entries_.size() when c is empty
  std::size_t find(const Grid_cell& c) const
  {
    const std::uint32_t s = table_.find(tag(c), [&](std::uint32_t start) { return entries_[start].c == c; });
    return s == Table::npos ? entries_.size() : s;
  }

  // 32 bits of the cell's hash (a slot of 8 bytes; equal tags are told
  // apart by the run's cell)
  using Table = Basic_cell_table<std::uint32_t>;
  static std::uint32_t tag(const Grid_cell& c)
  {
    const std::uint32_t t = static_cast<std::uint32_t>(hash_cell(c) >> 32);
    return t == Table::empty_key ? t - 1 : t;
  }

  double cell_;
  std::vector<Entry> entries_;
  Table table_;
};

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_SPATIAL_GRID_H
