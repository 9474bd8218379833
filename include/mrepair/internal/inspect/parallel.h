// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_PARALLEL_H
#define MREPAIR_INTERNAL_INSPECT_PARALLEL_H

// The reproducible chunked reduction and the prefix sum of the inspection;
// the plain loop is `parallel_for_index` of utility.h.

#include <mrepair/internal/utility.h>

#include <algorithm>
#include <cstddef>
#include <vector>

namespace mrepair {
namespace internal {

// Splits [0,n) into a fixed number of chunks (independent of the thread count,
// so that floating-point sums are reproducible), runs f(begin, end, acc) on
// each, possibly in parallel, and returns the per-chunk accumulators in order.
template <typename Acc, typename F>
std::vector<Acc> chunked(std::size_t n, const F& f)
{
  std::size_t chunks = std::min<std::size_t>(64, (n + 8191) / 8192);
  if (chunks == 0) chunks = 1;
  std::vector<Acc> acc(chunks);
  parallel_for_index(chunks, 1, [&](std::size_t c) {
    f(n * c / chunks, n * (c + 1) / chunks, acc[c]);
  });
  return acc;
}

// Turns counts into offsets in place (exclusive prefix sum); returns the total.
template <typename T>
T exclusive_scan_in_place(std::vector<T>& v)
{
  T sum = 0;
  for (T& x : v) {
    T c = x;
    x = sum;
    sum += c;
  }
  return sum;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_INSPECT_PARALLEL_H
