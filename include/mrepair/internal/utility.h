// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The small tools every algorithm uses, written once: double-precision vector
// helpers on any point type, angle constants, the mesh-type trait that decides
// whether a dynamic property map is an array (safe to write from threads),
// the TBB loop, the coordinate-range guard and a union-find.
#ifndef MREPAIR_INTERNAL_UTILITY_H
#define MREPAIR_INTERNAL_UTILITY_H

#include <mrepair/internal/coordinate_range.h>

#include <CGAL/Polyhedron_3_fwd.h>
#include <CGAL/Surface_mesh/Surface_mesh_fwd.h>
#include <boost/graph/graph_traits.hpp>
#include <CGAL/number_utils.h>
#include <boost/property_map/property_map.hpp>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/parallel_sort.h>
#endif

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstddef>
#include <memory>
#include <numeric>
#include <type_traits>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {

// ---- constants ---------------------------------------------------------------
constexpr double pi = 3.14159265358979323846;
constexpr double two_pi = 2. * pi;
constexpr double radians_per_degree = pi / 180.;
constexpr double degrees_per_radian = 180. / pi;
inline double to_radians(double degrees) { return degrees * radians_per_degree; }
inline double to_degrees(double radians) { return radians * degrees_per_radian; }

// ---- vectors -----------------------------------------------------------------
using Vec3 = std::array<double, 3>;

inline Vec3 sub(const Vec3& a, const Vec3& b) { return {{a[0] - b[0], a[1] - b[1], a[2] - b[2]}}; }
inline Vec3 add(const Vec3& a, const Vec3& b) { return {{a[0] + b[0], a[1] + b[1], a[2] + b[2]}}; }
inline Vec3 mul(const Vec3& a, double s) { return {{a[0] * s, a[1] * s, a[2] * s}}; }
inline Vec3 neg(const Vec3& a) { return {{-a[0], -a[1], -a[2]}}; }
// The same four as operators, for formulas that read better with them (the
// remesher's). Found by ordinary lookup from code inside mrepair::internal.
inline Vec3 operator+(const Vec3& a, const Vec3& b) { return add(a, b); }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return sub(a, b); }
inline Vec3 operator*(const Vec3& a, double s) { return mul(a, s); }
inline Vec3 operator*(double s, const Vec3& a) { return mul(a, s); }
inline Vec3& operator+=(Vec3& a, const Vec3& b) { return a = add(a, b); }
inline Vec3& operator-=(Vec3& a, const Vec3& b) { return a = sub(a, b); }
inline Vec3& operator*=(Vec3& a, double s) { return a = mul(a, s); }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]}};
}
/// the term of edge (p, q) in Newell's normal of a polygon (the sum over its
/// edges: twice its vector area), for polygons that need not be triangles
/// nor planar.
inline Vec3 newell_term(const Vec3& p, const Vec3& q)
{
  return {{(p[1] - q[1]) * (p[2] + q[2]), (p[2] - q[2]) * (p[0] + q[0]), (p[0] - q[0]) * (p[1] + q[1])}};
}
/// the normal of triangle (a, b, c), not normalised (twice its area): the one
/// formula every user shares, with `a` as the corner the two edges leave
/// from (the rounding depends on which corner that is)
inline Vec3 triangle_normal(const Vec3& a, const Vec3& b, const Vec3& c)
{
  return cross(sub(b, a), sub(c, a));
}
inline double squared_norm(const Vec3& a) { return dot(a, a); }
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline double distance(const Vec3& a, const Vec3& b) { return norm(sub(a, b)); }
inline bool is_zero(const Vec3& a) { return a[0] == 0 && a[1] == 0 && a[2] == 0; }
inline bool is_finite(const Vec3& a)
{
  return std::isfinite(a[0]) && std::isfinite(a[1]) && std::isfinite(a[2]);
}
/// `a` scaled to unit length, or the zero vector when `a` has no length.
inline Vec3 normalized(const Vec3& a)
{
  const double n = norm(a);
  return n > 0 && std::isfinite(n) ? mul(a, 1. / n) : Vec3{{0, 0, 0}};
}
/// angle between two vectors in [0, pi]; the atan2 form stays accurate near 0
/// and pi, where acos of a dot product loses half its digits. 0 if one is zero.
inline double angle(const Vec3& a, const Vec3& b) { return std::atan2(norm(cross(a, b)), dot(a, b)); }

/// three doubles in a row (flat coordinate arrays) as a vector.
inline Vec3 load_vec3(const double* p) { return {{p[0], p[1], p[2]}}; }

