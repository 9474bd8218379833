// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The worker of classify_input() (input_profile.h): the measures of a
// triangle mesh and the scan rule.
#ifndef MREPAIR_INTERNAL_INPUT_PROFILE_CLASSIFIER_H
#define MREPAIR_INTERNAL_INPUT_PROFILE_CLASSIFIER_H

#include <mrepair/internal/clean_scan_mesh/mesh_ops.h>
#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/utility.h>
#include <mrepair/input_classification.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

namespace mrepair {
namespace internal {
// The thresholds of the scan rule (doc/guarantees.md, "Input kind").
constexpr std::size_t scan_min_faces = 2000;
constexpr double scan_max_edge_cv = 0.6;
constexpr double scan_max_coplanar_share = 0.2;
constexpr double scan_max_skinny_share = 0.1;

// `asked`: a profile other than `automatic` is returned as chosen by the
// user, with the measures.
template <typename TriangleMesh, typename VertexPointMap>
Input_classification classify_input(const TriangleMesh& tm, const VertexPointMap& vpm,
                                    Input_profile asked)
{
  namespace SC = clean_pipeline;
  Input_classification c;
  c.faces = internal::face_count(tm);
  // Reads only: in parallel on any mesh, with the reproducible chunked sums
  // (a sequential pass took 0.1 s of a 1M-face job, twice).
  struct Measures
  {
    double sum = 0, sum2 = 0;
    std::size_t n_edges = 0, interior = 0, coplanar = 0, triangles = 0, skinny = 0;
  };
  const double cos_coplanar = std::cos(0.01 * internal::pi / 180.);
  const double sin5 = std::sin(5. * internal::pi / 180.);
  using edge_descriptor = typename boost::graph_traits<TriangleMesh>::edge_descriptor;
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  const std::vector<edge_descriptor> es(edges(tm).begin(), edges(tm).end());
  const std::vector<face_descriptor> fs(faces(tm).begin(), faces(tm).end());
  auto measure_edges = [&](std::size_t b, std::size_t e, Measures& m) {
    for (std::size_t i = b; i < e; ++i) {
      const auto h = halfedge(es[i], tm);
      const internal::Vec3 p = internal::point(vpm, source(h, tm)), q = internal::point(vpm, target(h, tm));
      const double l = internal::norm(internal::sub(p, q));
      if (!std::isfinite(l)) continue;
      m.sum += l;
      m.sum2 += l * l;
      ++m.n_edges;
      if (is_border_edge(h, tm)) continue;
      ++m.interior;
      const internal::Vec3 n1 = SC::face_normal(h, tm, vpm), n2 = SC::face_normal(opposite(h, tm), tm, vpm);
      const double l1 = internal::norm(n1), l2 = internal::norm(n2);
      if (l1 > 0. && l2 > 0. && internal::dot(n1, n2) >= cos_coplanar * l1 * l2) ++m.coplanar;
    }
  };
  auto measure_faces = [&](std::size_t b, std::size_t e, Measures& m) {
    for (std::size_t j = b; j < e; ++j) {
      internal::Vec3 p[3];
      int k = 0;
      for (auto v : CGAL::vertices_around_face(halfedge(fs[j], tm), tm)) {
        if (k < 3) p[k] = internal::point(vpm, v);
        ++k;
      }
      if (k != 3) continue;
      ++m.triangles;
      const double twice_area =
          internal::norm(internal::cross(internal::sub(p[1], p[0]), internal::sub(p[2], p[0])));
      double len[3];
      for (int i = 0; i < 3; ++i) len[i] = internal::norm(internal::sub(p[(i + 1) % 3], p[i]));
      // sin of the angle at vertex i = 2 area / (product of its two edges):
      // under sin 5 degrees the angle is below 5 (a needle) or above 175 (a cap)
      bool thin = false;
      for (int i = 0; i < 3; ++i) {
        const double d = len[i] * len[(i + 2) % 3];
        if (!(d > 0.) || twice_area <= sin5 * d) thin = true;
      }
      if (thin && std::isfinite(twice_area)) ++m.skinny;
    }
  };
  double sum = 0, sum2 = 0;
  std::size_t n_edges = 0, interior = 0, coplanar = 0, triangles = 0, skinny = 0;
  for (const Measures& m : internal::chunked<Measures>(es.size(), measure_edges)) {
    sum += m.sum;
    sum2 += m.sum2;
    n_edges += m.n_edges;
    interior += m.interior;
    coplanar += m.coplanar;
  }
  for (const Measures& m : internal::chunked<Measures>(fs.size(), measure_faces)) {
    triangles += m.triangles;
    skinny += m.skinny;
  }
  const double mean = n_edges ? sum / double(n_edges) : 0.;
  const double var = n_edges ? std::max(0., sum2 / double(n_edges) - mean * mean) : 0.;
  c.edge_length_cv = mean > 0. ? std::sqrt(var) / mean : 0.;
  c.coplanar_edge_share = interior ? double(coplanar) / double(interior) : 0.;
  c.skinny_face_share = triangles ? double(skinny) / double(triangles) : 0.;

  char measures[160];
  std::snprintf(measures, sizeof measures,
                "%zu faces, edge-length CV %.2f, %.1f%% coplanar edges, %.1f%% slivers", c.faces,
                c.edge_length_cv, 100. * c.coplanar_edge_share, 100. * c.skinny_face_share);
  if (asked != Input_profile::automatic) {
    c.profile = asked;
    c.chosen_by_user = true;
    c.reason = std::string("chosen by the caller (") + measures + ")";
    return c;
  }
  std::string why;
  if (c.faces < internal::scan_min_faces)
    why = "fewer than " + std::to_string(internal::scan_min_faces) + " faces";
  else if (c.edge_length_cv > internal::scan_max_edge_cv)
    why = "edge lengths vary (CV above 0.6)";
  else if (c.coplanar_edge_share > internal::scan_max_coplanar_share)
    why = "exactly flat regions (over 20% coplanar edges)";
  else if (c.skinny_face_share > internal::scan_max_skinny_share)
    why = "tessellation slivers (over 10% of the faces)";
  if (why.empty()) {
    c.profile = Input_profile::scan;
    c.reason = std::string("dense near-uniform sampling: ") + measures;
  } else {
    c.profile = Input_profile::cad;
    c.reason = why + ": " + measures;
  }
  return c;
}

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_INPUT_PROFILE_CLASSIFIER_H
