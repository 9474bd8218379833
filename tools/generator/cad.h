// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Defect generator, CAD mode: a closed two-body part (a box, and a silo made
// of a cylinder, a hemispherical cap and a bottom disk) tessellated as nine
// independent parametric patches, as a CAD exporter does: every patch owns
// its boundary vertices (duplicated, slightly perturbed), neighbouring patches
// sample a shared seam with different densities (T-junctions), some seams are
// pulled apart (narrow gaps); then flipped, duplicate and degenerate faces,
// fins (non-manifold edges) and pinched vertices are added, all counted.
// The part mode does the same to a real clean part (make_cad_soup_from_part).
#ifndef MREPAIR_TOOLS_GENERATOR_CAD_H
#define MREPAIR_TOOLS_GENERATOR_CAD_H

#include "generator/common.h"

#include <algorithm>
#include <functional>
#include <limits>
#include <numeric>

namespace mrepair {
namespace generator {

struct Cad_options
{
  std::size_t faces = 20000;
  double perturbation = 1e-4;  // G: seam vertices moved by up to G * bbox diagonal
  double gap_fraction = 0.3;   // share of seams pulled apart into a narrow gap
  std::size_t flipped = 0, duplicates = 0, degenerate = 0, fins = 0, pinched = 0;
};

struct Cad_seam
{
  int patch_a, side_a, patch_b, side_b;
  std::size_t segments_a, segments_b;
  bool curved, gap;
  double gap_width;  // absolute, 0 when not a gap seam
  std::size_t unmatched;  // vertices of one side not at a vertex of the other
};

struct Cad_defect
{
  std::string kind, variant;
  std::vector<std::uint32_t> vertices, faces;
  Vec3 position;
};

struct Cad_result
{
  std::vector<std::string> patch_names;
  std::vector<std::size_t> patch_faces, patch_boundary_edges;
  std::vector<Cad_seam> seams;
  std::vector<Cad_defect> defects;
  std::size_t seam_edges = 0, t_junction_vertices = 0, curved_unmatched_vertices = 0;
  double diagonal = 0, max_gap = 0;
};

namespace internal_cad {

struct Patch
{
  std::string name;
  std::function<Vec3(double, double)> eval;
  double len_u, len_v;  // lengths of the parameter directions
  bool periodic_u = false, pole_v1 = false, curved = false, box = false;
  Vec3 inside;          // a point inside the body, for orientation
  std::size_t nu = 1, nv = 1;
  std::array<double, 4> retract{0, 0, 0, 0};  // per side (v=0, u=1, v=1, u=0), in absolute length
  std::vector<int> sides() const
  {
    std::vector<int> s{0};
    if (!periodic_u) s.push_back(1);
    if (!pole_v1) s.push_back(2);
    if (!periodic_u) s.push_back(3);
    return s;
  }
  std::size_t side_segments(int side) const { return side % 2 == 0 ? nu : nv; }
  Vec3 side_mid(int side) const
  {
    switch (side) {
      case 0: return eval(0.5, 0);
      case 1: return eval(1, 0.5);
      case 2: return eval(0.5, 1);
      default: return eval(0, 0.5);
    }
  }
};

inline std::size_t gcd(std::size_t a, std::size_t b) { return b == 0 ? a : gcd(b, a % b); }

}  // namespace internal_cad

inline Tri_soup make_cad_soup(const Cad_options& o, std::uint64_t seed, Cad_result& res)
{
  using internal_cad::Patch;
  Random rng(seed);
  std::vector<Patch> patches;
  const Vec3 B0{0, 0, 0}, B1{2, 1.2, 0.8};
  const Vec3 box_mid = 0.5 * (B0 + B1);
  static const char* axis_name = "xyz";
  for (int c = 0; c < 3; ++c)
    for (int hi = 0; hi < 2; ++hi) {
      int ua = (c + 1) % 3, va = (c + 2) % 3;
      Patch p;
      p.name = std::string("box_") + (hi ? "+" : "-") + axis_name[c];
      p.eval = [=](double u, double v) {
        Vec3 q;
        q[c] = hi ? B1[c] : B0[c];
        q[ua] = B0[ua] + u * (B1[ua] - B0[ua]);
        q[va] = B0[va] + v * (B1[va] - B0[va]);
        return q;
      };
      p.len_u = B1[ua] - B0[ua];
      p.len_v = B1[va] - B0[va];
      p.box = true;
      p.inside = box_mid;
      patches.push_back(p);
    }
  const double cx = 3.2, cy = 0.6, R = 0.5, z1 = 1.0;
  const Vec3 silo_mid{cx, cy, 0.6};
  {
    Patch p;
    p.name = "silo_cylinder";
    p.eval = [=](double u, double v) {
      return Vec3{cx + R * dcos(2 * pi * u), cy + R * dsin(2 * pi * u), v * z1};
    };
    p.len_u = 2 * pi * R;
    p.len_v = z1;
    p.periodic_u = p.curved = true;
    p.inside = silo_mid;
    patches.push_back(p);
    p.name = "silo_cap";
    p.eval = [=](double u, double v) {
      double phi = v * pi / 2;
      return Vec3{cx + R * dcos(phi) * dcos(2 * pi * u), cy + R * dcos(phi) * dsin(2 * pi * u),
                  z1 + R * dsin(phi)};
    };
    p.len_v = pi * R / 2;
    p.pole_v1 = true;
    patches.push_back(p);
    p.name = "silo_bottom";
    p.eval = [=](double u, double v) {
      return Vec3{cx + R * (1 - v) * dcos(2 * pi * u), cy + R * (1 - v) * dsin(2 * pi * u), 0};
    };
    p.len_v = R;
    patches.push_back(p);
  }
  Vec3 lo{0, 0, 0}, hi{cx + R, 1.2, z1 + R};
  res.diagonal = norm(hi - lo);

  // Resolution: per patch and direction a multiplier 1, 2 or 3 on a common
  // spacing h, so that seams get 1:2, 1:3, 2:3 sample ratios; h fitted to the face budget.
  std::vector<std::array<int, 2>> mult(patches.size());
  for (auto& m : mult)
    for (int& k : m) {
      std::uint64_t r = rng.below(10);
      k = r < 5 ? 1 : (r < 8 ? 2 : 3);
    }
  auto count = [&](double h, bool assign) {
    double f = 0;
    for (std::size_t i = 0; i < patches.size(); ++i) {
      Patch& p = patches[i];
      std::size_t nu = std::max<std::size_t>(p.periodic_u ? 3 : 1, static_cast<std::size_t>(std::lround(p.len_u / h))) * mult[i][0];
      std::size_t nv = std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(p.len_v / h))) * mult[i][1];
      if (assign) { p.nu = nu; p.nv = nv; }
      f += 2.0 * nu * nv - (p.pole_v1 ? static_cast<double>(nu) : 0);
    }
    return f;
  };
  double h = 0.5;
  const double target = static_cast<double>(std::max<std::size_t>(o.faces, 200));
  for (int it = 0; it < 30; ++it) h *= std::sqrt(count(h, false) / target);
  count(h, true);