/// squared distance from `p` to the triangle a-b-c (its closest point found by
/// the Voronoi region of `p`: a corner, an edge, or the inside). A degenerate
/// triangle gives the distance to its nearest edge.
inline double squared_distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c)
{
  auto to_segment = [&](const Vec3& s, const Vec3& t) {
    const Vec3 st = sub(t, s);
    const double l2 = dot(st, st);
    const double u = l2 > 0 ? std::clamp(dot(sub(p, s), st) / l2, 0., 1.) : 0.;
    return squared_norm(sub(p, add(s, mul(st, u))));
  };
  const Vec3 n = triangle_normal(a, b, c);
  const double n2 = dot(n, n);
  if (n2 > 0) {
    // inside the prism over the triangle: the distance to its plane
    const bool inside = dot(cross(sub(b, a), sub(p, a)), n) >= 0 && dot(cross(sub(c, b), sub(p, b)), n) >= 0 &&
                        dot(cross(sub(a, c), sub(p, c)), n) >= 0;
    if (inside) {
      const double h = dot(sub(p, a), n);
      return h * h / n2;
    }
  }
  return std::min({to_segment(a, b), to_segment(b, c), to_segment(c, a)});
}

/// any point type with x(), y(), z() (any kernel, exact ones included) in doubles.
template <typename Point>
Vec3 to_vec3(const Point& p)
{
  return {{CGAL::to_double(p.x()), CGAL::to_double(p.y()), CGAL::to_double(p.z())}};
}

/// the point of `v` in doubles.
template <typename VertexPointMap, typename Vertex>
Vec3 point(const VertexPointMap& vpm, Vertex v)
{
  return to_vec3(get(vpm, v));
}

/// stores `q` as the point of `v`, in the map's own point type.
template <typename VertexPointMap, typename Vertex>
void set_point(const VertexPointMap& vpm, Vertex v, const Vec3& q)
{
  using Point = typename boost::property_traits<VertexPointMap>::value_type;
  put(vpm, v, Point(q[0], q[1], q[2]));
}

template <typename VertexPointMap, typename Vertex>
bool is_finite_point(const VertexPointMap& vpm, Vertex v)
{
  return is_finite(point(vpm, v));
}

// ---- mesh types --------------------------------------------------------------
/// true for `CGAL::Surface_mesh`: its dynamic property maps are arrays, which
/// threads may write at distinct indices. `Polyhedron_3`'s are hash maps.
template <typename T> struct Is_surface_mesh : std::false_type {};
template <typename P> struct Is_surface_mesh<CGAL::Surface_mesh<P>> : std::true_type {};
/// true for `CGAL::Polyhedron_3`.
template <typename T> struct Is_polyhedron : std::false_type {};
template <typename T, typename I, template <class, class, class> class H, typename A>
struct Is_polyhedron<CGAL::Polyhedron_3<T, I, H, A>> : std::true_type {};

/// the number of faces (vertices, halfedges) of a mesh, in O(1) on Surface_mesh and
/// Polyhedron_3. `faces(m).size()` walks the whole range (std::distance),
/// and BGL's `num_faces()` counts a Surface_mesh's removed faces too:
/// a local operation that asked for the count paid O(mesh) per call.
template <typename Mesh>
std::size_t face_count(const Mesh& m)
{
  if constexpr (Is_surface_mesh<Mesh>::value)
    return static_cast<std::size_t>(m.number_of_faces());
  else if constexpr (Is_polyhedron<Mesh>::value)
    return static_cast<std::size_t>(m.size_of_facets());
  else
    return static_cast<std::size_t>(faces(m).size());
}
template <typename Mesh>
std::size_t vertex_count(const Mesh& m)
{
  if constexpr (Is_surface_mesh<Mesh>::value)
    return static_cast<std::size_t>(m.number_of_vertices());
  else if constexpr (Is_polyhedron<Mesh>::value)
    return static_cast<std::size_t>(m.size_of_vertices());
  else
    return static_cast<std::size_t>(vertices(m).size());
}
template <typename Mesh>
std::size_t halfedge_count(const Mesh& m)
{
  if constexpr (Is_surface_mesh<Mesh>::value)
    return static_cast<std::size_t>(m.number_of_halfedges());
  else if constexpr (Is_polyhedron<Mesh>::value)
    return static_cast<std::size_t>(m.size_of_halfedges());
  else
    return static_cast<std::size_t>(halfedges(m).size());
}

/// true when `v` was removed from `m`: only `Surface_mesh` keeps removed
/// elements addressable (marked, until garbage collection), so this is
/// false on other meshes, where callers must not hold removed descriptors.
template <typename Mesh>
bool is_removed_vertex(const Mesh& m, typename boost::graph_traits<Mesh>::vertex_descriptor v)
{
  if constexpr (Is_surface_mesh<Mesh>::value)
    return m.is_removed(v);
  else
    return false;
}

// ---- parallel loops ----------------------------------------------------------
/// calls f(i) for i in [0, n), with TBB when it is linked and the range holds
/// more than one grain.
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
#else
  (void)grain;  // one thread: no grains
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

// Calls f(index, acc) for every index slot of one element kind of a
// Surface_mesh, removed ones included (`Index` is one of its index types,
// `slots` their number with the removed): in chunks, possibly in parallel,
// each chunk with its own accumulator, returned in index order.
template <typename Index, typename Acc, typename SurfaceMesh, typename F>
std::vector<Acc> chunked_over_slots(const SurfaceMesh&, std::size_t slots, const F& f)
{
  using size_type = typename SurfaceMesh::size_type;
  return chunked<Acc>(slots, [&](std::size_t b, std::size_t e, Acc& acc) {
    for (std::size_t i = b; i < e; ++i) f(Index(static_cast<size_type>(i)), acc);
  });
}

