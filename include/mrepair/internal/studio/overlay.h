// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_STUDIO_OVERLAY_H
#define MREPAIR_INTERNAL_STUDIO_OVERLAY_H

// What the studio and the HTML report draw (doc/studio.md): the defects of a
// `Defect_locations` as coloured points, segments and triangles (the
// "defect overlay"), and a preview of a mesh, decimated by vertex clustering
// above a face budget. Shared by the CLI (`--html`) and the Python module.

#include <mrepair/defect_locations.h>
#include <mrepair/internal/inspect/surface_arrays.h>
#include <mrepair/internal/utility.h>

#include <CGAL/boost/graph/helpers.h>
#include <CGAL/boost/graph/iterator.h>
#include <CGAL/boost/graph/properties.h>
#include <CGAL/number_utils.h>

#include <boost/graph/graph_traits.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <iterator>
#include <string>
#include <type_traits>
#include <unordered_map>
#include <vector>

namespace mrepair {
namespace internal {

// Positions and faces numbered as `Defect_locations` numbers them.
struct Indexed_faces
{
  std::vector<double> xyz;                    // 3 per vertex
  std::vector<std::size_t> face_off{0};       // face f: corners[face_off[f] .. face_off[f+1])
  std::vector<std::size_t> corners;
  std::size_t num_vertices() const { return xyz.size() / 3; }
  std::size_t num_faces() const { return face_off.size() - 1; }
  std::size_t triangles(std::size_t f) const { return face_off[f + 1] - face_off[f] - 2; }
};

// A soup: the polygons inspect_polygon_soup() keeps (at least 3 indices, all
// in range), in order.
template <typename PointRange, typename PolygonRange>
Indexed_faces indexed_faces_of_soup(const PointRange& points, const PolygonRange& polygons)
{
  Indexed_faces m;
  const std::size_t nv = static_cast<std::size_t>(std::distance(std::begin(points), std::end(points)));
  m.xyz.reserve(3 * nv);
  for (const auto& p : points) {
    m.xyz.push_back(CGAL::to_double(p.x()));
    m.xyz.push_back(CGAL::to_double(p.y()));
    m.xyz.push_back(CGAL::to_double(p.z()));
  }
  for (const auto& poly : polygons) {
    if (!is_kept_soup_polygon(poly, nv)) continue;
    for (const auto& idx : poly) m.corners.push_back(static_cast<std::size_t>(idx));
    m.face_off.push_back(m.corners.size());
  }
  return m;
}

// A FaceGraph: vertices and faces in the order of vertices(pm) and faces(pm).
template <typename PolygonMesh>
Indexed_faces indexed_faces_of_mesh(const PolygonMesh& pm)
{
  Indexed_faces m;
  auto vpm = get(CGAL::vertex_point, pm);
  auto vim = CGAL::get_initialized_vertex_index_map(pm);
  std::vector<std::size_t> id;
  std::size_t n = 0;
  for (auto v : vertices(pm)) {
    const std::size_t i = static_cast<std::size_t>(get(vim, v));
    if (i >= id.size()) id.resize(i + 1, 0);
    id[i] = n++;
    const auto& p = get(vpm, v);
    m.xyz.push_back(CGAL::to_double(p.x()));
    m.xyz.push_back(CGAL::to_double(p.y()));
    m.xyz.push_back(CGAL::to_double(p.z()));
  }
  for (auto f : faces(pm)) {
    for (auto v : CGAL::vertices_around_face(halfedge(f, pm), pm))
      m.corners.push_back(id[static_cast<std::size_t>(get(vim, v))]);
    m.face_off.push_back(m.corners.size());
  }
  return m;
}

// ---- defect overlay ------------------------------------------------------------------

// one kind of defect, drawn (doc/studio.md, "geometry form")
struct Overlay_kind
{
  std::string key, label, color;
  std::size_t count = 0;  // the report's count
  std::vector<float> points, segments, triangles;  // 3, 6, 9 floats per element
  bool has_first = false;
  std::array<double, 3> first{{0, 0, 0}};
  double first_radius = 0;
  std::size_t drawn = 0;  // instances drawn
  bool truncated = false;
};

struct Defect_overlay
{
  std::vector<Overlay_kind> kinds;  // in the order of overlay_kind_table()
};

struct Overlay_kind_info
{
  const char* key;
  const char* label;
  const char* color;
};

// the kinds, in the order of the contract
inline const std::array<Overlay_kind_info, 9>& overlay_kind_table()
{
  static const std::array<Overlay_kind_info, 9> table = {{
      {"boundary_loops", "boundary loops", "#1f77b4"},
      {"small_holes", "small holes", "#17becf"},
      {"non_manifold_edges", "non-manifold edges", "#d62728"},
      {"non_manifold_vertices", "non-manifold vertices", "#ff7f0e"},
      {"spikes", "spiked vertices", "#e377c2"},
      {"near_degenerate_faces", "near-degenerate faces", "#bcbd22"},
      {"small_components", "small components", "#9467bd"},
      {"crossing_pairs", "crossing triangle pairs", "#ff0000"},
      {"t_junctions", "T-junctions", "#2ca02c"},
  }};
  return table;
}

// Draws one kind: instances in list order while the elements (points,
// segments and triangles together) fit in `max_elements`.
class Overlay_drawer
{
  const Indexed_faces& m_;
  std::size_t max_elements_;
  double min_radius_;
  Overlay_kind& k_;
  std::size_t elements_ = 0;
  // the instance being drawn
  std::vector<float> pts_, segs_, tris_;

