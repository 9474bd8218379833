// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_INSPECT_PARALLEL_H
#define MREPAIR_INTERNAL_INSPECT_PARALLEL_H

#include <algorithm>
#include <cstddef>
#include <vector>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#endif

namespace mrepair {
namespace internal {

// Calls f(i) for i in [0,n), in parallel with TBB when the range is worth it.
template <typename F>
void parallel_for_index(std::size_t n, std::size_t grain, const F& f)
{
#ifdef CGAL_LINKED_WITH_TBB
  if (n > grain) {
    tbb::parallel_for(tbb::blocked_range<std::size_t>(0, n, grain),
                      [&](const tbb::blocked_range<std::size_t>& r) {
                        for (std::size_t i = r.begin(); i != r.end(); ++i) f(i);
                      });
    return;
  }
#endif
  for (std::size_t i = 0; i < n; ++i) f(i);
}

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
