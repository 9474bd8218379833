// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_CONVERT_H
#define MREPAIR_INTERNAL_IO_CONVERT_H

// Between the flat soup the readers and writers use and the user's types:
// point and polygon vectors, and polygon meshes (built through the
// manifoldness test of build_mesh.h). Running out of memory is reported in
// the `Io_result`, never thrown.

#include <mrepair/internal/io/build_mesh.h>
#include <mrepair/internal/io/common.h>
#include <mrepair/internal/utility.h>
#include <mrepair/io_result.h>
#include <mrepair/status.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/named_params_helper.h>
#include <CGAL/number_utils.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cstdint>
#include <limits>
#include <new>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace mrepair {
namespace internal {
namespace io {

template <typename Point>
double coordinate(const Point& p, int d)
{
  return CGAL::to_double(d == 0 ? p.x() : (d == 1 ? p.y() : p.z()));
}

/// runs `fill()`; false (and `r` says why) when memory ran out.
template <typename Fill>
bool fill_or_report_oom(const std::string& path, Io_result& r, const Fill& fill)
{
  try {
    fill();
  } catch (const std::bad_alloc&) {
    r.status = Status::io_error;
    r.message = path + ": out of memory";
    return false;
  }
  return true;
}

/// one polygon from `n` raw indices: a resizable container takes them all, a
/// fixed array (std::array<I, N>) its N (the caller checked every polygon has N)
template <class Polygon>
void assign_polygon(Polygon& poly, const std::int64_t* first, std::size_t n)
{
  using Index = typename Polygon::value_type;
  poly.resize(n);
  for (std::size_t k = 0; k < n; ++k) poly[k] = static_cast<Index>(first[k]);
}
template <class I, std::size_t N>
void assign_polygon(std::array<I, N>& poly, const std::int64_t* first, std::size_t)
{
  for (std::size_t k = 0; k < N; ++k) poly[k] = static_cast<I>(first[k]);
}

/// true when every polygon of `raw` has `n` corners
inline bool all_polygons_have(const Raw_soup& raw, std::size_t n)
{
  for (std::size_t f = 0; f < raw.num_polygons(); ++f)
    if (raw.starts[f + 1] - raw.starts[f] != n) return false;
  return true;
}

/// moves what `raw` holds into `points` and `polygons` (empty on entry).
template <class Point, class Polygon>
void raw_to_soup(const std::string& path, Raw_soup& raw, std::vector<Point>& points,
                 std::vector<Polygon>& polygons, Io_result& r)
{
  try {
    points.reserve(raw.num_points());
    for (std::size_t i = 0; i < raw.num_points(); ++i)
      points.emplace_back(raw.xyz[3 * i], raw.xyz[3 * i + 1], raw.xyz[3 * i + 2]);
    raw.xyz = Big_vector<double>();
    polygons.reserve(raw.num_polygons());
    polygons.resize(raw.num_polygons());
    // in parallel: allocating a million small polygons is the cost here, and
    // each thread allocates from its own arena
    std::atomic<bool> out_of_memory{false};
    const std::size_t block = 8192;
    parallel_for_index((raw.num_polygons() + block - 1) / block, 1, [&](std::size_t j) {
      try {
        for (std::size_t f = j * block; f < std::min(raw.num_polygons(), (j + 1) * block); ++f) {
          const std::size_t b = raw.starts[f];
          assign_polygon(polygons[f], &raw.indices[b], raw.starts[f + 1] - b);
        }
      } catch (const std::bad_alloc&) {
        out_of_memory = true;
      }
    });
    if (out_of_memory) throw std::bad_alloc();
  } catch (const std::bad_alloc&) {
    points.clear();
    polygons.clear();
    r = Io_result();
    r.status = Status::io_error;
    r.message = path + ": out of memory";
  }
}

/// the caller's point and polygon vectors as the writers read them (write.h):
/// no intermediate copy. An index that is negative (signed types) or beyond
/// `std::int64_t` (unsigned types) reads as -1, i.e. out of range.
template <class Point, class Polygon>
struct Vectors_view
{
  const std::vector<Point>& points;
  const std::vector<Polygon>& polygons;
  std::size_t num_points() const { return points.size(); }
  std::size_t num_polygons() const { return polygons.size(); }
  void point(std::size_t i, double* c) const
  {
    for (int d = 0; d < 3; ++d) c[d] = coordinate(points[i], d);
  }
  std::size_t degree(std::size_t f) const { return static_cast<std::size_t>(polygons[f].size()); }
  std::int64_t index(std::size_t f, std::size_t k) const
  {
    const auto i = polygons[f][k];
    if (std::is_unsigned<std::decay_t<decltype(i)>>::value &&
        static_cast<std::uint64_t>(i) > static_cast<std::uint64_t>((std::numeric_limits<std::int64_t>::max)()))
      return -1;
    return static_cast<std::int64_t>(i);
  }
  const double* xyz() const { return nullptr; }
  /// parallel formatting only for plain floating-point coordinates (an exact
  /// kernel's lazy numbers may be refined by `to_double`, not thread-safe)
  static constexpr bool parallel =
      std::is_floating_point<std::decay_t<decltype(std::declval<const Point&>().x())>>::value;
};

/// a `Surface_mesh` as the writers read it, with no intermediate copy (a
/// 10M-face mesh's copy is 440 MB and a sequential pass): polygon f has its
/// vertices in the order of `vertices_around_face(halfedge(f))`. Without
/// removed elements point i is vertex i and polygon f face f; with them
/// (`with_gaps`), the kept elements in index order, as `mesh_to_raw` numbers
/// them, through two slot tables and a renumbering of the vertices.
template <class P, class VertexPointMap>
struct Surface_mesh_view
{
  using Mesh = CGAL::Surface_mesh<P>;
  using size_type = typename Mesh::size_type;
  const Mesh& m;
  VertexPointMap vpm;
  std::vector<size_type> vertex_slot, face_slot;  // output index -> mesh index (empty: the same)
  std::vector<size_type> vertex_number;           // mesh vertex index -> output index

