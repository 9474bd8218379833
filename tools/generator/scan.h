// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Defect generator, scan mode: injects counted scanner-like defects into a
// clean, closed (or at least manifold) triangle mesh. Each defect claims a
// neighbourhood of vertices (with a margin) so that defects never touch each
// other and the manifest's counts stay exact.
#ifndef MREPAIR_TOOLS_GENERATOR_SCAN_H
#define MREPAIR_TOOLS_GENERATOR_SCAN_H

#include "generator/common.h"

#include <functional>
#include <utility>

namespace mrepair {
namespace generator {

struct Scan_options
{
  std::size_t spikes = 0, foldovers = 0, tunnels = 0, holes = 0, jagged_holes = 0,
              islands = 0, slivers = 0, isolated = 0, nan_isolated = 0, nan_referenced = 0,
              pinned_danglers = 0;
  double noise = 0;  // scanner noise along the normal, in mean edge lengths (0: none)
};

/// one injected defect; ids refer to the working arrays until `finish` remaps them.
struct Defect
{
  std::string kind, variant;
  std::vector<std::uint32_t> vertices, faces;
  Vec3 position{0, 0, 0};
  std::vector<std::pair<std::string, double>> figures;
};

class Scan_injector
{
public:
  /// `closed_surface`: the caller guarantees a closed, connected, manifold
  /// surface (the procedural one), which skips the edge sort of the checks.
  Scan_injector(Tri_soup& s, std::uint64_t seed, bool closed_surface = false) : s_(s), rng_(seed)
  {
    build(closed_surface);
  }

  double mean_edge_length() const { return e_; }
  std::size_t base_boundary_edges() const { return base_boundary_edges_; }
  std::size_t base_components() const { return base_components_; }
  long long base_boundary_loops() const { return base_loops_; }  // -1: not a manifold boundary
  const std::vector<Defect>& defects() const { return defects_; }
  const std::vector<std::pair<std::string, std::size_t>>& shortfalls() const { return shortfalls_; }

  void add_noise(double amplitude)
  {
    if (amplitude <= 0) return;
    std::vector<Vec3> n(s_.points.size(), Vec3{0, 0, 0});
    for (std::size_t f = 0; f < F0_; ++f) {
      Vec3 fn = face_normal(static_cast<std::uint32_t>(f));
      for (std::uint32_t v : s_.faces[f]) n[v] = n[v] + fn;
    }
    for (std::size_t v = 0; v < V0_; ++v)
      s_.points[v] = s_.points[v] + (amplitude * e_ * rng_.uniform(-1, 1)) * normalized(n[v]);
  }

  void run(const Scan_options& o)
  {
    // Order: geometry-moving defects first, face removal and splits next,
    // appended vertices last; NaN last of all so that no normal sees it.
    inject("spike", o.spikes, [this](std::uint32_t v) { return spike(v); });
    inject("foldover", o.foldovers, [this](std::uint32_t v) { return foldover(v); });
    inject("tunnel", o.tunnels, [this](std::uint32_t v) { return tunnel(v); });
    inject("hole", o.holes, [this](std::uint32_t v) { return hole(v); });
    pinned_left_ = o.pinned_danglers;
    inject("jagged_hole", o.jagged_holes, [this](std::uint32_t v) { return jagged_hole(v); });
    if (pinned_left_ > 0) shortfalls_.push_back({"pinned_dangler", pinned_left_});
    inject("island", o.islands, [this](std::uint32_t v) { return island(v); });
    inject("sliver", o.slivers, [this](std::uint32_t v) { return sliver(v); });
    inject("isolated_vertex", o.isolated, [this](std::uint32_t v) { return isolated(v, false); });
    inject("nan_vertex", o.nan_isolated, [this](std::uint32_t v) { return isolated(v, true); });
    inject("nan_referenced_vertex", o.nan_referenced, [this](std::uint32_t v) { return nan_referenced(v); });
  }

  /// drops removed faces and the vertices they alone used, remaps the defects' ids.
  void finish()
  {
    std::vector<std::uint32_t> fmap(s_.faces.size(), kNone), vmap(s_.points.size(), kNone);
    std::vector<char> used(s_.points.size(), 0);
    std::size_t nf = 0;
    for (std::size_t f = 0; f < s_.faces.size(); ++f)
      if (!removed_[f]) {
        fmap[f] = static_cast<std::uint32_t>(nf++);
        for (std::uint32_t v : s_.faces[f]) used[v] = 1;
      }
    std::size_t nv = 0;
    for (std::size_t v = 0; v < s_.points.size(); ++v)
      if (used[v] || keep_[v]) {
        vmap[v] = static_cast<std::uint32_t>(nv);
        s_.points[nv++] = s_.points[v];
      }
    s_.points.resize(nv);
    nf = 0;
    for (std::size_t f = 0; f < s_.faces.size(); ++f)
      if (!removed_[f]) {
        Tri t = s_.faces[f];
        for (auto& v : t) v = vmap[v];
        s_.faces[nf++] = t;
      }
    s_.faces.resize(nf);
    for (Defect& d : defects_) {
      auto remap = [](std::vector<std::uint32_t>& ids, const std::vector<std::uint32_t>& map) {
        std::vector<std::uint32_t> out;
        for (std::uint32_t i : ids)
          if (map[i] != kNone) out.push_back(map[i]);
        ids.swap(out);
      };
      remap(d.vertices, vmap);
      remap(d.faces, fmap);
    }
  }

private:
  static constexpr std::uint32_t kNone = 0xffffffffu;