// The border halfedges of `pm` in the order of `halfedges(pm)`. Steps look
// for them on every run, also when there are none (the cleaning's last
// iterations): on Surface_mesh the index range is scanned in chunks, in
// parallel (30M halfedges on a 10M-face scan), the same list in the same order.
template <typename PM>
void border_halfedges(const PM& pm, std::vector<typename boost::graph_traits<PM>::halfedge_descriptor>& out)
{
  out.clear();
  if constexpr (Is_surface_mesh<PM>::value) {
    using H = typename PM::Halfedge_index;
    const std::size_t slots = pm.number_of_halfedges() + pm.number_of_removed_halfedges();
    auto parts = chunked_over_slots<H, std::vector<H>>(pm, slots, [&](H h, std::vector<H>& part) {
      if (!pm.is_removed(h) && pm.is_border(h)) part.push_back(h);
    });
    for (const std::vector<H>& part : parts) out.insert(out.end(), part.begin(), part.end());
  } else {
    for (auto h : halfedges(pm))
      if (is_border(h, pm)) out.push_back(h);
  }
}

/// sorts [first, last) with TBB when there is one. `less` must be a strict
/// total order on the values that can occur (ties would go either way,
/// depending on the threads).
template <typename RandomIt, typename Less>
void parallel_sort(RandomIt first, RandomIt last, const Less& less)
{
#ifdef CGAL_LINKED_WITH_TBB
  tbb::parallel_sort(first, last, less);
#else
  std::sort(first, last, less);
#endif
}

/// the same loop over work that writes a dynamic property map of `Mesh`: in
/// parallel only where those maps are arrays, and only past 20,000 items,
/// below which the threads cost more than they save.
template <typename Mesh, typename F>
void parallel_for_mesh_elements(std::size_t n, const F& f, bool allowed = true)
{
  if (allowed && Is_surface_mesh<Mesh>::value && n > 20000)
    parallel_for_index(n, 4096, f);
  else
    for (std::size_t i = 0; i < n; ++i) f(i);
}

// ---- buffers filled in parallel ------------------------------------------------
/// an allocator whose `construct()` without arguments default-initialises:
/// `resize(n)` of a vector of trivial values then writes nothing. A large
/// array that a parallel loop fills anyway is otherwise zeroed first, on one
/// thread, which at 10M faces is also where all its pages fault in; left
/// alone, they fault in on the threads that fill them.
template <typename T, typename Base = std::allocator<T>>
class Default_init_allocator : public Base
{
  using Traits = std::allocator_traits<Base>;

public:
  template <typename U>
  struct rebind
  {
    using other = Default_init_allocator<U, typename Traits::template rebind_alloc<U>>;
  };
  using Base::Base;
  Default_init_allocator() = default;
  template <typename U, typename B>
  Default_init_allocator(const Default_init_allocator<U, B>& other) : Base(other) {}

  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    Traits::construct(static_cast<Base&>(*this), p, std::forward<Args>(args)...);
  }
};

/// a vector whose `resize(n)` leaves trivial values unwritten: for arrays that
/// are filled in full, in parallel, right after (see above).
template <typename T>
using Parallel_filled_vector = std::vector<T, Default_init_allocator<T>>;

// ---- union-find --------------------------------------------------------------
/// disjoint sets over [0, n), with path halving; the smaller index is the root,
/// so that roots do not depend on the order of the unions.
template <typename Index = std::size_t>
class Union_find
{
public:
  explicit Union_find(std::size_t n = 0) { reset(n); }
  void reset(std::size_t n)
  {
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), Index(0));
  }
  std::size_t size() const { return parent_.size(); }
  Index find(Index x)
  {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  /// joins the sets of x and y; true when they were apart.
  bool unite(Index x, Index y)
  {
    x = find(x);
    y = find(y);
    if (x == y) return false;
    if (x < y) std::swap(x, y);
    parent_[x] = y;
    return true;
  }

private:
  std::vector<Index> parent_;
};

/// wall seconds since construction or the last `restart()`: the "seconds"
/// of the reports.
class Stopwatch
{
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();

public:
  double seconds() const
  {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
  }
  void restart() { start_ = std::chrono::steady_clock::now(); }
};

/// empties containers and gives their memory back (`clear()` keeps the capacity).
template <typename... Containers>
void free_memory(Containers&... c)
{
  (Containers().swap(c), ...);
}

// Hole filling adds elements once the cleaning's statistics and marks
// exist; on Surface_mesh an addition beyond the capacity copies every
// property array. The cleaning reserves this room (12.5% of the faces) before
// any of them exists, and the soup builder reserves it from the start, so
// that a soup repaired and then cleaned is never copied for it (unused
// capacity is only address space).
struct Element_counts
{
  std::size_t vertices, edges, faces;
};
inline Element_counts with_room_for_fills(std::size_t nv, std::size_t ne, std::size_t nf)
{
  const std::size_t room = nf / 8 + 4096;
  return Element_counts{nv + room / 2, ne + 3 * room / 2, nf + room};
}

}  // namespace internal
}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_UTILITY_H
