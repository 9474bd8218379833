// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_PARALLEL_H
#define MREPAIR_INTERNAL_INSPECT_PARALLEL_H

// The prefix sum and the stable counting sort of the inspection (and of the
// soup stage's side and face sorts); the plain
// loop `parallel_for_index` and the chunked reduction `chunked` are in utility.h.

#include <mrepair/internal/utility.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace mrepair {
namespace internal {

// Turns counts into offsets in place (exclusive prefix sum); returns the total.
template <typename Vector>
typename Vector::value_type exclusive_scan_in_place(Vector& v)
{
  using T = typename Vector::value_type;
  T sum = 0;
  for (T& x : v) {
    T c = x;
    x = sum;
    sum += c;
  }
  return sum;
}

// A stable counting sort of the items [0,n) into `buckets` buckets: bucket b
// holds order[first[b]] .. order[first[b+1]-1], items in increasing order.
// `key(i)` is the bucket of item i, or `skip` to leave it out; it is called
// up to twice per item.
//
// One pass scattering n items into millions of buckets is random writes on
// one core (at 10M faces: 0.3 s for the 30M corners of the vertex table).
// Many items go through two cache-friendly passes instead, both parallel:
// items to a thousand or so ranges of consecutive buckets (per-chunk counts,
// chunks in order: stable), then each range sorted into its buckets in a
// buffer of its own (the keys kept beside the items for it, 4 bytes each).
// The result is the one of the single pass.
template <typename T, typename Key>
void bucket_items(std::size_t n, std::size_t buckets, T skip, const Key& key, std::vector<T>& first,
                  std::vector<T>& order)
{
#ifdef CGAL_LINKED_WITH_TBB
  if (n >= (std::size_t(1) << 20) && buckets >= (std::size_t(1) << 16)) {
    int shift = 0;
    while ((buckets >> shift) > 1024) ++shift;
    const std::size_t ranges = (buckets >> shift) + 1;
    const std::size_t chunks = std::min<std::size_t>(64, n >> 16);
    auto chunk_begin = [&](std::size_t c) { return n * c / chunks; };
    std::vector<T> at(chunks * ranges, 0);  // per chunk and range: count, then write position
    parallel_for_index(chunks, 1, [&](std::size_t c) {
      T* h = &at[c * ranges];
      for (std::size_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
        const T k = key(i);
        if (k != skip) ++h[std::size_t(k) >> shift];
      }
    });
    std::vector<T> range_first(ranges + 1, 0);
    T total = 0;
    for (std::size_t r = 0; r < ranges; ++r) {
      range_first[r] = total;
      for (std::size_t c = 0; c < chunks; ++c) {
        const T count = at[c * ranges + r];
        at[c * ranges + r] = total;
        total += count;
      }
    }
    range_first[ranges] = total;
    order.resize(total);
    Parallel_filled_vector<T> keys(total);  // beside order: the second pass reads no key(i)
    parallel_for_index(chunks, 1, [&](std::size_t c) {
      T* pos = &at[c * ranges];
      for (std::size_t i = chunk_begin(c); i < chunk_begin(c + 1); ++i) {
        const T k = key(i);
        if (k == skip) continue;
        const T p = pos[std::size_t(k) >> shift]++;
        order[p] = static_cast<T>(i);
        keys[p] = k;
      }
    });
    free_memory(at);
    first.resize(buckets + 1);
    first[buckets] = total;
    parallel_for_index(ranges, 1, [&](std::size_t r) {
      const std::size_t b0 = r << shift, b1 = std::min(buckets, (r + 1) << shift);
      if (b0 >= b1) return;
      const T lo = range_first[r], hi = range_first[r + 1];
      const std::vector<T> items(order.begin() + lo, order.begin() + hi);
      std::vector<T> pos(b1 - b0 + 1, 0);
      for (T j = lo; j < hi; ++j) ++pos[std::size_t(keys[j]) - b0 + 1];
      for (std::size_t b = 0; b < b1 - b0; ++b) {
        pos[b + 1] += pos[b];
        first[b0 + b] = lo + pos[b];
      }
      for (T j = lo; j < hi; ++j) order[lo + pos[std::size_t(keys[j]) - b0]++] = items[j - lo];
    });
    return;
  }
#endif
  first.assign(buckets + 1, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const T k = key(i);
    if (k != skip) ++first[k];
  }
  const T total = exclusive_scan_in_place(first);
  first[buckets] = total;
  order.resize(total);
  std::vector<T> pos(first.begin(), first.end() - 1);
  for (std::size_t i = 0; i < n; ++i) {
    const T k = key(i);
    if (k != skip) order[pos[k]++] = static_cast<T>(i);
  }
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_INSPECT_PARALLEL_H