  // ---- adjacency of the base mesh (faces [0, F0), vertices [0, V0)) --------
  void build(bool closed_surface)
  {
    F0_ = s_.faces.size();
    V0_ = s_.points.size();
    removed_.assign(F0_, 0);
    keep_.assign(V0_, 0);
    claimed_.assign(V0_, 0);
    dist_.assign(V0_, -1);
    region_mark_.assign(F0_, 0);
    star_begin_.assign(V0_ + 1, 0);
    for (const Tri& t : s_.faces)
      for (std::uint32_t v : t) ++star_begin_[v + 1];
    for (std::size_t v = 0; v < V0_; ++v) star_begin_[v + 1] += star_begin_[v];
    star_.resize(3 * F0_);
    std::vector<std::uint32_t> fill(star_begin_.begin(), star_begin_.end() - 1);
    for (std::size_t f = 0; f < F0_; ++f)
      for (std::uint32_t v : s_.faces[f]) star_[fill[v]++] = static_cast<std::uint32_t>(f);

    double total = 0;
    for (std::size_t f = 0; f < F0_; ++f)
      for (int k = 0; k < 3; ++k)
        total += norm(s_.points[s_.faces[f][(k + 1) % 3]] - s_.points[s_.faces[f][k]]);
    e_ = F0_ ? total / (3.0 * F0_) : 1.0;

    if (closed_surface) {
      base_components_ = 1;
      return;
    }
    // Vertices on a boundary or a non-manifold edge, or unreferenced, take no defect.
    std::vector<std::uint64_t> keys(3 * F0_);
    for (std::size_t f = 0; f < F0_; ++f)
      for (int k = 0; k < 3; ++k) {
        std::uint64_t a = s_.faces[f][k], b = s_.faces[f][(k + 1) % 3];
        keys[3 * f + k] = (std::min(a, b) << 32) | std::max(a, b);
      }
    std::sort(keys.begin(), keys.end());
    for (std::size_t i = 0; i < keys.size();) {
      std::size_t j = i;
      while (j < keys.size() && keys[j] == keys[i]) ++j;
      if (j - i != 2) {
        claimed_[keys[i] >> 32] = 1;
        claimed_[keys[i] & 0xffffffffu] = 1;
        ++base_boundary_edges_;
      }
      i = j;
    }
    for (std::size_t v = 0; v < V0_; ++v)
      if (star_begin_[v] == star_begin_[v + 1]) claimed_[v] = 1;
    count_base_topology();
  }

  void count_base_topology()
  {
    // components by union-find over face vertices
    std::vector<std::uint32_t> parent(V0_);
    for (std::size_t v = 0; v < V0_; ++v) parent[v] = static_cast<std::uint32_t>(v);
    auto find = [&](std::uint32_t x) {
      while (parent[x] != x) x = parent[x] = parent[parent[x]];
      return x;
    };
    for (std::size_t f = 0; f < F0_; ++f) {
      std::uint32_t a = find(s_.faces[f][0]);
      for (int k = 1; k < 3; ++k) {
        std::uint32_t b = find(s_.faces[f][k]);
        if (a != b) parent[b] = a;
      }
    }
    for (std::size_t v = 0; v < V0_; ++v)
      if (star_begin_[v] != star_begin_[v + 1] && find(static_cast<std::uint32_t>(v)) == v) ++base_components_;
    // boundary loops: walk boundary halfedges when each vertex has at most one
    if (base_boundary_edges_ == 0) { base_loops_ = 0; return; }
    std::vector<std::uint32_t> next(V0_, kNone);
    for (std::size_t f = 0; f < F0_; ++f)
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = s_.faces[f][k], b = s_.faces[f][(k + 1) % 3];
        if (face_with(b, a, kNone) == kNone) {  // no twin: boundary halfedge a->b
          if (next[a] != kNone) { base_loops_ = -1; return; }
          next[a] = b;
        }
      }
    std::vector<char> seen(V0_, 0);
    base_loops_ = 0;
    for (std::size_t v = 0; v < V0_; ++v) {
      if (next[v] == kNone || seen[v]) continue;
      ++base_loops_;
      for (std::uint32_t x = static_cast<std::uint32_t>(v); x != kNone && !seen[x]; x = next[x]) seen[x] = 1;
    }
  }