  void put(std::vector<float>& out, std::size_t v) const
  {
    for (int i = 0; i < 3; ++i) out.push_back(static_cast<float>(m_.xyz[3 * v + i]));
  }

public:
  Overlay_drawer(const Indexed_faces& m, std::size_t max_elements, double min_radius, Overlay_kind& k)
    : m_(m), max_elements_(max_elements), min_radius_(min_radius), k_(k)
  {}

  void point(std::size_t v) { put(pts_, v); }
  void segment(std::size_t v, std::size_t w)
  {
    put(segs_, v);
    put(segs_, w);
  }
  void face(std::size_t f)
  {
    if (f >= m_.num_faces()) return;
    const std::size_t c0 = m_.face_off[f];
    for (std::size_t c = c0 + 1; c + 1 < m_.face_off[f + 1]; ++c) {  // a fan
      put(tris_, m_.corners[c0]);
      put(tris_, m_.corners[c]);
      put(tris_, m_.corners[c + 1]);
    }
  }
  // ends an instance: kept when it fits, and the first one gives "first";
  // returns false once an instance did not fit (drawing stops there)
  bool end_instance()
  {
    const std::size_t n = pts_.size() / 3 + segs_.size() / 6 + tris_.size() / 9;
    bool ok = !k_.truncated && elements_ + n <= max_elements_;
    if (k_.drawn == 0 && !k_.truncated) {
      // the first instance: its centre and size, for "fly to", from its
      // finite corners (a component or face may touch a NaN point)
      auto finite_at = [](const std::vector<float>& a, std::size_t i) {
        return std::isfinite(a[i]) && std::isfinite(a[i + 1]) && std::isfinite(a[i + 2]);
      };
      double c[3] = {0, 0, 0};
      std::size_t np = 0;
      for (const std::vector<float>* a : {&pts_, &segs_, &tris_})
        for (std::size_t i = 0; i + 2 < a->size(); i += 3)
          if (finite_at(*a, i)) {
            ++np;
            for (int j = 0; j < 3; ++j) c[j] += (*a)[i + j];
          }
      if (np > 0) {
        for (double& x : c) x /= double(np);
        double r2 = 0;
        for (const std::vector<float>* a : {&pts_, &segs_, &tris_})
          for (std::size_t i = 0; i + 2 < a->size(); i += 3) {
            if (!finite_at(*a, i)) continue;
            double d2 = 0;
            for (int j = 0; j < 3; ++j) d2 += ((*a)[i + j] - c[j]) * ((*a)[i + j] - c[j]);
            r2 = std::max(r2, d2);
          }
        if (std::isfinite(c[0]) && std::isfinite(c[1]) && std::isfinite(c[2]) && std::isfinite(r2)) {
          k_.has_first = true;
          k_.first = {{c[0], c[1], c[2]}};
          k_.first_radius = std::max(std::sqrt(r2), min_radius_);
        }
      }
    }
    if (ok) {
      k_.points.insert(k_.points.end(), pts_.begin(), pts_.end());
      k_.segments.insert(k_.segments.end(), segs_.begin(), segs_.end());
      k_.triangles.insert(k_.triangles.end(), tris_.begin(), tris_.end());
      elements_ += n;
      ++k_.drawn;
    } else {
      k_.truncated = true;
    }
    pts_.clear();
    segs_.clear();
    tris_.clear();
    return ok;
  }
};

// the edges of a boundary loop of Defect_locations (walk rules there)
template <typename F>
void for_each_loop_edge(const std::vector<Defect_locations::Index>& loop, const F& f)
{
  const bool walks = std::find(loop.begin(), loop.end(), Defect_locations::walk_end) != loop.end();
  if (!walks) {
    for (std::size_t i = 0; i < loop.size(); ++i) f(loop[i], loop[(i + 1) % loop.size()]);
    return;
  }
  for (std::size_t i = 0; i + 1 < loop.size(); ++i)
    if (loop[i] != Defect_locations::walk_end && loop[i + 1] != Defect_locations::walk_end) f(loop[i], loop[i + 1]);
}

// The defect overlay of `d` on the mesh `m` it was found on: per kind at
// most `max_elements` elements (points + segments + triangles).
inline Defect_overlay make_defect_overlay(const Indexed_faces& m, const Defect_locations& d,
                                          std::size_t max_elements)
{
  // the smallest "fly to" radius: 1/500 of the bounding box diagonal
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t v = 0; v < m.num_vertices(); ++v)
    for (int i = 0; i < 3; ++i)
      if (std::isfinite(m.xyz[3 * v + i])) {
        lo[i] = std::min(lo[i], m.xyz[3 * v + i]);
        hi[i] = std::max(hi[i], m.xyz[3 * v + i]);
      }
  double diag2 = 0;
  for (int i = 0; i < 3; ++i)
    if (hi[i] >= lo[i]) diag2 += (hi[i] - lo[i]) * (hi[i] - lo[i]);
  const double min_radius = diag2 > 0 ? std::sqrt(diag2) / 500 : 1.0;

