// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_STITCH_SOUP_DRIVER_H
#define MREPAIR_INTERNAL_STITCH_SOUP_DRIVER_H

// The steps the entry points of stitch_soup.h share around a
// `Soup_repairer`: running its stages under the visitor, the final status,
// and writing the triangles back into the user's soup types.

#include <mrepair/internal/stitch_soup/soup_repairer.h>
#include <mrepair/stitch_soup_result.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <array>
#include <iterator>
#include <string>
#include <type_traits>

namespace mrepair {
namespace internal {

// The "clean" phase: loads the soup into `w` (merging, dropping, triangulating).
template <class PointRange, class PolygonRange, class VisitorHandle>
bool load_soup(Soup_repairer& w, const PointRange& points, const PolygonRange& polygons,
               VisitorHandle& vis)
{
  Phase_scope<VisitorHandle> phase(vis, "clean");
  return w.load(points, polygons);
}

// The stages of `clean_polygon_soup`: load (clean) and count what is left,
// unless cancelled. Returns false when `r` already holds the final status.
template <class PointRange, class PolygonRange, class VisitorHandle>
bool load_and_clean_soup(Soup_repairer& w, const PointRange& points,
                         const PolygonRange& polygons, VisitorHandle& vis, Soup_repair_result& r)
{
  if (!load_soup(w, points, polygons, vis)) return false;
  if (vis.stop_requested()) {
    r.status = Status::cancelled;
    return false;
  }
  r.faces_out = w.T.size();
  r.vertices_out = w.P.size();
  return true;
}

// The stages shared by the in-place and the mesh-building entry points: load
// (clean), then cut, orient and stitch unless cancelled. Returns false when
// `r` already holds the final status.
template <class PointRange, class PolygonRange, class VisitorHandle>
bool load_and_repair_soup(Soup_repairer& w, const PointRange& points,
                          const PolygonRange& polygons, VisitorHandle& vis, Soup_repair_result& r)
{
  if (!load_soup(w, points, polygons, vis)) return false;
  if (vis.stop_requested() || !w.run_topology(vis)) {
    r.status = Status::cancelled;
    return false;
  }
  return true;
}

// ok, or partial with a message when polygons were dropped for bad data.
inline void finish_soup_status(Soup_repair_result& r)
{
  if (r.status != Status::ok) return;
  if (r.polygons_in == 0 || r.points_in == 0) {
    r.status = Status::empty_input;
    r.message = r.polygons_in == 0 ? "no polygons" : "no points";
    return;
  }
  std::string msg;
  if (r.removed_invalid_index)
    msg += std::to_string(r.removed_invalid_index) + " polygon(s) with out-of-range indices dropped";
  if (r.removed_non_finite) {
    if (!msg.empty()) msg += "; ";
    msg += std::to_string(r.removed_non_finite) + " polygon(s) using non-finite points dropped";
  }
  if (!msg.empty()) {
    r.status = Status::partial;
    r.message = msg;
  }
}

template <class Polygon>
Polygon make_soup_triangle(std::size_t a, std::size_t b, std::size_t c)
{
  Polygon p;
  using I = std::decay_t<decltype(*std::begin(p))>;
  if constexpr (std::is_same<Polygon, std::array<I, 3>>::value) {
    p = {I(a), I(b), I(c)};
  } else {
    p.resize(3);
    auto it = std::begin(p);
    *it++ = I(a);
    *it++ = I(b);
    *it = I(c);
  }
  return p;
}

template <class PointRange, class PolygonRange>
void write_back_soup(const Soup_repairer& w, PointRange& points, PolygonRange& polygons)
{
  using Point = typename PointRange::value_type;
  using Polygon = typename PolygonRange::value_type;
  PointRange pts;
  pts.reserve(w.P.size());
  for (const auto& p : w.P) pts.push_back(Point(p[0], p[1], p[2]));
  PolygonRange polys;
  polys.reserve(w.T.size());
  for (const auto& t : w.T) polys.push_back(make_soup_triangle<Polygon>(t[0], t[1], t[2]));
  points.swap(pts);
  polygons.swap(polys);
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_STITCH_SOUP_DRIVER_H