  std::pair<const std::uint32_t*, const std::uint32_t*> star(std::uint32_t v) const
  {
    return {star_.data() + star_begin_[v], star_.data() + star_begin_[v + 1]};
  }
  /// a base face other than `not_f` with the directed edge a->b, or kNone.
  std::uint32_t face_with(std::uint32_t a, std::uint32_t b, std::uint32_t not_f) const
  {
    auto st = star(a);
    for (auto it = st.first; it != st.second; ++it) {
      if (*it == not_f) continue;
      const Tri& t = s_.faces[*it];
      for (int k = 0; k < 3; ++k)
        if (t[k] == a && t[(k + 1) % 3] == b) return *it;
    }
    return kNone;
  }
  std::vector<std::uint32_t> ring(std::uint32_t v) const
  {
    std::vector<std::uint32_t> r;
    auto st = star(v);
    for (auto it = st.first; it != st.second; ++it)
      for (std::uint32_t w : s_.faces[*it])
        if (w != v && std::find(r.begin(), r.end(), w) == r.end()) r.push_back(w);
    return r;
  }
  Vec3 face_normal(std::uint32_t f) const
  {
    const Tri& t = s_.faces[f];
    return cross(s_.points[t[1]] - s_.points[t[0]], s_.points[t[2]] - s_.points[t[0]]);
  }
  Vec3 vertex_normal(std::uint32_t v) const
  {
    Vec3 n{0, 0, 0};
    auto st = star(v);
    for (auto it = st.first; it != st.second; ++it) n = n + face_normal(*it);
    return normalized(n);
  }
  Vec3 centroid(const Tri& t) const
  {
    return (1.0 / 3) * (s_.points[t[0]] + s_.points[t[1]] + s_.points[t[2]]);
  }

  /// breadth-first rings of `v` up to `radius`; fails (claims nothing) when one
  /// of them is claimed already. On success `dist_` holds the distances of `region_`.
  bool claim(std::uint32_t v, int radius)
  {
    for (std::uint32_t u : region_) dist_[u] = -1;
    region_.clear();
    if (claimed_[v]) return false;
    region_.push_back(v);
    dist_[v] = 0;
    for (std::size_t i = 0; i < region_.size(); ++i) {
      std::uint32_t u = region_[i];
      if (dist_[u] == radius) continue;
      auto st = star(u);
      for (auto it = st.first; it != st.second; ++it)
        for (std::uint32_t w : s_.faces[*it])
          if (dist_[w] < 0) {
            if (claimed_[w]) return false;
            dist_[w] = dist_[u] + 1;
            region_.push_back(w);
          }
    }
    for (std::uint32_t u : region_) claimed_[u] = 1;
    claimed_now_ = true;
    return true;
  }

  void inject(const char* kind, std::size_t count, const std::function<bool(std::uint32_t)>& make)
  {
    if (V0_ == 0) { if (count) shortfalls_.push_back({kind, count}); return; }
    std::size_t missing = 0;
    for (std::size_t i = 0; i < count; ++i) {
      bool ok = false;
      for (int attempt = 0; attempt < 400 && !ok; ++attempt) {
        claimed_now_ = false;
        ok = make(static_cast<std::uint32_t>(rng_.below(V0_)));
        // a rejected attempt gives its neighbourhood back (it held no claimed vertex before)
        if (!ok && claimed_now_)
          for (std::uint32_t u : region_) claimed_[u] = 0;
      }
      if (!ok) ++missing;
    }
    if (missing) shortfalls_.push_back({kind, missing});
  }

  std::uint32_t add_point(const Vec3& p)
  {
    s_.points.push_back(p);
    keep_.push_back(0);
    return static_cast<std::uint32_t>(s_.points.size() - 1);
  }
  std::uint32_t add_face(std::uint32_t a, std::uint32_t b, std::uint32_t c)
  {
    s_.faces.push_back({a, b, c});
    removed_.push_back(0);
    return static_cast<std::uint32_t>(s_.faces.size() - 1);
  }

  /// largest angle between the normals of two adjacent base faces among `faces` and their neighbours.
  double max_dihedral(const std::vector<std::uint32_t>& faces) const
  {
    double best = 0;
    for (std::uint32_t f : faces)
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = s_.faces[f][k], b = s_.faces[f][(k + 1) % 3];
        std::uint32_t g = face_with(b, a, f);
        if (g != kNone) best = std::max(best, angle_deg(face_normal(f), face_normal(g)));
      }
    return best;
  }
  std::vector<std::uint32_t> star_vector(std::uint32_t v) const
  {
    auto st = star(v);
    return std::vector<std::uint32_t>(st.first, st.second);
  }

