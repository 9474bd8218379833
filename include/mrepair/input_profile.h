// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INPUT_PROFILE_H
#define MREPAIR_INPUT_PROFILE_H

#include <mrepair/internal/clean_scan_mesh/mesh_ops.h>
#include <mrepair/internal/inspect/parallel.h>
#include <mrepair/internal/utility.h>
#include <mrepair/parameters.h>
#include <mrepair/report.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/Named_function_parameters.h>

#include <cmath>
#include <cstddef>
#include <cstdio>
#include <string>
#include <vector>

/// \file input_profile.h
/// Tells a dense scan from a CAD export or print model, so that the
/// scan-cleaning steps of RameshCleaner (spike relaxation, boundary erosion,
/// small-component removal, near-degenerate collapses) run only where their
/// assumptions hold: a surface sampled densely with near-uniform edges, whose
/// defects are noise. On a CAD tessellation the same steps read sharp
/// features as spikes, long thin triangles as defects and separate parts as
/// islands.

MREPAIR_ADD_NAMED_PARAMETER(input_profile)  // mrepair::Input_profile (automatic)
// const Input_classification*: classify_input() of this very mesh, already
// computed by the caller (repair.h), which clean_scan_mesh() then reuses
MREPAIR_ADD_NAMED_PARAMETER(input_classification)

namespace mrepair {

/// \ingroup mrepair_clean
/// what kind of input a repair treats.
enum class Input_profile {
  automatic,  ///< decided by `classify_input()`
  scan,       ///< dense scan: every RameshCleaner step
  cad         ///< CAD export, print model, small patch: keep the geometry, fix validity, fill holes
};

inline const char* to_string(Input_profile p)
{
  switch (p) {
    case Input_profile::automatic: return "auto";
    case Input_profile::scan: return "scan";
    case Input_profile::cad: return "cad";
  }
  return "unknown";
}

/// parses "auto", "scan" or "cad"; false when unknown.
inline bool parse_input_profile(const std::string& s, Input_profile& out)
{
  if (s == "auto" || s == "automatic") out = Input_profile::automatic;
  else if (s == "scan") out = Input_profile::scan;
  else if (s == "cad") out = Input_profile::cad;
  else return false;
  return true;
}

/// \ingroup mrepair_clean
/// the decision of `classify_input()` and the measures behind it.
struct Input_classification
{
  Input_profile profile = Input_profile::cad;
  bool chosen_by_user = false;      ///< the caller fixed the profile; no measure decided
  std::string reason;               ///< one line a user can read
  std::size_t faces = 0;
  double edge_length_cv = 0;        ///< standard deviation / mean of the edge lengths
  double coplanar_edge_share = 0;   ///< interior edges whose faces are coplanar (< 0.01 degree)
  double skinny_face_share = 0;     ///< triangles with an angle under 5 degrees

  void to_report(Report& r) const
  {
    r.add("profile", to_string(profile));
    r.add("chosen_by", chosen_by_user ? "user" : "auto");
    r.add("reason", reason);
    r.add("faces", faces);
    r.add("edge_length_cv", edge_length_cv);
    r.add("coplanar_edge_share", coplanar_edge_share);
    r.add("skinny_face_share", skinny_face_share);
  }
};

namespace internal {
// The thresholds of the scan rule (doc/guarantees.md, "Input kind").
constexpr std::size_t scan_min_faces = 2000;
constexpr double scan_max_edge_cv = 0.6;
constexpr double scan_max_coplanar_share = 0.2;
constexpr double scan_max_skinny_share = 0.1;
}  // namespace internal

/// \ingroup mrepair_clean
/// classifies a triangle mesh as a dense scan or as a CAD / print / modelled
/// mesh.
///
/// A mesh is a scan when all of these hold:
/// - at least 2000 faces (a scan samples a surface densely; small meshes are
///   patches, parts and test cases whose every face matters);
/// - edge lengths are near-uniform: coefficient of variation at most 0.6
///   (scanner and reconstruction output is sampled at one density; CAD
///   tessellations mix long and short edges, with CVs of 0.8 and more);
/// - at most 20% of the interior edges join coplanar faces (within 0.01
///   degree): measured surfaces are noisy, tessellated planes are exact;
/// - at most 10% of the triangles have an angle under 5 degrees (CAD
///   tessellation fans are full of slivers, scans are not).
///
/// Anything else is `cad`. Non-finite points are skipped.
///
/// \param np optional: `vertex_point_map`, `input_profile` (a value other
///   than `automatic` is returned as chosen by the user, with the measures)
template <typename TriangleMesh,
          typename NamedParameters = CGAL::parameters::Default_named_parameters>
Input_classification classify_input(const TriangleMesh& tm,
                                    const NamedParameters& np = CGAL::parameters::default_values())
{
  namespace SC = internal::clean_pipeline;
  auto vpm = CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, CGAL::internal_np::vertex_point),
      get_const_property_map(CGAL::vertex_point, tm));
  const Input_profile asked =
      internal::get_or(np, internal_np::input_profile, Input_profile::automatic);

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

}  // namespace mrepair

#endif  // MREPAIR_INPUT_PROFILE_H
