// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_CLOSE_GAPS_TOLERANCE_H
#define MREPAIR_INTERNAL_CLOSE_GAPS_TOLERANCE_H

// The worker of `estimate_gap_tolerance()` (close_gaps.h; the rule and the
// data behind it are in doc/close_gaps.md).

#include <mrepair/gap_closing_result.h>
#include <mrepair/internal/close_gaps/boundary_grid.h>
#include <mrepair/internal/utility.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace mrepair {
namespace internal {

// The constants of the rule (doc/close_gaps.md, "Automatic tolerance").
constexpr double gap_candidate_ratio = 1.0;    // candidate: partner nearer than its longest boundary edge
constexpr double gap_knee_jump = 2.0;          // a knee: the next distance at least this factor larger
constexpr double gap_knee_start = 0.9;         // knees are looked for above this quantile of the candidates
constexpr double gap_tolerance_margin = 1.5;   // room for the distances changing while the gap closes
constexpr std::size_t gap_min_candidates = 16; // fewer: no distribution to read a knee from (tolerance 0)
// A seam's two sides face each other: their outward directions (in the
// faces' planes, away from the faces) and their loop directions point
// opposite ways, or at most at right angles across a crease. A partner whose
// surface lies on the same side (outward directions within 60 degrees: the
// two sides of a thin open end, a fold) or whose boundary runs the same way
// is the model's shape, not a seam: it does not count as a candidate. On the
// blade soups of doc/close_gaps.md the thin open ends alone raised the knee
// from 0.063 to 0.132.
constexpr double gap_facing_max_cosine = 0.5;
// A CAD exporter's seam gaps come from tessellating a shared curve twice to a
// chord tolerance: 1e-4 to 1e-3 of the part's size (the generated soups of
// doc/close_gaps.md: 0.0007 to 0.0015 of the diagonal). A knee farther than 1%
// of the boundary's diagonal is the model's own narrow features: on small
// real meshes (CGAL's nm_vertices_pinched, non-conform_snapping-overlap,
// geometry-central's triple_vierbein) such tolerances zipped real holes and
// removed 10-15% of the faces.
constexpr double gap_max_diagonal_share = 0.01;

template <class TriangleMesh, class VertexPointMap>
Gap_tolerance_estimate estimate_tolerance(const TriangleMesh& tm, const VertexPointMap& vpm)
{
  using GT = boost::graph_traits<TriangleMesh>;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using Id = std::uint32_t;
  constexpr Id npos = Id(-1);
  Gap_tolerance_estimate e;

  // boundary vertices get dense ids; each keeps its border halfedges' other ends
  auto id = get(CGAL::dynamic_vertex_property_t<std::uint32_t>(), tm);
  for (vertex_descriptor v : vertices(tm)) put(id, v, npos);
  std::vector<vertex_descriptor> vd;
  std::vector<Vec3> p;
  std::vector<std::uint64_t> edges;  // (source id, target id) of border halfedges
  std::vector<Vec3> edge_outward;    // per border halfedge: unit, in its face's plane, away from the face
  auto id_of = [&](vertex_descriptor v) {
    Id i = get(id, v);
    if (i != npos) return i;
    i = Id(vd.size());
    put(id, v, i);
    vd.push_back(v);
    p.push_back(point(vpm, v));
    return i;
  };
  for (halfedge_descriptor h : halfedges(tm))
    if (is_border(h, tm)) {
      Id a = id_of(source(h, tm)), b = id_of(target(h, tm));
      edges.push_back((std::uint64_t(a) << 32) | b);
      // the face is on the left of its halfedge b->a, so outward is n x (a->b)
      const halfedge_descriptor hi = opposite(h, tm);
      const Vec3 pc = point(vpm, target(next(hi, tm), tm));
      const Vec3 n = triangle_normal(p[b], p[a], pc);
      edge_outward.push_back(normalized(cross(n, sub(p[b], p[a]))));
    }
  const std::size_t nb = vd.size();
  e.boundary_vertices = nb;
  e.boundary_edges = edges.size();
  if (edges.empty()) return e;
  for (const Vec3& q : p)
    if (!is_finite(q)) {
      e.status = Status::non_finite_input;
      return e;
    }

  // per vertex: the longest incident boundary edge, and its loop neighbours
  std::vector<double> longest(nb, 0.);
  std::vector<Id> start(nb + 1, 0);
  for (std::uint64_t k : edges) {
    ++start[Id(k >> 32) + 1];
    ++start[Id(k) + 1];
  }
  for (std::size_t i = 0; i < nb; ++i) start[i + 1] += start[i];
  std::vector<Id> nbr(start[nb]);
  {
    std::vector<Id> fill(start.begin(), start.end() - 1);
    for (std::uint64_t k : edges) {
      Id a = Id(k >> 32), b = Id(k);
      const double l = distance(p[a], p[b]);
      longest[a] = std::max(longest[a], l);
      longest[b] = std::max(longest[b], l);
      nbr[fill[a]++] = b;
      nbr[fill[b]++] = a;
    }
  }
  // per vertex: the sums of its border edges' outward and loop directions
  std::vector<Vec3> vertex_outward(nb, Vec3{{0, 0, 0}}), vertex_tangent(nb, Vec3{{0, 0, 0}});
  for (std::size_t k = 0; k < edges.size(); ++k) {
    const Id a = Id(edges[k] >> 32), b = Id(edges[k]);
    const Vec3 t = normalized(sub(p[b], p[a]));
    for (Id x : {a, b}) {
      vertex_outward[x] = add(vertex_outward[x], edge_outward[k]);
      vertex_tangent[x] = add(vertex_tangent[x], t);
    }
  }
  std::vector<double> lengths(longest);
  std::nth_element(lengths.begin(), lengths.begin() + nb / 2, lengths.end());
  e.median_edge_length = lengths[nb / 2];

  Vec3 lo = p[0], hi = p[0];
  for (const Vec3& q : p)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], q[d]);
      hi[d] = std::max(hi[d], q[d]);
    }
  Segment_grid grid;
  grid.init(lo, std::max({e.median_edge_length, distance(lo, hi) * 1e-6, 1e-300}), 2 * edges.size());
  for (std::size_t k = 0; k < edges.size(); ++k) grid.insert(k, p[Id(edges[k] >> 32)], p[Id(edges[k])]);

  // d(v): distance to the nearest boundary edge that does not touch v or a loop
  // neighbour of v (those are always within one edge length), searched within
  // the longest boundary edge at v: a seam partner is nearer than that, the
  // rest of a real hole's rim is not.
  std::vector<double> d(nb, std::numeric_limits<double>::infinity());
  std::vector<char> not_facing(nb, 0);
  auto near = [&](std::size_t i) {
    const Id v = Id(i);
    const double r = gap_candidate_ratio * longest[v];
    // the nearest edge, and the nearest one facing v: v is a candidate when
    // they are equally near (at a corner the nearest point is the end of two
    // edges, only one of which may face v)
    double best = std::numeric_limits<double>::infinity(), best_facing = best;
    const Vec3 ov = normalized(vertex_outward[v]), tv = normalized(vertex_tangent[v]);
    auto excluded = [&](Id x) {
      if (x == v) return true;
      for (Id j = start[v]; j < start[v + 1]; ++j)
        if (nbr[j] == x) return true;
      return false;
    };
    auto visit = [&](const Segment_grid::Item& it) {
      const std::size_t k = std::size_t(it.key);
      const Id a = Id(edges[k] >> 32), b = Id(edges[k]);
      if (excluded(a) || excluded(b)) return;
      const Vec3 ab = sub(it.b, it.a);
      const double l2 = dot(ab, ab);
      double t = l2 > 0 ? dot(sub(p[v], it.a), ab) / l2 : 0;
      t = std::min(1., std::max(0., t));
      const double dv = distance(p[v], add(it.a, mul(ab, t)));
      best = std::min(best, dv);
      if (dv < best_facing && dot(ov, edge_outward[k]) <= gap_facing_max_cosine &&
          dot(tv, normalized(ab)) <= gap_facing_max_cosine)
        best_facing = dv;
    };
    // growing radii: a seam partner is found in the first query; only a vertex
    // with long edges and nobody near pays for a query as wide as its longest
    // edge (on the 1M-face anchor soup one such query per vertex took 13 s)
    // (a radius of 0 never grows: at most 32 rounds, the last one at r)
    double q = std::min(r, std::max(e.median_edge_length, r / 64));
    for (int round = 0;; ++round, q = std::min(r, 4 * q)) {
      if (round == 32) q = r;
      best = best_facing = std::numeric_limits<double>::infinity();
      grid.query(p[v], q, visit);
      if (best <= q || q >= r || round >= 32) break;
    }
    if (!(best < r)) return;
    if (!(best_facing <= best * (1 + 1e-9))) {
      not_facing[v] = 1;
      return;
    }
    d[v] = best;
  };
  if (nb >= 4096) parallel_for_index(nb, 256, near);
  else
    for (std::size_t i = 0; i < nb; ++i) near(i);

  std::vector<double> c;
  for (double x : d)
    if (std::isfinite(x)) c.push_back(x);
  e.candidates = c.size();
  e.not_facing = std::size_t(std::count(not_facing.begin(), not_facing.end(), char(1)));
  // a handful of near pairs (three loose triangles, a needle next to a cap)
  // is no seam: leave it to the user
  if (c.size() < gap_min_candidates) return e;
  std::sort(c.begin(), c.end());
  e.largest_candidate_distance = c.back();
  // the knee: the first jump by gap_knee_jump above the gap_knee_start
  // quantile; what lies above it are a few narrow features of the model, not
  // the bulk of the seams
  std::size_t knee = c.size() - 1;
  const std::size_t from = static_cast<std::size_t>(gap_knee_start * double(c.size() - 1));
  for (std::size_t i = from; i + 1 < c.size(); ++i)
    if (c[i + 1] > gap_knee_jump * c[i] && c[i + 1] > 0) {
      knee = i;
      break;
    }
  e.knee_distance = c[knee];
  e.above_knee = c.size() - 1 - knee;
  e.tolerance = std::min(gap_tolerance_margin * c[knee], gap_max_diagonal_share * distance(lo, hi));
  // coincident seams only: a positive limit still lets the zero-distance pairs close
  if (!(e.tolerance > 0)) e.tolerance = 1e-9 * e.median_edge_length;
  return e;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_CLOSE_GAPS_TOLERANCE_H