  const Inspection_report& r = d.report;
  Defect_overlay o;
  for (const Overlay_kind_info& info : overlay_kind_table()) {
    o.kinds.emplace_back();
    Overlay_kind& k = o.kinds.back();
    k.key = info.key;
    k.label = info.label;
    k.color = info.color;
  }
  const std::size_t nv = m.num_vertices();
  auto kind = [&](std::size_t i, std::size_t count) -> Overlay_kind& {
    o.kinds[i].count = count;
    return o.kinds[i];
  };
  auto loops = [&](Overlay_kind& k, auto&& indices) {
    Overlay_drawer draw(m, max_elements, min_radius, k);
    for (std::size_t l : indices) {
      for_each_loop_edge(d.boundary_loops[l], [&](std::size_t v, std::size_t w) {
        if (v < nv && w < nv) draw.segment(v, w);
      });
      if (!draw.end_instance()) break;
    }
  };
  {
    std::vector<std::size_t> all(d.boundary_loops.size());
    for (std::size_t i = 0; i < all.size(); ++i) all[i] = i;
    loops(kind(0, r.boundary_loops), all);
    loops(kind(1, r.small_holes), d.small_holes);
  }
  {
    Overlay_drawer draw(m, max_elements, min_radius, kind(2, r.non_manifold_edges));
    for (const auto& e : d.non_manifold_edges) {
      draw.segment(e[0], e[1]);
      if (!draw.end_instance()) break;
    }
  }
  auto vertices = [&](Overlay_kind& k, const std::vector<Defect_locations::Index>& list) {
    Overlay_drawer draw(m, max_elements, min_radius, k);
    for (std::size_t v : list) {
      if (v < nv) draw.point(v);
      if (!draw.end_instance()) break;
    }
  };
  vertices(kind(3, r.non_manifold_vertices), d.non_manifold_vertices);
  vertices(kind(4, r.spiked_vertices), d.spiked_vertices);
  {
    Overlay_drawer draw(m, max_elements, min_radius, kind(5, r.near_degenerate_faces));
    for (std::size_t f : d.near_degenerate_faces) {
      draw.face(f);
      if (!draw.end_instance()) break;
    }
  }
  {
    Overlay_drawer draw(m, max_elements, min_radius, kind(6, r.small_components));
    for (const auto& c : d.small_components) {
      for (std::size_t f : c) draw.face(f);
      if (!draw.end_instance()) break;
    }
  }
  {
    Overlay_drawer draw(m, max_elements, min_radius, kind(7, r.self_intersecting_pairs));
    for (const auto& p : d.self_intersecting_pairs) {
      draw.face(p[0]);
      draw.face(p[1]);
      if (!draw.end_instance()) break;
    }
  }
  {
    Overlay_drawer draw(m, max_elements, min_radius, kind(8, r.t_junctions));
    for (std::size_t i = 0; i < d.t_junction_vertices.size(); ++i) {
      draw.point(d.t_junction_vertices[i]);
      draw.segment(d.t_junction_edges[i][0], d.t_junction_edges[i][1]);
      if (!draw.end_instance()) break;
    }
  }
  return o;
}

// ---- preview ---------------------------------------------------------------------------

struct Mesh_preview
{
  std::vector<float> positions;         // 3 per vertex
  std::vector<std::uint32_t> indices;   // 3 per triangle
  std::size_t faces = 0;                // triangles of the full mesh (polygons fanned)
  bool decimated = false;
};

// The mesh as triangles (polygons fanned) when it has at most `face_budget`
// of them; else a vertex clustering on a uniform grid, the cell shrunk until
// at most `face_budget` triangles are left: each cell's vertices become their
// mean, triangles with two corners in one cell and repeated triangles (same
// three cells, either orientation) are dropped. Faces with a non-finite
// corner are left out of a decimated preview.
inline Mesh_preview make_preview(const Indexed_faces& m, std::size_t face_budget)
{
  Mesh_preview out;
  const std::size_t nf = m.num_faces(), nv = m.num_vertices();
  for (std::size_t f = 0; f < nf; ++f) out.faces += m.triangles(f);
  auto fan = [&](const auto& emit) {
    for (std::size_t f = 0; f < nf; ++f) {
      const std::size_t c0 = m.face_off[f];
      for (std::size_t c = c0 + 1; c + 1 < m.face_off[f + 1]; ++c) emit(m.corners[c0], m.corners[c], m.corners[c + 1]);
    }
  };
  if (out.faces <= face_budget) {
    out.positions.resize(3 * nv);
    for (std::size_t i = 0; i < 3 * nv; ++i) out.positions[i] = static_cast<float>(m.xyz[i]);
    out.indices.reserve(3 * out.faces);
    fan([&](std::size_t a, std::size_t b, std::size_t c) {
      out.indices.push_back(static_cast<std::uint32_t>(a));
      out.indices.push_back(static_cast<std::uint32_t>(b));
      out.indices.push_back(static_cast<std::uint32_t>(c));
    });
    return out;
  }
  out.decimated = true;
  std::vector<unsigned char> finite(nv);
  double lo[3] = {HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi[3] = {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (std::size_t v = 0; v < nv; ++v) {
    const double* p = &m.xyz[3 * v];
    finite[v] = std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]);
    if (finite[v])
      for (int i = 0; i < 3; ++i) {
        lo[i] = std::min(lo[i], p[i]);
        hi[i] = std::max(hi[i], p[i]);
      }
  }
  if (face_budget == 0 || !(lo[0] <= hi[0])) return out;
  // first cell size: about budget / 2 occupied cells over the surface area
  double area = 0;
  fan([&](std::size_t a, std::size_t b, std::size_t c) {
    if (!finite[a] || !finite[b] || !finite[c]) return;
    const double *p = &m.xyz[3 * a], *q = &m.xyz[3 * b], *w = &m.xyz[3 * c];
    const double u[3] = {q[0] - p[0], q[1] - p[1], q[2] - p[2]}, s[3] = {w[0] - p[0], w[1] - p[1], w[2] - p[2]};
    const double n[3] = {u[1] * s[2] - u[2] * s[1], u[2] * s[0] - u[0] * s[2], u[0] * s[1] - u[1] * s[0]};
    area += 0.5 * std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  });
  const double extent = std::max({hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]});
  double cell = area > 0 ? std::sqrt(2 * area / double(face_budget)) : extent / 2;
  if (!(cell > 0)) cell = 1;
  std::vector<std::uint64_t> key(nv);
  std::vector<std::uint32_t> cluster(nv);
  for (int attempt = 0;; ++attempt) {
    // at most 2^21 cells per axis
    cell = std::max(cell, extent / double((1 << 21) - 1));
    for (std::size_t v = 0; v < nv; ++v) {
      if (!finite[v]) {
        key[v] = ~std::uint64_t(0);
        continue;
      }
      std::uint64_t k = 0;
      for (int i = 0; i < 3; ++i) {
        const double c = std::floor((m.xyz[3 * v + i] - lo[i]) / cell);
        k = (k << 21) | static_cast<std::uint64_t>(std::min(std::max(c, 0.0), double((1 << 21) - 1)));
      }
      key[v] = k;
    }
    std::unordered_map<std::uint64_t, std::uint32_t> ids;
    ids.reserve(std::min<std::size_t>(nv, 2 * face_budget + 16));
    std::vector<double> sum;
    std::vector<std::uint32_t> cnt;
    for (std::size_t v = 0; v < nv; ++v) {
      if (!finite[v]) continue;
      auto it = ids.emplace(key[v], static_cast<std::uint32_t>(cnt.size())).first;
      if (it->second == cnt.size()) {
        cnt.push_back(0);
        sum.insert(sum.end(), {0.0, 0.0, 0.0});
      }
      const std::uint32_t c = it->second;
      cluster[v] = c;
      ++cnt[c];
      for (int i = 0; i < 3; ++i) sum[3 * c + i] += m.xyz[3 * v + i];
    }
    // the triangles between three distinct cells, each set of cells once
    std::vector<std::array<std::uint32_t, 3>> tris;
    fan([&](std::size_t a, std::size_t b, std::size_t c) {
      if (!finite[a] || !finite[b] || !finite[c]) return;
      const std::uint32_t x = cluster[a], y = cluster[b], z = cluster[c];
      if (x != y && y != z && x != z) tris.push_back({{x, y, z}});
    });
    std::vector<std::array<std::uint32_t, 3>> sorted(tris);
    for (auto& t : sorted) std::sort(t.begin(), t.end());
    std::vector<std::size_t> order(tris.size());
    for (std::size_t i = 0; i < order.size(); ++i) order[i] = i;
    std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
      return sorted[i] != sorted[j] ? sorted[i] < sorted[j] : i < j;
    });
    std::vector<unsigned char> keep(tris.size(), 0);
    std::size_t kept = 0;
    for (std::size_t i = 0; i < order.size(); ++i)
      if (i == 0 || sorted[order[i]] != sorted[order[i - 1]]) {
        keep[order[i]] = 1;
        ++kept;
      }
    if (kept > face_budget && attempt < 30) {
      // fewer, larger cells: the triangle count scales about as 1 / cell^2
      cell *= std::max(1.05, 1.02 * std::sqrt(double(kept) / double(face_budget)));
      continue;
    }
    // the clusters that a kept triangle uses, renumbered
    std::vector<std::uint32_t> renum(cnt.size(), 0xffffffffu);
    for (std::size_t i = 0; i < tris.size(); ++i) {
      if (!keep[i]) continue;
      if (out.indices.size() / 3 >= face_budget) break;
      for (std::uint32_t c : tris[i]) {
        if (renum[c] == 0xffffffffu) {
          renum[c] = static_cast<std::uint32_t>(out.positions.size() / 3);
          for (int j = 0; j < 3; ++j) out.positions.push_back(static_cast<float>(sum[3 * c + j] / cnt[c]));
        }
        out.indices.push_back(renum[c]);
      }
    }
    return out;
  }
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_STUDIO_OVERLAY_H