  // ---- defects -------------------------------------------------------------

  // A vertex pushed 3-10 mean edge lengths along its normal. Straight spikes
  // keep every dihedral angle (angle between adjacent normals) below 90 degrees;
  // leaning ones (also pushed sideways by 1-2 times the height) overhang.
  bool spike(std::uint32_t v)
  {
    if (!claim(v, 3)) return false;
    Vec3 n = vertex_normal(v);
    double h = rng_.uniform(3, 10) * e_;
    const bool leaning = spikes_made_ % 2 == 1;  // alternate, so that retries do not bias the mix
    Vec3 offset = h * n;
    if (leaning) offset = offset + (rng_.uniform(1, 2) * h) * normalized(cross(n, rng_.direction()));
    const Vec3 old = s_.points[v];
    s_.points[v] = old + offset;
    Defect d{"spike", leaning ? "leaning" : "straight", {v}, star_vector(v), s_.points[v], {}};
    const double dihedral = max_dihedral(d.faces);
    // a non-convex 1-ring can make a straight spike overhang: keep those below 90 degrees only
    if (!leaning && dihedral >= 90) { s_.points[v] = old; return false; }
    d.figures.push_back({"height_over_mean_edge", h / e_});
    d.figures.push_back({"max_dihedral_deg", dihedral});
    defects_.push_back(std::move(d));
    ++spikes_made_;
    return true;
  }

  // A vertex moved past one of its neighbours (tangentially), so that the
  // faces between them flip.
  bool foldover(std::uint32_t v)
  {
    if (!claim(v, 3)) return false;
    std::vector<std::uint32_t> r = ring(v), st = star_vector(v);
    std::uint32_t w = r[rng_.below(r.size())];
    std::vector<Vec3> before;
    for (std::uint32_t f : st) before.push_back(face_normal(f));
    Vec3 old = s_.points[v], n = vertex_normal(v);
    s_.points[v] = s_.points[w] + rng_.uniform(0.3, 0.7) * (s_.points[w] - old) +
                   (rng_.uniform(-0.1, 0.1) * e_) * n;
    std::vector<std::uint32_t> flipped;
    for (std::size_t i = 0; i < st.size(); ++i)
      if (dot(face_normal(st[i]), before[i]) < 0) flipped.push_back(st[i]);
    if (flipped.empty()) { s_.points[v] = old; return false; }
    Defect d{"foldover", "moved_past_neighbour", {v, w}, flipped, s_.points[v], {}};
    d.figures.push_back({"flipped_faces", static_cast<double>(flipped.size())});
    defects_.push_back(std::move(d));
    return true;
  }

