// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Local operations shared by the scan-cleaning steps (small components,
// boundary cleaning, hole filling, the pipeline): double-precision geometry on
// any vertex point map, and face removal that never leaves a pinched
// (non-manifold) vertex behind.
#ifndef MREPAIR_INTERNAL_CLEAN_SCAN_MESH_MESH_OPS_H
#define MREPAIR_INTERNAL_CLEAN_SCAN_MESH_MESH_OPS_H

#include <CGAL/boost/graph/Euler_operations.h>
#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>
#include <CGAL/Named_function_parameters.h>

#include <mrepair/parameters.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <vector>

// Internal hook (not for users): a pointer to an object with
// `before(vertex_range)` / `after(vertex_range)` called around every edit of
// the scan-cleaning steps, so that the pipeline keeps its geometric
// statistics current instead of recomputing them (see clean_scan_mesh.h).
MREPAIR_ADD_NAMED_PARAMETER(clean_edit_observer)

namespace mrepair {
namespace internal {
namespace clean_pipeline {

/// the default edit observer: does nothing.
struct No_edit_observer
{
  template <typename R> void before(const R&) {}
  template <typename R> void after(const R&) {}
};

/// the edit observer of a pack (a pointer), or a no-op one.
template <typename NP>
auto edit_observer(const NP& np)
{
  static No_edit_observer none;
  return CGAL::parameters::choose_parameter(
      CGAL::parameters::get_parameter(np, internal_np::clean_edit_observer), &none);
}

using Vec3 = std::array<double, 3>;

inline Vec3 sub(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 add(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 mul(const Vec3& a, double s) { return {a[0] * s, a[1] * s, a[2] * s}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }

template <typename VPM, typename V>
Vec3 point(const VPM& vpm, V v)
{
  const auto& p = get(vpm, v);
  return {CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())};
}

template <typename VPM, typename V>
void set_point(const VPM& vpm, V v, const Vec3& q)
{
  using P = typename boost::property_traits<VPM>::value_type;
  put(vpm, v, P(q[0], q[1], q[2]));
}

template <typename VPM, typename V>
bool is_finite_point(const VPM& vpm, V v)
{
  Vec3 p = point(vpm, v);
  return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
}

// Non-normalised normal (twice the area) of the polygon of halfedge `h`'s face
// (Newell's method, so it also works on quads).
template <typename PM, typename VPM>
Vec3 face_normal(typename boost::graph_traits<PM>::halfedge_descriptor h, const PM& pm,
                 const VPM& vpm)
{
  Vec3 n{0, 0, 0};
  for (auto hh : CGAL::halfedges_around_face(h, pm)) {
    Vec3 a = point(vpm, source(hh, pm)), b = point(vpm, target(hh, pm));
    n[0] += (a[1] - b[1]) * (a[2] + b[2]);
    n[1] += (a[2] - b[2]) * (a[0] + b[0]);
    n[2] += (a[0] - b[0]) * (a[1] + b[1]);
  }
  return n;
}

// Dihedral angle in degrees of the edge of `h`, measured as the angle between
// the two face normals (0 = flat, 180 = folded back onto itself). 0 on a
// border edge; 180 when a face is degenerate (undefined normal: treat as bad).
template <typename PM, typename VPM>
double dihedral_angle_deg(typename boost::graph_traits<PM>::halfedge_descriptor h, const PM& pm,
                          const VPM& vpm)
{
  if (is_border_edge(h, pm)) return 0.;
  Vec3 n1 = face_normal(h, pm, vpm), n2 = face_normal(opposite(h, pm), pm, vpm);
  double l1 = norm(n1), l2 = norm(n2);
  if (!(l1 > 0.) || !(l2 > 0.)) return 180.;
  double c = dot(n1, n2) / (l1 * l2);
  c = std::max(-1., std::min(1., c));
  return std::acos(c) * 180. / 3.14159265358979323846;
}

// True when a halfedge around `v` is a border halfedge (works on both
// Surface_mesh and Polyhedron whatever halfedge(v) is).
template <typename PM>
bool is_border_vertex(typename boost::graph_traits<PM>::vertex_descriptor v, const PM& pm)
{
  for (auto h : CGAL::halfedges_around_target(halfedge(v, pm), pm))
    if (is_border(h, pm)) return true;
  return false;
}

/// Removes a set of faces so that no pinched vertex is left.
///
/// `mark` is a face property of char, zero on every face on entry and on
/// exit; it is used as scratch (2 = to remove).
/// Before anything is removed, every vertex of a marked face is inspected: if
/// the faces it keeps split into several fans (its neighbourhood would no
/// longer be a disk or half-disk, which a halfedge structure cannot hold), all
/// fans but the largest are marked too, and their vertices inspected in turn.
/// Then the faces are removed with `CGAL::Euler::remove_face`, which drops
/// edges and vertices left without faces.
///
/// `survivors` receives the vertices of removed faces that keep a face (the
/// new boundary vertices), read before removal so that no handle of a removed
/// element is ever touched (Polyhedron_3 frees them).
///
/// Returns the number of faces removed; `extra` is increased by the faces
/// added to resolve pinches.
template <typename PM, typename FaceMark, typename Observer = No_edit_observer>
std::size_t remove_faces_without_pinches(
    PM& pm, std::vector<typename boost::graph_traits<PM>::face_descriptor>& to_remove,
    FaceMark& mark, std::size_t& extra,
    std::vector<typename boost::graph_traits<PM>::vertex_descriptor>* survivors_out = nullptr,
    Observer* observer = nullptr)
{
  using GT = boost::graph_traits<PM>;
  using vertex_descriptor = typename GT::vertex_descriptor;
  using halfedge_descriptor = typename GT::halfedge_descriptor;
  using face_descriptor = typename GT::face_descriptor;

  // Deduplicate the input against the mark (callers may list a face twice).
  {
    std::vector<face_descriptor> uniq;
    uniq.reserve(to_remove.size());
    for (face_descriptor f : to_remove)
      if (get(mark, f) != 2) {
        put(mark, f, char(2));
        uniq.push_back(f);
      }
    to_remove.swap(uniq);
  }

  std::vector<vertex_descriptor> work;
  for (face_descriptor f : to_remove)
    for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm), pm)) work.push_back(v);

