// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Worker of compare_to_reference(): the distance of each reference point to
// the output surface (an AABB tree of its triangles), then, for the points
// farther than the tolerance, the winding number of the closed components of
// the output around them (a ray cast, exact predicates). Both loops run over
// the points in parallel with TBB when the concurrency tag allows it: the
// trees are built before and only read inside the loops.
#ifndef MREPAIR_INTERNAL_COMPARE_TO_REFERENCE_WORKER_H
#define MREPAIR_INTERNAL_COMPARE_TO_REFERENCE_WORKER_H

#include <mrepair/internal/clean_scan_mesh/safety.h>
#include <mrepair/internal/utility.h>
#include <mrepair/reference_comparison.h>

#include <CGAL/Bbox_3.h>
#include <CGAL/Side_of_triangle_mesh.h>
#include <CGAL/Kernel/global_functions.h>
#include <CGAL/Kernel_traits.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/tags.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <iterator>
#include <limits>
#include <type_traits>
#include <vector>

namespace mrepair {
namespace internal {

/// calls f(i) for i in [0, n): in parallel when `ConcurrencyTag` allows it
/// and TBB is linked, else in order.
template <typename ConcurrencyTag, typename F>
void for_each_reference_point(std::size_t n, const F& f)
{
  if constexpr (std::is_same<ConcurrencyTag, CGAL::Sequential_tag>::value) {
    for (std::size_t i = 0; i < n; ++i) f(i);
  } else {
    parallel_for_index(n, 256, f);
  }
}

/// the bounding-box diagonal of the finite points `p[i]` (`finite[i]`).
template <typename Point>
double diagonal_of(const std::vector<Point>& p, const std::vector<char>& finite)
{
  double lo[3] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                  std::numeric_limits<double>::infinity()};
  double hi[3] = {-lo[0], -lo[1], -lo[2]};
  bool any = false;
  for (std::size_t i = 0; i < p.size(); ++i) {
    if (!finite[i]) continue;
    any = true;
    const double c[3] = {CGAL::to_double(p[i].x()), CGAL::to_double(p[i].y()), CGAL::to_double(p[i].z())};
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min(lo[k], c[k]);
      hi[k] = std::max(hi[k], c[k]);
    }
  }
  if (!any) return 0.;
  return std::sqrt((hi[0] - lo[0]) * (hi[0] - lo[0]) + (hi[1] - lo[1]) * (hi[1] - lo[1]) +
                   (hi[2] - lo[2]) * (hi[2] - lo[2]));
}

/// The winding number around `p` of the faces in `tree` (closed components
/// of `tm`): the signed count of the faces a ray from `p` crosses, +1 where it
/// leaves through the side the face's normal points to. Exact predicates
/// decide every crossing; a ray that meets an edge or a vertex, or a face
/// whose plane holds `p`, is not trusted and the next of a fixed list of
/// directions is tried. Returns false when none gives a clean count (then
/// `p` lies on the surface or on a plane through its faces in every
/// direction tried: the caller counts it as on the output).
template <typename Tree, typename TriangleMesh, typename VPM, typename Point>
bool winding_number(const Tree& tree, const TriangleMesh& tm, const VPM& vpm, const Point& p,
                    double reach, int& winding)
{
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  using Kernel = typename CGAL::Kernel_traits<Point>::Kernel;
  // no axis, no simple ratio: CAD models are full of axis-aligned and 45-degree faces
  static const double directions[][3] = {{1., 0.3183098862, 0.1414213562},  {-0.2718281828, 1., 0.5772156649},
                                         {0.6180339887, -0.4142135624, 1.}, {-1., -0.7320508076, 0.2360679775},
                                         {0.1234567891, 0.9876543211, -1.}, {0.5, -1., -0.3819660113}};
  std::vector<face_descriptor> crossed;
  for (const auto& d : directions) {
    const Point q(p.x() + reach * d[0], p.y() + reach * d[1], p.z() + reach * d[2]);
    if (q == p) return false;
    crossed.clear();
    tree.all_intersected_primitives(typename Kernel::Ray_3(p, q), std::back_inserter(crossed));
    int w = 0;
    bool clean = true;
    for (face_descriptor f : crossed) {
      const auto h = halfedge(f, tm);
      const Point a = get(vpm, source(h, tm)), b = get(vpm, target(h, tm)),
                  c = get(vpm, target(next(h, tm), tm));
      const CGAL::Orientation side = CGAL::orientation(a, b, c, p);
      if (side == CGAL::COPLANAR || CGAL::orientation(p, q, a, b) == CGAL::COPLANAR ||
          CGAL::orientation(p, q, b, c) == CGAL::COPLANAR || CGAL::orientation(p, q, c, a) == CGAL::COPLANAR) {
        clean = false;
        break;
      }
      w += side == CGAL::NEGATIVE ? 1 : -1;  // p behind the face: the ray leaves through its front
    }
    if (clean) {
      winding = w;
      return true;
    }
  }
  return false;
}