  // A micro tunnel: a thin triangular tube (a handle, genus + 1) arching from
  // face f1 over the surface to face f2 about three rings away. f1 and f2 are
  // removed; f1's triangle is swept along a half-ellipse in the vertical plane
  // through both faces (rising along the normal, descending into f2), shrinking
  // to half size at the top and turning slowly so that it lands on f2's
  // vertices: 6 intermediate rings, 42 faces, 18 new vertices, consistently
  // oriented with the surface and free of self-intersections.
  bool tunnel(std::uint32_t v)
  {
    if (!claim(v, 6)) return false;
    std::vector<std::uint32_t> far;
    for (std::uint32_t u : region_)
      if (dist_[u] == 3) far.push_back(u);
    if (far.empty()) return false;
    std::uint32_t u = far[rng_.below(far.size())];
    auto sv = star_vector(v), su = star_vector(u);
    std::uint32_t f1 = sv[rng_.below(sv.size())];
    std::vector<std::uint32_t> cands;
    for (std::uint32_t f : su) {
      bool ok = true;
      for (std::uint32_t w : s_.faces[f]) ok = ok && dist_[w] >= 2;
      if (ok) cands.push_back(f);
    }
    if (cands.empty()) return false;
    std::uint32_t f2 = cands[rng_.below(cands.size())];
    const Tri t1 = s_.faces[f1], t2 = s_.faces[f2];
    Vec3 n = normalized(vertex_normal(v) + vertex_normal(u));
    Vec3 c1 = centroid(t1), c2 = centroid(t2), dvec = c2 - c1;
    dvec = dvec - dot(dvec, n) * n;
    const double len = norm(dvec);
    if (len < 0.5 * e_) return false;
    const Vec3 dh = (1.0 / len) * dvec, w = cross(dh, n);
    const double a = 0.5 * len, b = 0.5 * len + e_;  // half-ellipse: horizontal, vertical semi-axes
    const Vec3 mid = 0.5 * (c1 + c2);
    // f1's corners in the start frame (dh, w); the sweep keeps these coordinates
    std::array<double, 3> al, be;
    for (int k = 0; k < 3; ++k) {
      Vec3 o = s_.points[t1[k]] - c1;
      al[k] = dot(o, dh);
      be[k] = dot(o, w);
    }
    // f2 reversed (as the tube arrives from above), in the end frame (-dh, w):
    // the cyclic shift and the total twist that land the swept ring on it
    const std::array<std::uint32_t, 3> rev{t2[0], t2[2], t2[1]};
    std::array<double, 3> ga, de;
    for (int k = 0; k < 3; ++k) {
      Vec3 o = s_.points[rev[k]] - c2;
      ga[k] = -dot(o, dh);
      de[k] = dot(o, w);
    }
    auto unit2 = [](double x, double y) {
      double r = std::sqrt(x * x + y * y);
      return r > 0 ? std::make_pair(x / r, y / r) : std::make_pair(1.0, 0.0);
    };
    int shift = 0;
    double best = std::numeric_limits<double>::infinity(), zr = 0, zi = 0;
    for (int sft = 0; sft < 3; ++sft) {
      double d = 0, sr = 0, si = 0;
      for (int k = 0; k < 3; ++k) {
        auto p = unit2(al[k], be[k]), q = unit2(ga[(k + sft) % 3], de[(k + sft) % 3]);
        d += (p.first - q.first) * (p.first - q.first) + (p.second - q.second) * (p.second - q.second);
        sr += q.first * p.first + q.second * p.second;  // q * conj(p)
        si += q.second * p.first - q.first * p.second;
      }
      if (d < best) { best = d; shift = sft; zr = sr; zi = si; }
    }
    const double twist = datan2(zi, zr);
    std::vector<std::array<std::uint32_t, 3>> rings;
    rings.push_back({t1[0], t1[1], t1[2]});
    const int K = 6;
    for (int k = 1; k <= K; ++k) {
      const double th = pi * k / (K + 1), frac = static_cast<double>(k) / (K + 1);
      const Vec3 c = mid + (-a * dcos(th)) * dh + (b * dsin(th)) * n;
      const Vec3 T = normalized((a * dsin(th)) * dh + (b * dcos(th)) * n);
      const Vec3 N = cross(T, w);
      const double scale = 1 - 0.5 * dsin(th), cr = dcos(frac * twist), sr = dsin(frac * twist);
      std::array<std::uint32_t, 3> ring;
      for (int j = 0; j < 3; ++j) {
        double x = cr * al[j] - sr * be[j], y = sr * al[j] + cr * be[j];
        ring[j] = add_point(c + scale * (x * N + y * w));
      }
      rings.push_back(ring);
    }
    rings.push_back({rev[shift], rev[(shift + 1) % 3], rev[(shift + 2) % 3]});
    removed_[f1] = removed_[f2] = 1;
    Defect d{"tunnel", "handle", {}, {}, mid + b * n, {}};
    for (const auto& r : rings) d.vertices.insert(d.vertices.end(), r.begin(), r.end());
    // segment between consecutive rings P, Q (both counter-clockwise seen along the travel)
    for (std::size_t r = 0; r + 1 < rings.size(); ++r) {
      const auto &P = rings[r], &Q = rings[r + 1];
      for (int i = 0; i < 3; ++i) {
        int j = (i + 1) % 3;
        d.faces.push_back(add_face(P[i], P[j], Q[j]));
        d.faces.push_back(add_face(P[i], Q[j], Q[i]));
      }
    }
    d.figures.push_back({"span_over_mean_edge", len / e_});
    d.figures.push_back({"height_over_mean_edge", b / e_});
    defects_.push_back(std::move(d));
    return true;
  }

