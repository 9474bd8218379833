// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Body of the mesh fuzz target (fuzz_mesh.cpp), shared with the regression test.
//   byte 0: bits 0-2 the call (see run_mesh); bit 3 poison one vertex with NaN
//   byte 1: a parameter (tolerance, target size)
//   byte 2: a second parameter (vertex to poison, small knobs)
//   rest:   an encoded soup (fuzz_decode.h), made a mesh by polygon_soup_to_manifold_mesh
// After each call: valid triangle mesh, finite points; a call that reports
// bad input (empty_input, non_finite_input, invalid_mesh, invalid_parameter)
// leaves the mesh untouched.
#ifndef MREPAIR_FUZZ_MESH_H
#define MREPAIR_FUZZ_MESH_H

#include "fuzz_check.h"

#include <mrepair/adaptive_remesh.h>
#include <mrepair/clean_scan_mesh.h>
#include <mrepair/close_gaps.h>
#include <mrepair/stitch_soup.h>

#include <CGAL/boost/graph/copy_face_graph.h>

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace mrepair_fuzz {

namespace MP = mrepair::parameters;

inline bool reports_bad_input(mrepair::Status s)
{
  using mrepair::Status;
  return s == Status::empty_input || s == Status::non_finite_input || s == Status::invalid_mesh ||
         s == Status::invalid_parameter || s == Status::non_manifold_input;
}

/// runs `call` (returning a result with a `status`) and checks the mesh after it.
template <class Call>
std::string checked_call(Surface_mesh& m, const std::string& what, Call call)
{
  const Snapshot<Surface_mesh> before(m);
  const mrepair::Status s = call();
  const std::string w = what + " (status " + mrepair::to_string(s) + ")";
  if (reports_bad_input(s)) {
    if (!before.same(m)) return w + ": mesh changed although the call reported bad input";
    return check_mesh(m, w, true, false);
  }
  return check_mesh(m, w, true);
}

inline double bbox_diagonal(const Surface_mesh& m)
{
  double lo[3] = {0, 0, 0}, hi[3] = {0, 0, 0};
  bool first = true;
  for (auto v : vertices(m)) {
    const Point& p = m.point(v);
    if (!finite(p)) continue;
    for (int d = 0; d < 3; ++d) {
      if (first || p[d] < lo[d]) lo[d] = p[d];
      if (first || p[d] > hi[d]) hi[d] = p[d];
    }
    first = false;
  }
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

inline std::string run_mesh(const std::uint8_t* data, std::size_t size)
{
  Byte_reader in(data, size);
  const std::uint8_t op = in.byte(), p1 = in.byte(), p2 = in.byte();
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  decode_soup(in, pts, polys);
  Surface_mesh m;
  const auto sr = mrepair::polygon_soup_to_manifold_mesh(pts, polys, m, MP::merge_epsilon((p2 & 128) ? 1e-3 : 0.0));
  if (!mrepair::succeeded(sr.status) || faces(m).empty()) return {};
  if (std::string e = check_mesh(m, "polygon_soup_to_manifold_mesh", true); !e.empty()) return e;
  if (op & 8) {  // a NaN vertex: every call must notice it before its first predicate
    auto v = *std::next(vertices(m).begin(), p2 % vertices(m).size());
    const Point q = m.point(v);
    m.point(v) = Point(std::numeric_limits<double>::quiet_NaN(), q.y(), q.z());
  }
  const double diag = bbox_diagonal(m);
  const double frac = (p1 + 1) / 256.0;  // (0, 1]
  auto gaps = [&](double tol, bool relative) {
    return checked_call(m, "close_gaps", [&] {
      return mrepair::close_gaps(m, tol, MP::gap_relative_tolerance(relative, MP::gap_lambda(((p2 >> 1) & 7) / 7.0))).status;
    });
  };
  auto clean = [&] {
    return checked_call(m, "clean_scan_mesh", [&] {
      return mrepair::clean_scan_mesh(m, MP::min_component_faces(std::size_t(p2 % 8),
                                         MP::max_hole_vertices(std::size_t(3 + p1 % 32),
                                         MP::max_clean_iterations(std::size_t(1 + p2 % 3))))).status;
    });
  };
  auto uniform = [&](double L) {
    return checked_call(m, "isotropic_remesh", [&] {
      return mrepair::isotropic_remesh(m, L, CGAL::parameters::number_of_iterations(3)).status;
    });
  };
  switch (op & 7) {
    case 0: return gaps(0.25 * frac, true);
    case 1: return gaps(frac * diag, false);
    case 2: return clean();
    case 3: return uniform(diag * (0.1 + 0.5 * frac));
    case 4:
      return checked_call(m, "adaptive_remesh", [&] {
        // a floor on the edge length keeps the output to a few hundred faces
        return mrepair::adaptive_remesh(m, diag * (0.002 + 0.05 * frac),
                                        MP::remesh_min_edge_length(0.08 * diag,
                                        CGAL::parameters::number_of_iterations(3))).status;
      });
    case 5:
      return checked_call(m, "remesh_to_face_count", [&] {
        return mrepair::remesh_to_face_count(m, std::size_t(4 + p1 % 300),
                                             CGAL::parameters::number_of_iterations(3)).status;
      });
    case 6: {  // the usual sequence
      if (std::string e = gaps(0.05, true); !e.empty()) return e;
      if (std::string e = clean(); !e.empty()) return e;
      return uniform(bbox_diagonal(m) * (0.1 + 0.5 * frac));
    }
    default:
      return checked_call(m, "clean_scan_mesh (defaults)", [&] { return mrepair::clean_scan_mesh(m).status; });
  }
}

} // namespace mrepair_fuzz

#endif // MREPAIR_FUZZ_MESH_H