  std::vector<vertex_descriptor> local_survivors;
  std::vector<vertex_descriptor>* survivors =
      survivors_out ? survivors_out : (observer ? &local_survivors : nullptr);
  const std::size_t survivors_start = survivors ? survivors->size() : 0;
  std::vector<face_descriptor> ring;   // faces around a vertex, null = border
  std::vector<int> run_of;             // run index of each ring slot, -1 = gap
  std::vector<vertex_descriptor> checked;
  while (!work.empty()) {
    vertex_descriptor v = work.back();
    work.pop_back();
    ring.clear();
    for (halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, pm), pm))
      ring.push_back(is_border(h, pm) ? GT::null_face() : face(h, pm));
    const std::size_t n = ring.size();
    auto kept = [&](std::size_t i) {
      return ring[i] != GT::null_face() && get(mark, ring[i]) != 2;
    };
    std::size_t start = n;  // a gap slot to start the cyclic scan from
    for (std::size_t i = 0; i < n; ++i)
      if (!kept(i)) { start = i; break; }
    if (start == n) continue;  // all faces kept: untouched
    run_of.assign(n, -1);
    std::vector<std::size_t> run_size;
    for (std::size_t k = 1; k <= n; ++k) {
      std::size_t i = (start + k) % n;
      if (!kept(i)) continue;
      std::size_t prev = (i + n - 1) % n;
      if (run_of[prev] < 0) run_size.push_back(0);
      run_of[i] = int(run_size.size()) - 1;
      ++run_size.back();
    }
    if (run_size.size() <= 1) {
      if (survivors && run_size.size() == 1) checked.push_back(v);
      continue;
    }
    // Pinch: keep the largest fan, remove the others.
    std::size_t best = std::max_element(run_size.begin(), run_size.end()) - run_size.begin();
    for (std::size_t i = 0; i < n; ++i)
      if (run_of[i] >= 0 && std::size_t(run_of[i]) != best) {
        face_descriptor f = ring[i];
        put(mark, f, char(2));
        to_remove.push_back(f);
        ++extra;
        for (vertex_descriptor w : CGAL::vertices_around_face(halfedge(f, pm), pm))
          work.push_back(w);
      }
    work.push_back(v);  // re-check (now a single fan)
  }

  if (survivors) {
    // A vertex checked early may have lost its last fan later: re-test.
    std::sort(checked.begin(), checked.end());
    checked.erase(std::unique(checked.begin(), checked.end()), checked.end());
    for (vertex_descriptor v : checked) {
      bool keeps = false;
      for (halfedge_descriptor h : CGAL::halfedges_around_target(halfedge(v, pm), pm))
        if (!is_border(h, pm) && get(mark, face(h, pm)) != 2) { keeps = true; break; }
      if (keeps) survivors->push_back(v);
    }
  }

  if (observer) {
    std::vector<vertex_descriptor> touched;
    for (face_descriptor f : to_remove)
      for (vertex_descriptor v : CGAL::vertices_around_face(halfedge(f, pm), pm))
        touched.push_back(v);
    std::sort(touched.begin(), touched.end());
    touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
    observer->before(touched);
  }
  // Leave the mark all-zero, so that slots recycled by later face creations
  // (Surface_mesh) or reused addresses (Polyhedron_3) carry no stale mark.
  for (face_descriptor f : to_remove) put(mark, f, char(0));
  for (face_descriptor f : to_remove) CGAL::Euler::remove_face(halfedge(f, pm), pm);
  if (observer)
    observer->after(std::vector<vertex_descriptor>(survivors->begin() + survivors_start,
                                                   survivors->end()));
  return to_remove.size();
}

}  // namespace clean_pipeline
}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLEAN_SCAN_MESH_MESH_OPS_H