  /// checks that removing `R` (with `region_mark_` set on it) leaves every
  /// touched vertex a manifold (at most one fan) except those in `allowed`,
  /// and returns the boundary loops it opens (vertex sequences), or fails.
  bool check_removal(const std::vector<std::uint32_t>& R, std::vector<std::vector<std::uint32_t>>* loops,
                     const std::vector<std::uint32_t>& allowed = {})
  {
    auto kept = [this](std::uint32_t f) { return !removed_[f] && !region_mark_[f]; };
    std::vector<std::uint32_t> touched;
    for (std::uint32_t f : R)
      for (std::uint32_t v : s_.faces[f])
        if (std::find(touched.begin(), touched.end(), v) == touched.end()) touched.push_back(v);
    std::vector<std::pair<std::uint32_t, std::uint32_t>> bnd;  // boundary halfedges of kept faces
    for (std::uint32_t v : touched) {
      if (std::find(allowed.begin(), allowed.end(), v) != allowed.end()) continue;
      int boundary = 0;
      for (std::uint32_t w : ring(v)) {
        int k = 0;
        std::uint32_t f = face_with(v, w, kNone), g = face_with(w, v, kNone);
        if (f != kNone && kept(f)) ++k;
        if (g != kNone && kept(g)) ++k;
        if (k == 1) ++boundary;
      }
      if (boundary > 2) return false;
    }
    for (std::uint32_t f : R)
      for (int k = 0; k < 3; ++k) {
        std::uint32_t a = s_.faces[f][k], b = s_.faces[f][(k + 1) % 3];
        std::uint32_t g = face_with(b, a, f);
        if (g != kNone && kept(g)) bnd.push_back({b, a});
      }
    if (!loops) return true;
    loops->clear();
    std::vector<char> used(bnd.size(), 0);
    for (std::size_t i = 0; i < bnd.size(); ++i) {
      if (used[i]) continue;
      std::vector<std::uint32_t> loop;
      std::size_t j = i;
      while (!used[j]) {
        used[j] = 1;
        loop.push_back(bnd[j].first);
        std::size_t nxt = bnd.size();
        for (std::size_t k = 0; k < bnd.size(); ++k)
          if (!used[k] && bnd[k].first == bnd[j].second) { nxt = k; break; }
        if (nxt == bnd.size()) break;
        j = nxt;
      }
      loops->push_back(loop);
    }
    return true;
  }
  void mark(const std::vector<std::uint32_t>& R, char value)
  {
    for (std::uint32_t f : R) region_mark_[f] = value;
  }
  /// base faces around the vertices at distance < `rings` from the claimed centre.
  std::vector<std::uint32_t> disk(int rings)
  {
    std::vector<std::uint32_t> R;
    for (std::uint32_t u : region_)
      if (dist_[u] < rings) {
        auto st = star(u);
        for (auto it = st.first; it != st.second; ++it)
          if (!region_mark_[*it]) { region_mark_[*it] = 1; R.push_back(*it); }
      }
    return R;
  }

  // A small hole: one face or the faces around the 1..4-ring of a vertex,
  // 3-30 boundary vertices on a single loop.
  bool hole(std::uint32_t v)
  {
    int rings = static_cast<int>(rng_.below(5));
    if (!claim(v, rings + 2)) return false;
    std::vector<std::uint32_t> R;
    if (rings == 0) {
      auto st = star_vector(v);
      R.push_back(st[rng_.below(st.size())]);
      region_mark_[R[0]] = 1;
    } else {
      R = disk(rings);
    }
    std::vector<std::vector<std::uint32_t>> loops;
    bool ok = check_removal(R, &loops) && loops.size() == 1 && loops[0].size() >= 3 && loops[0].size() <= 30;
    mark(R, 0);
    if (!ok) return false;
    for (std::uint32_t f : R) removed_[f] = 1;
    Defect d{"hole", rings == 0 ? "one_face" : "disk", loops[0], {}, s_.points[v], {}};
    d.figures.push_back({"boundary_vertices", static_cast<double>(loops[0].size())});
    d.figures.push_back({"removed_faces", static_cast<double>(R.size())});
    defects_.push_back(std::move(d));
    return true;
  }