  // Seams: pair patch sides whose curves have the same midpoint.
  for (std::size_t a = 0; a < patches.size(); ++a)
    for (int sa : patches[a].sides())
      for (std::size_t b = a + 1; b < patches.size(); ++b)
        for (int sb : patches[b].sides()) {
          if (norm(patches[a].side_mid(sa) - patches[b].side_mid(sb)) > 1e-9) continue;
          Cad_seam s{static_cast<int>(a), sa, static_cast<int>(b), sb, patches[a].side_segments(sa),
                     patches[b].side_segments(sb), patches[a].curved || patches[b].curved, false, 0, 0};
          std::size_t g = internal_cad::gcd(s.segments_a, s.segments_b);
          s.unmatched = (s.segments_a - g) + (s.segments_b - g);
          res.seams.push_back(s);
        }
  // Narrow gaps: one side of some seams retracted into its patch by 1-3 G
  // (never more than 40 % of that patch's row spacing).
  std::size_t want_gaps = static_cast<std::size_t>(std::lround(o.gap_fraction * res.seams.size()));
  if (o.gap_fraction > 0 && want_gaps == 0) want_gaps = 1;
  for (std::size_t k = 0; k < want_gaps && k < res.seams.size(); ++k) {
    std::size_t i = k + rng.below(res.seams.size() - k);  // partial shuffle: pick distinct seams
    std::swap(res.seams[k], res.seams[i]);
    Cad_seam& s = res.seams[k];
    bool side_b = rng.below(2) == 1;
    Patch& p = patches[side_b ? s.patch_b : s.patch_a];
    int side = side_b ? s.side_b : s.side_a;
    double spacing = side % 2 == 0 ? p.len_v / p.nv : p.len_u / p.nu;
    double w = std::min(rng.uniform(1, 3) * std::max(o.perturbation, 1e-6) * res.diagonal, 0.4 * spacing);
    p.retract[side] = w;
    s.gap = true;
    s.gap_width = w;
    res.max_gap = std::max(res.max_gap, w);
  }
  std::sort(res.seams.begin(), res.seams.end(), [](const Cad_seam& x, const Cad_seam& y) {
    return std::make_pair(x.patch_a, x.side_a) < std::make_pair(y.patch_a, y.side_a);
  });
  for (const Cad_seam& s : res.seams) {
    if (s.curved) res.curved_unmatched_vertices += s.unmatched;
    else res.t_junction_vertices += s.unmatched;
  }