  /// the view of a mesh that may have removed elements
  static Surface_mesh_view with_gaps(const Mesh& mesh, VertexPointMap map)
  {
    Surface_mesh_view view{mesh, map, {}, {}, {}};
    if (!mesh.has_garbage()) return view;
    view.vertex_number.assign(mesh.num_vertices(), size_type(-1));
    kept_slots<typename Mesh::Vertex_index>(mesh, mesh.num_vertices(), view.vertex_slot, &view.vertex_number);
    kept_slots<typename Mesh::Face_index>(mesh, mesh.num_faces(), view.face_slot, nullptr);
    return view;
  }
  // the indices of the elements of one kind not removed, in order (and, when
  // `number` is given, each one's position among them): counts per block,
  // then the fill, both in parallel
  template <class Index>
  static void kept_slots(const Mesh& mesh, std::size_t slots, std::vector<size_type>& kept,
                         std::vector<size_type>* number)
  {
    constexpr std::size_t block = std::size_t(1) << 14;
    const std::size_t blocks = (slots + block - 1) / block;
    auto kept_in = [&](std::size_t i) { return !mesh.is_removed(Index(static_cast<size_type>(i))); };
    std::vector<std::size_t> start(blocks + 1, 0);
    parallel_for_index(blocks, 1, [&](std::size_t b) {
      for (std::size_t i = b * block; i < std::min(slots, (b + 1) * block); ++i) start[b + 1] += kept_in(i);
    });
    for (std::size_t b = 0; b < blocks; ++b) start[b + 1] += start[b];
    kept.resize(start[blocks]);
    parallel_for_index(blocks, 1, [&](std::size_t b) {
      std::size_t at = start[b];
      for (std::size_t i = b * block; i < std::min(slots, (b + 1) * block); ++i)
        if (kept_in(i)) {
          if (number) (*number)[i] = static_cast<size_type>(at);
          kept[at++] = static_cast<size_type>(i);
        }
    });
  }
  bool gaps() const { return !vertex_number.empty(); }
  std::size_t num_points() const { return m.number_of_vertices(); }
  std::size_t num_polygons() const { return m.number_of_faces(); }
  void point(std::size_t i, double* c) const
  {
    const size_type slot = gaps() ? vertex_slot[i] : static_cast<size_type>(i);
    const auto& p = get(vpm, typename Mesh::Vertex_index(slot));
    for (int d = 0; d < 3; ++d) c[d] = coordinate(p, d);
  }
  typename Mesh::Face_index face(std::size_t f) const
  {
    return typename Mesh::Face_index(gaps() ? face_slot[f] : static_cast<size_type>(f));
  }
  std::size_t degree(std::size_t f) const { return static_cast<std::size_t>(m.degree(face(f))); }
  std::int64_t index(std::size_t f, std::size_t k) const
  {
    auto h = m.halfedge(face(f));
    for (; k > 0; --k) h = m.next(h);
    const size_type v = static_cast<size_type>(m.target(h));
    return static_cast<std::int64_t>(gaps() ? vertex_number[v] : v);
  }
  const double* xyz() const { return nullptr; }
  /// the mesh's own point map (an array) and plain floating-point coordinates
  static constexpr bool parallel =
      std::is_same<VertexPointMap, typename Mesh::template Property_map<typename Mesh::Vertex_index, P>>::value &&
      std::is_floating_point<std::decay_t<decltype(std::declval<const P&>().x())>>::value;
};

/// copies `pmesh` into `raw`, vertices numbered consecutively in the order of
/// `vertices(pmesh)`; false (and `r` says why) when memory ran out.
template <class PolygonMesh, class VertexPointMap, class NamedParameters>
bool mesh_to_raw(const std::string& path, const PolygonMesh& pmesh, const VertexPointMap& vpm,
                 const NamedParameters& np, Raw_soup& raw, Io_result& r)
{
  return fill_or_report_oom(path, r, [&] {
    // the mesh's own indices may have gaps (Surface_mesh with removed
    // elements): renumber them consecutively in the order of vertices(pmesh)
    auto vim = CGAL::get_initialized_vertex_index_map(pmesh, np);
    std::size_t max_id = 0, nv = 0;
    for (auto v : vertices(pmesh)) {
      max_id = (std::max)(max_id, static_cast<std::size_t>(get(vim, v)));
      ++nv;
    }
    std::vector<std::int64_t> renum(nv ? max_id + 1 : 0, -1);
    raw.xyz.reserve(3 * nv);
    std::int64_t next = 0;
    for (auto v : vertices(pmesh)) {
      renum[static_cast<std::size_t>(get(vim, v))] = next++;
      const auto& p = get(vpm, v);
      for (int d = 0; d < 3; ++d) raw.xyz.push_back(coordinate(p, d));
    }
    raw.starts.reserve(faces(pmesh).size() + 1);
    raw.indices.reserve(3 * faces(pmesh).size());
    for (auto f : faces(pmesh)) {
      for (auto v : CGAL::vertices_around_face(halfedge(f, pmesh), pmesh))
        raw.indices.push_back(renum[static_cast<std::size_t>(get(vim, v))]);
      raw.starts.push_back(raw.indices.size());
    }
  });
}

/// builds `pmesh` (empty on entry) from a checked soup when it is a manifold,
/// consistently oriented polygon mesh; else `r` says why and `pmesh` stays empty.
template <class PolygonMesh, class VertexPointMap>
void raw_to_mesh(const std::string& path, const Raw_soup& raw, PolygonMesh& pmesh,
                 const VertexPointMap& vpm, Io_result& r)
{
  using Point = typename boost::property_traits<VertexPointMap>::value_type;
  try {
    // the same test as PMP::is_polygon_soup_a_polygon_mesh, on flat arrays
    bool is_mesh = true;
    with_soup_topology(raw.num_points(), raw.indices.size(), [&](auto& topology) {
      std::string why;
      if (!topology.compute(raw.num_points(), raw.indices.data(), raw.starts.data(),
                            raw.num_polygons(), why)) {
        r.status = Status::non_manifold_input;
        r.message = path + ": not a manifold, consistently oriented polygon mesh (" + why +
                    "); run `mrepair soup` first";
        is_mesh = false;
        return;
      }
      build_mesh(topology, raw.num_points(), raw.indices.data(), raw.starts.data(),
                 raw.num_polygons(), pmesh, [&](auto v, std::size_t i) {
                   const double* q = &raw.xyz[3 * i];
                   put(vpm, v, Point(q[0], q[1], q[2]));
                 });
    });
    if (!is_mesh) return;
    const std::size_t isolated = r.points - static_cast<std::size_t>(vertices(pmesh).size());
    if (isolated)
      r.message += (r.message.empty() ? path + ": " : std::string("; ")) +
                   std::to_string(isolated) +
                   " point(s) used by no polygon were not added to the mesh";
  } catch (const std::bad_alloc&) {
    CGAL::clear(pmesh);
    r.status = Status::io_error;
    r.message = path + ": out of memory building the mesh";
  }
}

/// true when `polygons` over `num_points` points form a manifold, consistently
/// oriented polygon mesh; `why` receives the reason when not.
template <class PolygonRange>
bool is_soup_a_mesh(const PolygonRange& polygons, std::size_t num_points, std::string& why)
{
  std::vector<std::int64_t> indices;
  std::vector<std::size_t> starts{0};
  starts.reserve(polygons.size() + 1);
  for (const auto& poly : polygons) {
    for (const auto& i : poly) {
      // a negative signed index or one that does not fit stays out of range
      const std::int64_t v = static_cast<std::int64_t>(i);
      indices.push_back(v < 0 || static_cast<std::uint64_t>(i) >= num_points ? -1 : v);
    }
    starts.push_back(indices.size());
  }
  bool is_mesh = false;
  with_soup_topology(num_points, indices.size(), [&](auto& topology) {
    is_mesh = topology.compute(num_points, indices.data(), starts.data(), polygons.size(), why);
  });
  return is_mesh;
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_CONVERT_H