inline double output_diagonal(const CGAL::Bbox_3& b)
{
  return std::sqrt((b.xmax() - b.xmin()) * (b.xmax() - b.xmin()) + (b.ymax() - b.ymin()) * (b.ymax() - b.ymin()) +
                   (b.zmax() - b.zmin()) * (b.zmax() - b.zmin()));
}

/// fills `r` for the reference points `ref` (their finiteness in `finite`)
/// against the triangle mesh `tm` (checked by the caller: triangles, finite
/// points, at least one face). `tolerance` < 0: 1e-6 x the diagonal.
template <typename ConcurrencyTag, typename Point, typename TriangleMesh, typename VPM, typename GT>
void compare_points_to_mesh(const std::vector<Point>& ref, const std::vector<char>& finite,
                            const TriangleMesh& tm, const VPM& vpm, const GT& /* the tree's traits */, double tolerance,
                            Reference_comparison& r)
{
  using face_descriptor = typename boost::graph_traits<TriangleMesh>::face_descriptor;
  // the tree type of CGAL's inside test: the same name on CGAL 5.5 and 6
  using Tree = typename CGAL::Side_of_triangle_mesh<TriangleMesh, GT, VPM>::AABB_tree;
  const std::size_t n = ref.size();
  std::vector<face_descriptor> all_faces(faces(tm).begin(), faces(tm).end());
  Tree tree(all_faces.begin(), all_faces.end(), tm, vpm);
  tree.build();
  tree.accelerate_distance_queries();

  // distance of every finite point (NaN for the others)
  std::vector<double> distance(n, std::numeric_limits<double>::quiet_NaN());
  for_each_reference_point<ConcurrencyTag>(n, [&](std::size_t i) {
    if (finite[i]) distance[i] = std::sqrt(CGAL::to_double(tree.squared_distance(ref[i])));
  });
  std::vector<std::size_t> far;
  for (std::size_t i = 0; i < n; ++i) {
    if (!finite[i]) continue;
    r.max_distance = std::max(r.max_distance, distance[i]);
    if (!(distance[i] <= tolerance)) far.push_back(i);
  }
  r.max_distance_relative = r.diagonal > 0. ? r.max_distance / r.diagonal : 0.;
  // The closed components bound the output's volume: a far point around
  // which they wind (non-zero winding number) is inside the output (absorbed
  // by a union), not lost. The winding number, not the parity of crossings:
  // inside two shells that overlap is inside; in a cavity (an inward shell
  // within an outward one) is outside.
  auto id = get(CGAL::dynamic_face_property_t<std::size_t>(), tm);
  std::vector<std::size_t> faces_of;
  std::vector<double> area_of;
  clean_pipeline::label_components(tm, vpm, id, faces_of, area_of);
  std::vector<char> open(faces_of.size(), 0);
  for (auto h : halfedges(tm))
    if (is_border(h, tm)) open[get(id, face(opposite(h, tm), tm))] = 1;
  std::vector<face_descriptor> closed_faces;
  for (face_descriptor f : all_faces)
    if (!open[get(id, f)]) closed_faces.push_back(f);
  r.inside_tested = !closed_faces.empty();
  std::vector<char> inside(far.size(), 0);
  if (r.inside_tested && !far.empty()) {
    // the whole tree when every component is closed, else one of the closed ones
    const bool all_closed = closed_faces.size() == all_faces.size();
    Tree closed_tree;
    if (!all_closed) {
      closed_tree.insert(closed_faces.begin(), closed_faces.end(), tm, vpm);
      closed_tree.build();
    }
    const Tree& closed = all_closed ? tree : closed_tree;
    const double reach = 2. * (r.diagonal + output_diagonal(closed.bbox()));  // past the output
    for_each_reference_point<ConcurrencyTag>(far.size(), [&](std::size_t k) {
      int winding = 0;
      inside[k] = !winding_number(closed, tm, vpm, ref[far[k]], reach, winding) || winding != 0;
    });
  }
  for (std::size_t k = 0; k < far.size(); ++k) {
    if (inside[k])
      ++r.vertices_inside;
    else
      r.lost.push_back(far[k]);
  }
  r.vertices_lost = r.lost.size();
}

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_COMPARE_TO_REFERENCE_WORKER_H