  // A jagged hole: a 2- or 3-ring disk grown by 3-8 random faces along its
  // border, then 1-3 faces inside it kept as danglers attached by one edge
  // (manifold), plus, when asked, danglers attached by a single vertex
  // (making that vertex non-manifold, a bowtie).
  bool jagged_hole(std::uint32_t v)
  {
    if (!claim(v, 7)) return false;
    std::vector<std::uint32_t> R = disk(2 + static_cast<int>(rng_.below(2)));
    std::vector<std::vector<std::uint32_t>> loops;
    auto valid = [&]() { return check_removal(R, &loops) && loops.size() == 1; };
    bool ok = valid();
    int grow = static_cast<int>(rng_.between(3, 8));
    for (int g = 0; ok && g < grow; ++g) {
      std::vector<std::uint32_t> cands;
      for (std::uint32_t f : R)
        for (int k = 0; k < 3; ++k) {
          std::uint32_t h = face_with(s_.faces[f][(k + 1) % 3], s_.faces[f][k], f);
          if (h == kNone || region_mark_[h]) continue;
          bool inside = true;
          for (std::uint32_t w : s_.faces[h]) inside = inside && dist_[w] >= 0 && dist_[w] <= 4;
          if (inside && std::find(cands.begin(), cands.end(), h) == cands.end()) cands.push_back(h);
        }
      if (cands.empty()) break;
      std::uint32_t h = cands[rng_.below(cands.size())];
      region_mark_[h] = 1;
      R.push_back(h);
      if (!valid()) { region_mark_[h] = 0; R.pop_back(); }
    }
    ok = ok && valid();
    auto all_in_R = [&](std::uint32_t x) {
      auto st = star(x);
      for (auto it = st.first; it != st.second; ++it)
        if (!region_mark_[*it]) return false;
      return true;
    };
    std::vector<std::uint32_t> edge_danglers, vertex_danglers, pinned;
    int want = static_cast<int>(rng_.between(1, 3));
    for (int attempt = 0; ok && attempt < 20 && static_cast<int>(edge_danglers.size()) < want; ++attempt) {
      std::uint32_t f = R[rng_.below(R.size())];
      if (!region_mark_[f]) continue;
      int shared = 0, apex = -1;
      for (int k = 0; k < 3; ++k) {
        std::uint32_t h = face_with(s_.faces[f][(k + 1) % 3], s_.faces[f][k], f);
        if (h != kNone && !region_mark_[h]) { ++shared; apex = (k + 2) % 3; }
      }
      if (shared != 1 || !all_in_R(s_.faces[f][apex])) continue;
      region_mark_[f] = 0;
      std::vector<std::uint32_t> R2;
      for (std::uint32_t g : R)
        if (g != f) R2.push_back(g);
      std::swap(R, R2);
      if (valid()) edge_danglers.push_back(f);
      else { std::swap(R, R2); region_mark_[f] = 1; }
    }
    ok = ok && valid() && !edge_danglers.empty();
    if (!ok) { mark(R, 0); return false; }
    std::vector<std::uint32_t> boundary = loops[0];
    // single-vertex danglers: a face of R touching the kept part at one vertex only
    for (int attempt = 0; pinned_left_ > 0 && attempt < 30; ++attempt) {
      std::uint32_t f = R[rng_.below(R.size())];
      if (!region_mark_[f]) continue;
      int touching = -1, count = 0;
      for (int k = 0; k < 3; ++k)
        if (!all_in_R(s_.faces[f][k])) { touching = k; ++count; }
      if (count != 1) continue;
      region_mark_[f] = 0;
      // the other two vertices must now have only f kept: their stars were inside R
      vertex_danglers.push_back(f);
      pinned.push_back(s_.faces[f][touching]);
      --pinned_left_;
      break;
    }
    std::vector<std::uint32_t> finalR;
    for (std::uint32_t f : R)
      if (region_mark_[f]) finalR.push_back(f);
    for (std::uint32_t f : finalR) removed_[f] = 1;
    mark(R, 0);
    Defect d{"jagged_hole", pinned.empty() ? "edge_danglers" : "edge_and_vertex_danglers", boundary,
             edge_danglers, s_.points[v], {}};
    d.faces.insert(d.faces.end(), vertex_danglers.begin(), vertex_danglers.end());
    d.figures.push_back({"boundary_vertices", static_cast<double>(boundary.size())});
    d.figures.push_back({"removed_faces", static_cast<double>(finalR.size())});
    d.figures.push_back({"edge_danglers", static_cast<double>(edge_danglers.size())});
    d.figures.push_back({"vertex_danglers", static_cast<double>(vertex_danglers.size())});
    defects_.push_back(std::move(d));
    if (!pinned.empty()) {
      Defect p{"pinned_dangler", "face_attached_by_one_vertex", pinned, vertex_danglers,
               s_.points[pinned[0]], {}};
      defects_.push_back(std::move(p));
    }
    return true;
  }

  // A small floating component near the surface: a copy of a vertex's 1- or
  // 2-ring lifted 1.5-3 mean edges along the normal (an open patch, one
  // boundary loop), or a closed tetrahedron 2 mean edges above the surface.
  bool island(std::uint32_t v)
  {
    if (!claim(v, 4)) return false;
    Vec3 n = vertex_normal(v);
    Defect d{"island", "", {}, {}, s_.points[v], {}};
    if (rng_.below(3) != 0) {
      d.variant = "open_patch";
      std::vector<std::uint32_t> R = disk(1 + static_cast<int>(rng_.below(2)));
      mark(R, 0);
      Vec3 lift = (rng_.uniform(1.5, 3) * e_) * n;
      std::vector<std::pair<std::uint32_t, std::uint32_t>> copies;
      auto copy = [&](std::uint32_t x) {
        for (auto& c : copies)
          if (c.first == x) return c.second;
        std::uint32_t y = add_point(s_.points[x] + lift);
        copies.push_back({x, y});
        d.vertices.push_back(y);
        return y;
      };
      for (std::uint32_t f : R) {
        Tri t = s_.faces[f];
        std::uint32_t a = copy(t[0]), b = copy(t[1]), c = copy(t[2]);
        d.faces.push_back(add_face(a, b, c));
      }
      d.position = s_.points[v] + lift;
    } else {
      d.variant = "tetrahedron";
      Vec3 c = s_.points[v] + (2 * e_) * n;
      Vec3 a = normalized(cross(n, rng_.direction())), b = cross(n, a);
      const double q[4][3] = {{1, 1, 1}, {1, -1, -1}, {-1, 1, -1}, {-1, -1, 1}};
      std::uint32_t ids[4];
      for (int i = 0; i < 4; ++i)
        ids[i] = add_point(c + (0.35 * e_) * (q[i][0] * a + q[i][1] * b + q[i][2] * n));
      const int tf[4][3] = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
      for (auto& t : tf) {
        std::uint32_t x = ids[t[0]], y = ids[t[1]], z = ids[t[2]];
        Vec3 fn = cross(s_.points[y] - s_.points[x], s_.points[z] - s_.points[x]);
        if (dot(fn, centroid({x, y, z}) - c) < 0) std::swap(y, z);
        d.faces.push_back(add_face(x, y, z));
      }
      d.vertices.assign(ids, ids + 4);
      d.position = c;
    }
    d.figures.push_back({"face_count", static_cast<double>(d.faces.size())});
    defects_.push_back(std::move(d));
    return true;
  }