  // Tessellation, patch by patch, each with its own vertices.
  Tri_soup soup;
  const double G = o.perturbation * res.diagonal;
  std::vector<char> interior_vertex;  // not on a seam: safe for local defects
  std::vector<char> box_face;         // box patch face whose first edge is an interior axis-aligned grid edge
  for (std::size_t pi_ = 0; pi_ < patches.size(); ++pi_) {
    const Patch& p = patches[pi_];
    const std::size_t cols = p.periodic_u ? p.nu : p.nu + 1;
    const std::size_t rows = p.pole_v1 ? p.nv : p.nv + 1;  // rows of grid vertices (pole apart)
    const std::uint32_t base = static_cast<std::uint32_t>(soup.points.size());
    for (std::size_t j = 0; j < rows; ++j)
      for (std::size_t i = 0; i < cols; ++i) {
        double u = static_cast<double>(i) / p.nu, v = static_cast<double>(j) / p.nv;
        bool bnd = j == 0 || (!p.pole_v1 && j == p.nv) || (!p.periodic_u && (i == 0 || i == p.nu));
        if (j == 0) v += p.retract[0] / p.len_v;
        if (!p.pole_v1 && j == p.nv) v -= p.retract[2] / p.len_v;
        if (!p.periodic_u && i == p.nu) u -= p.retract[1] / p.len_u;
        if (!p.periodic_u && i == 0) u += p.retract[3] / p.len_u;
        Vec3 q = p.eval(u, v);
        if (bnd && G > 0) q = q + (G * rng.uniform()) * rng.direction();
        soup.points.push_back(q);
        interior_vertex.push_back(!bnd);
      }
    std::uint32_t pole = 0;
    if (p.pole_v1) {
      pole = static_cast<std::uint32_t>(soup.points.size());
      soup.points.push_back(p.eval(0, 1));
      interior_vertex.push_back(1);
    }
    auto id = [&](std::size_t i, std::size_t j) {
      if (p.pole_v1 && j == p.nv) return pole;
      return static_cast<std::uint32_t>(base + j * cols + (i % (p.periodic_u ? p.nu : p.nu + 1)));
    };
    const std::size_t first_face = soup.faces.size();
    auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, bool axis_edge) {
      // convex bodies: orient every face away from the body's inside point
      Vec3 n = cross(soup.points[b] - soup.points[a], soup.points[c] - soup.points[a]);
      Vec3 cen = (1.0 / 3) * (soup.points[a] + soup.points[b] + soup.points[c]);
      bool flip = dot(n, cen - p.inside) < 0;
      soup.faces.push_back(flip ? Tri{b, a, c} : Tri{a, b, c});  // flipping keeps edge a-b first
      box_face.push_back(axis_edge && p.box);
    };
    for (std::size_t j = 0; j < p.nv; ++j)
      for (std::size_t i = 0; i < p.nu; ++i) {
        std::uint32_t p00 = id(i, j), p10 = id(i + 1, j), p11 = id(i + 1, j + 1), p01 = id(i, j + 1);
        if (p.pole_v1 && j + 1 == p.nv) {
          add(p00, p10, pole, false);
          continue;
        }
        bool interior_row = j > 0;  // edge p00-p10 off the seam and unperturbed
        add(p00, p10, p11, interior_row);
        add(p00, p11, p01, false);
      }
    res.patch_names.push_back(p.name);
    res.patch_faces.push_back(soup.faces.size() - first_face);
    // boundary edges of this patch: edges with one face in it
    std::vector<std::uint64_t> keys;
    for (std::size_t f = first_face; f < soup.faces.size(); ++f)
      for (int k = 0; k < 3; ++k) {
        std::uint64_t a = soup.faces[f][k], b = soup.faces[f][(k + 1) % 3];
        keys.push_back((std::min(a, b) << 32) | std::max(a, b));
      }
    std::sort(keys.begin(), keys.end());
    std::size_t boundary = 0;
    for (std::size_t i = 0; i < keys.size();) {
      std::size_t j = i;
      while (j < keys.size() && keys[j] == keys[i]) ++j;
      if (j - i == 1) ++boundary;
      i = j;
    }
    res.patch_boundary_edges.push_back(boundary);
    res.seam_edges += boundary;
  }

  // Soup defects, each on its own untouched faces and vertices.
  const std::size_t F = soup.faces.size();
  std::vector<char> busy_vertex(soup.points.size(), 0);
  auto pick_face = [&](bool need_box, bool need_interior) -> std::uint32_t {
    for (int attempt = 0; attempt < 10000; ++attempt) {
      std::uint32_t f = static_cast<std::uint32_t>(rng.below(F));
      if (need_box && !box_face[f]) continue;
      bool ok = true;
      for (std::uint32_t v : soup.faces[f]) ok = ok && !busy_vertex[v] && (!need_interior || interior_vertex[v]);
      if (!ok) continue;
      for (std::uint32_t v : soup.faces[f]) busy_vertex[v] = 1;
      return f;
    }
    return 0xffffffffu;
  };
  auto add_point = [&](const Vec3& q) {
    soup.points.push_back(q);
    busy_vertex.push_back(1);
    return static_cast<std::uint32_t>(soup.points.size() - 1);
  };
  auto add_face = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    soup.faces.push_back({a, b, c});
    return static_cast<std::uint32_t>(soup.faces.size() - 1);
  };
  auto face_centroid = [&](std::uint32_t f) {
    const Tri& t = soup.faces[f];
    return (1.0 / 3) * (soup.points[t[0]] + soup.points[t[1]] + soup.points[t[2]]);
  };
  auto unit_normal = [&](std::uint32_t f) {
    const Tri& t = soup.faces[f];
    return normalized(cross(soup.points[t[1]] - soup.points[t[0]], soup.points[t[2]] - soup.points[t[0]]));
  };
  // Defects stay off the seams, so that each one's effect on the counts is exact.
  for (std::size_t k = 0; k < o.flipped; ++k) {
    std::uint32_t f = pick_face(false, true);  // interior: 3 inconsistently oriented edges
    if (f == 0xffffffffu) break;
    std::swap(soup.faces[f][1], soup.faces[f][2]);
    res.defects.push_back({"flipped_face", "reversed", {}, {f}, face_centroid(f)});
  }
  for (std::size_t k = 0; k < o.duplicates; ++k) {
    std::uint32_t f = pick_face(false, true);  // interior: each copy makes exactly 3 non-manifold edges
    if (f == 0xffffffffu) break;
    Tri t = soup.faces[f];
    int r = static_cast<int>(rng.below(3));  // same face, cyclically rotated
    std::uint32_t g = add_face(t[r], t[(r + 1) % 3], t[(r + 2) % 3]);
    res.defects.push_back({"duplicate_face", r == 0 ? "identical" : "rotated", {}, {f, g}, face_centroid(f)});
  }
  for (std::size_t k = 0; k < o.degenerate; ++k) {
    bool collinear = k % 2 == 0;
    std::uint32_t f = pick_face(collinear, true);
    if (f == 0xffffffffu) break;
    Tri t = soup.faces[f];
    if (collinear) {
      // split the face at the exact midpoint of its axis-aligned first edge:
      // (a,b,c) -> (a,m,c), (m,b,c) and the zero-area (a,b,m)
      std::uint32_t a = t[0], b = t[1], c = t[2];
      Vec3 m = soup.points[a];
      for (int d = 0; d < 3; ++d)
        if (soup.points[a][d] != soup.points[b][d]) m[d] = 0.5 * (soup.points[a][d] + soup.points[b][d]);
      std::uint32_t mid = add_point(m);
      soup.faces[f] = {a, mid, c};
      std::uint32_t g = add_face(mid, b, c), d = add_face(a, b, mid);
      res.defects.push_back({"degenerate_face", "collinear", {mid}, {d, f, g}, m});
    } else {
      std::uint32_t d = add_face(t[0], t[1], t[1]);
      res.defects.push_back({"degenerate_face", "repeated_index", {t[0], t[1]}, {d}, face_centroid(f)});
    }
  }
  for (std::size_t k = 0; k < o.fins; ++k) {
    std::uint32_t f = pick_face(false, true);
    if (f == 0xffffffffu) break;
    Tri t = soup.faces[f];
    Vec3 a = soup.points[t[0]], b = soup.points[t[1]];
    Vec3 apex = 0.5 * (a + b) + (0.8 * norm(b - a)) * unit_normal(f);
    std::uint32_t x = add_point(apex);
    std::uint32_t g = add_face(t[1], t[0], x);  // a third face on edge t0-t1
    res.defects.push_back({"fin", "third_face_on_edge", {t[0], t[1], x}, {g}, apex});
  }
  for (std::size_t k = 0; k < o.pinched; ++k) {
    std::uint32_t f = pick_face(false, true);
    if (f == 0xffffffffu) break;
    Tri t = soup.faces[f];
    Vec3 v = soup.points[t[0]], n = unit_normal(f);
    double s = norm(soup.points[t[1]] - v);
    Vec3 e1 = normalized(soup.points[t[1]] - v), e2 = cross(n, e1);
    std::uint32_t x = add_point(v + s * (0.7 * n + 0.4 * e1));
    std::uint32_t y = add_point(v + s * (0.7 * n + 0.4 * e2));
    std::uint32_t g = add_face(t[0], x, y);  // touches the surface at t[0] only
    res.defects.push_back({"pinched_vertex", "face_attached_by_one_vertex", {t[0], x, y}, {g}, v});
  }
  return soup;
}

