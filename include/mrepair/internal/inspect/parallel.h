// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_PARALLEL_H
#define MREPAIR_INTERNAL_INSPECT_PARALLEL_H

// The prefix sum and the stable counting sort of the inspection; the plain
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
// `key(i)` is the bucket of item i, or `skip` to leave it out.
template <typename T, typename Key>
void bucket_items(std::size_t n, std::size_t buckets, T skip, const Key& key, std::vector<T>& first,
                  std::vector<T>& order)
{
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