  static double min_angle(const Vec3& a, const Vec3& b, const Vec3& c)
  {
    return std::min({angle_deg(b - a, c - a), angle_deg(a - b, c - b), angle_deg(a - c, b - c)});
  }
  static double max_angle(const Vec3& a, const Vec3& b, const Vec3& c)
  {
    return std::max({angle_deg(b - a, c - a), angle_deg(a - b, c - b), angle_deg(a - c, b - c)});
  }

  // A near-degenerate sliver: a face split 1-to-3 at a point very close to one
  // of its edges (a cap, an angle near 180 degrees) or to one of its vertices
  // (two needles with an edge of 0.5-2 % of the face's size).
  bool sliver(std::uint32_t v)
  {
    if (!claim(v, 2)) return false;
    auto st = star_vector(v);
    std::uint32_t f = st[rng_.below(st.size())];
    int r = static_cast<int>(rng_.below(3));
    std::uint32_t a = s_.faces[f][r], b = s_.faces[f][(r + 1) % 3], c = s_.faces[f][(r + 2) % 3];
    const Vec3 A = s_.points[a], B = s_.points[b], C = s_.points[c];
    bool cap = rng_.below(2) == 0;
    Vec3 p;
    if (cap) {
      Vec3 q = A + rng_.uniform(0.3, 0.7) * (B - A);
      p = q + rng_.uniform(0.005, 0.02) * (C - q);
    } else {
      p = A + rng_.uniform(0.005, 0.02) * (0.5 * (B + C) - A);
    }
    std::uint32_t m = add_point(p);
    removed_[f] = 1;
    Defect d{"sliver", cap ? "cap" : "needle", {m}, {}, p, {}};
    if (cap) {
      d.faces = {add_face(a, m, c), add_face(m, b, c), add_face(a, b, m)};
      d.figures.push_back({"max_angle_deg", max_angle(A, B, p)});
    } else {
      d.faces = {add_face(a, b, m), add_face(b, c, m), add_face(c, a, m)};
      d.figures.push_back({"min_angle_deg", std::min(min_angle(A, B, p), min_angle(C, A, p))});
      d.figures.push_back({"short_edge_over_mean_edge", norm(p - A) / e_});
    }
    defects_.push_back(std::move(d));
    return true;
  }

  // An unreferenced vertex: near the surface, or with NaN coordinates.
  bool isolated(std::uint32_t v, bool nan)
  {
    Vec3 p = s_.points[v] + (rng_.uniform(0.5, 2) * e_) * vertex_normal(v);
    if (nan) {
      double q = std::numeric_limits<double>::quiet_NaN();
      p = Vec3{q, q, q};
    }
    std::uint32_t id = add_point(p);
    keep_[id] = 1;
    defects_.push_back(Defect{nan ? "nan_vertex" : "isolated_vertex", "unreferenced", {id}, {}, p, {}});
    return true;
  }

  // A vertex of the surface whose coordinates become NaN (still referenced).
  bool nan_referenced(std::uint32_t v)
  {
    if (!claim(v, 2)) return false;
    double q = std::numeric_limits<double>::quiet_NaN();
    Defect d{"nan_referenced_vertex", "referenced", {v}, star_vector(v), s_.points[v], {}};
    s_.points[v] = Vec3{q, q, q};
    defects_.push_back(std::move(d));
    return true;
  }

  Tri_soup& s_;
  Random rng_;
  std::size_t F0_ = 0, V0_ = 0;
  double e_ = 1;
  std::vector<std::uint32_t> star_begin_, star_;
  std::vector<char> removed_, keep_, claimed_, region_mark_;
  std::vector<int> dist_;
  std::vector<std::uint32_t> region_;
  std::vector<Defect> defects_;
  std::vector<std::pair<std::string, std::size_t>> shortfalls_;
  std::size_t base_boundary_edges_ = 0, base_components_ = 0, pinned_left_ = 0, spikes_made_ = 0;
  bool claimed_now_ = false;
  long long base_loops_ = 0;
};

}  // namespace generator
}  // namespace mrepair

#endif  // MREPAIR_TOOLS_GENERATOR_SCAN_H