/// options of the part mode (`make_cad_soup_from_part`).
struct Cad_part_options
{
  std::size_t patches = 48;    // patch size cap: faces / patches (sharp edges split further)
  double sharp_cos = 0.8660254037844386;  // cos 30 degrees: a dihedral turn above 30 degrees is a feature
  double perturbation = 1e-4;  // G: seam vertices moved by up to G * bbox diagonal (and 1/4 of their faces' heights)
  double gap_fraction = 0.3;   // share of patches shifted rigidly by 1-3 G (cracks)
  double refine_fraction = 0.5;  // share of seams whose one side gets its edges split (T-junctions)
};

struct Cad_part_result
{
  std::size_t patches = 0, sharp_patches = 0, seams = 0, refined_seams = 0, shifted_patches = 0;
  std::size_t clean_boundary_edges = 0;  // of the (upsampled) clean part: not seams
  std::size_t seam_edges = 0;            // boundary edges of the soup that are seams
  std::size_t t_junction_vertices = 0;   // seam vertices of one side not at a vertex of the other
  double diagonal = 0, max_gap = 0, perturbation_absolute = 0;
};

/// turns a clean triangle mesh (a real part) into a CAD-like soup: patches
/// grown from random seeds up to a size cap and never across a sharp edge,
/// each owning its vertices; seam vertices perturbed; on some seams one side's
/// edges split at (perturbed) midpoints, so that its new vertices lie on the
/// other side's edges (T-junctions); some patches shifted rigidly (cracks).
inline Tri_soup make_cad_soup_from_part(const Tri_soup& part, const Cad_part_options& o,
                                        std::uint64_t seed, Cad_part_result& res)
{
  Random rng(seed);
  const std::size_t F = part.faces.size(), V = part.points.size();
  Vec3 lo = part.points.empty() ? Vec3{0, 0, 0} : part.points[0], hi = lo;
  for (const Vec3& p : part.points)
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], p[d]);
      hi[d] = std::max(hi[d], p[d]);
    }
  res.diagonal = norm(hi - lo);
  const double G = o.perturbation * res.diagonal;
  res.perturbation_absolute = G;

  // edge -> faces (sorted keys); a manifold edge has two entries
  std::vector<std::pair<std::uint64_t, std::uint32_t>> ef(3 * F);
  for (std::size_t f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) {
      std::uint64_t a = part.faces[f][k], b = part.faces[f][(k + 1) % 3];
      ef[3 * f + k] = {(std::min(a, b) << 32) | std::max(a, b), static_cast<std::uint32_t>(f)};
    }
  std::sort(ef.begin(), ef.end());
  const std::uint32_t none = 0xffffffffu;
  std::vector<std::array<std::uint32_t, 3>> nbr(F, {none, none, none});  // across edge k
  auto edge_slot = [&](std::uint32_t f, std::uint64_t key) {
    for (int k = 0; k < 3; ++k) {
      std::uint64_t a = part.faces[f][k], b = part.faces[f][(k + 1) % 3];
      if (((std::min(a, b) << 32) | std::max(a, b)) == key) return k;
    }
    return 0;
  };
  for (std::size_t i = 0; i < ef.size();) {
    std::size_t j = i;
    while (j < ef.size() && ef[j].first == ef[i].first) ++j;
    if (j - i == 1) ++res.clean_boundary_edges;
    if (j - i == 2) {
      std::uint32_t f = ef[i].second, g = ef[i + 1].second;
      nbr[f][edge_slot(f, ef[i].first)] = g;
      nbr[g][edge_slot(g, ef[i].first)] = f;
    }
    i = j;
  }
  std::vector<Vec3> fn(F);
  std::vector<double> min_height(V, std::numeric_limits<double>::max());
  for (std::size_t f = 0; f < F; ++f) {
    const Tri& t = part.faces[f];
    Vec3 n = cross(part.points[t[1]] - part.points[t[0]], part.points[t[2]] - part.points[t[0]]);
    double longest = std::max({norm(part.points[t[1]] - part.points[t[0]]), norm(part.points[t[2]] - part.points[t[1]]),
                               norm(part.points[t[0]] - part.points[t[2]])});
    double h = longest > 0 ? norm(n) / longest : 0;
    for (std::uint32_t v : t) min_height[v] = std::min(min_height[v], h);
    fn[f] = normalized(n);
  }

  // region growing: seeds in a shuffled order, breadth first, not across sharp edges
  std::vector<std::uint32_t> order(F);
  std::iota(order.begin(), order.end(), 0u);
  for (std::size_t i = F; i > 1; --i) std::swap(order[i - 1], order[rng.below(i)]);
  const std::size_t cap = std::max<std::size_t>(50, F / std::max<std::size_t>(1, o.patches));
  std::vector<std::uint32_t> patch(F, none);
  std::vector<std::uint32_t> queue;
  std::uint32_t np = 0;
  for (std::uint32_t s : order) {
    if (patch[s] != none) continue;
    queue.assign(1, s);
    patch[s] = np;
    bool stopped_by_feature = false;
    for (std::size_t q = 0; q < queue.size() && queue.size() < cap; ++q) {
      std::uint32_t f = queue[q];
      for (int k = 0; k < 3 && queue.size() < cap; ++k) {
        std::uint32_t g = nbr[f][k];
        if (g == none || patch[g] != none) continue;
        if (dot(fn[f], fn[g]) < o.sharp_cos) {
          stopped_by_feature = true;
          continue;
        }
        patch[g] = np;
        queue.push_back(g);
      }
    }
    res.sharp_patches += stopped_by_feature;
    ++np;
  }
  res.patches = np;

  // seams: patch pairs sharing edges; one side of some gets split edges
  std::vector<std::uint64_t> seam_keys;
  for (std::size_t f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) {
      std::uint32_t g = nbr[f][k];
      if (g != none && patch[g] != patch[f] && patch[f] < patch[g])
        seam_keys.push_back((std::uint64_t(patch[f]) << 32) | patch[g]);
    }
  std::sort(seam_keys.begin(), seam_keys.end());
  seam_keys.erase(std::unique(seam_keys.begin(), seam_keys.end()), seam_keys.end());
  res.seams = seam_keys.size();
  std::vector<std::uint32_t> refined_side(seam_keys.size(), none);  // the patch whose edges are split
  for (std::size_t i = 0; i < seam_keys.size(); ++i)
    if (rng.uniform() < o.refine_fraction) {
      refined_side[i] = rng.below(2) ? std::uint32_t(seam_keys[i] >> 32) : std::uint32_t(seam_keys[i] & 0xffffffffu);
      ++res.refined_seams;
    }
  std::vector<Vec3> shift(np, Vec3{0, 0, 0});
  for (std::uint32_t p = 0; p < np; ++p)
    if (rng.uniform() < o.gap_fraction) {
      double w = rng.uniform(1, 3) * G;
      shift[p] = w * rng.direction();
      res.max_gap = std::max(res.max_gap, w);
      ++res.shifted_patches;
    }

  // faces grouped by patch; each patch owns copies of its vertices
  std::vector<std::uint32_t> by_patch(F);
  std::iota(by_patch.begin(), by_patch.end(), 0u);
  std::stable_sort(by_patch.begin(), by_patch.end(), [&](std::uint32_t a, std::uint32_t b) { return patch[a] < patch[b]; });
  Tri_soup soup;
  std::vector<std::uint32_t> stamp(V, none), copy(V, none);
  std::vector<char> seam_vertex(V, 0);
  for (std::size_t f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k)
      if (nbr[f][k] != none && patch[nbr[f][k]] != patch[f])
        seam_vertex[part.faces[f][k]] = seam_vertex[part.faces[f][(k + 1) % 3]] = 1;
  auto perturbed = [&](const Vec3& q, double height) {
    double g = std::min(G, 0.25 * height);
    return g > 0 ? q + (g * rng.uniform()) * rng.direction() : q;
  };
  for (std::uint32_t f : by_patch) {
    const std::uint32_t p = patch[f];
    Tri t;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t v = part.faces[f][k];
      if (stamp[v] != p) {
        stamp[v] = p;
        copy[v] = static_cast<std::uint32_t>(soup.points.size());
        Vec3 q = seam_vertex[v] ? perturbed(part.points[v], min_height[v]) : part.points[v];
        soup.points.push_back(q + shift[p]);
      }
      t[k] = copy[v];
    }
    // split the one edge of this face on a refined seam side (faces with several: left whole)
    int split = -1, count = 0;
    for (int k = 0; k < 3; ++k) {
      std::uint32_t g = nbr[f][k];
      if (g == none || patch[g] == p) continue;
      std::uint64_t key = (std::uint64_t(std::min(p, patch[g])) << 32) | std::max(p, patch[g]);
      std::size_t i = std::lower_bound(seam_keys.begin(), seam_keys.end(), key) - seam_keys.begin();
      if (refined_side[i] == p) {
        split = k;
        ++count;
      }
    }
    if (count != 1) {
      soup.faces.push_back(t);
      continue;
    }
    const std::uint32_t a = t[split], b = t[(split + 1) % 3], c = t[(split + 2) % 3];
    const std::uint32_t oa = part.faces[f][split], ob = part.faces[f][(split + 1) % 3];
    Vec3 m = 0.5 * (part.points[oa] + part.points[ob]);
    std::uint32_t mid = static_cast<std::uint32_t>(soup.points.size());
    soup.points.push_back(perturbed(m, 0.5 * std::min(min_height[oa], min_height[ob])) + shift[p]);
    soup.faces.push_back({a, mid, c});
    soup.faces.push_back({mid, b, c});
    ++res.t_junction_vertices;
  }
  // seam edges: boundary edges of the soup that were not boundary in the part
  std::vector<std::uint64_t> keys;
  keys.reserve(3 * soup.faces.size());
  for (const Tri& t : soup.faces)
    for (int k = 0; k < 3; ++k) {
      std::uint64_t a = t[k], b = t[(k + 1) % 3];
      keys.push_back((std::min(a, b) << 32) | std::max(a, b));
    }
  std::sort(keys.begin(), keys.end());
  std::size_t boundary = 0;
  for (std::size_t i = 0; i < keys.size();) {
    std::size_t j = i;
    while (j < keys.size() && keys[j] == keys[i]) ++j;
    boundary += j - i == 1;
    i = j;
  }
  res.seam_edges = boundary - res.clean_boundary_edges;
  return soup;
}

}  // namespace generator
}  // namespace mrepair

#endif  // MREPAIR_TOOLS_GENERATOR_CAD_H
