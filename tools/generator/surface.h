// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Defect generator: clean input surfaces. A procedural closed genus-0 surface
// (a bumpy geodesic sphere), and 1-to-4 midpoint subdivision to upsample a
// loaded mesh.
#ifndef MREPAIR_TOOLS_GENERATOR_SURFACE_H
#define MREPAIR_TOOLS_GENERATOR_SURFACE_H

#include "generator/common.h"

namespace mrepair {
namespace generator {

/// smooth closed genus-0 surface with 20 n^2 triangles: an icosahedron whose
/// faces are split n x n (valence 6 except 12 vertices of valence 5, nearly
/// equilateral, as a scanner's reconstruction), projected to the unit sphere,
/// radius modulated by a few low-frequency bumps, then mildly stretched.
inline Tri_soup bumpy_sphere(std::size_t n)
{
  n = std::max<std::size_t>(std::min<std::size_t>(n, 60000), 1);
  const double phi = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3> ico;
  for (int a = -1; a <= 1; a += 2)
    for (int b = -1; b <= 1; b += 2) {
      ico.push_back({0, double(a), b * phi});
      ico.push_back({double(a), b * phi, 0});
      ico.push_back({b * phi, 0, double(a)});
    }
  std::vector<std::array<int, 3>> ifaces;  // triples at mutual distance 2, oriented outwards
  for (int i = 0; i < 12; ++i)
    for (int j = i + 1; j < 12; ++j)
      for (int k = j + 1; k < 12; ++k) {
        auto close = [&](int x, int y) { return std::abs(norm(ico[x] - ico[y]) - 2) < 1e-9; };
        if (!close(i, j) || !close(j, k) || !close(i, k)) continue;
        Vec3 nrm = cross(ico[j] - ico[i], ico[k] - ico[i]);
        if (dot(nrm, ico[i] + ico[j] + ico[k]) > 0) ifaces.push_back({i, j, k});
        else ifaces.push_back({i, k, j});
      }
  // A lattice point is a weighted sum of icosahedron corners; its canonical
  // key (corners sorted, zero weights dropped) welds points on shared edges.
  auto key = [](std::array<std::pair<std::uint64_t, std::uint64_t>, 3> cw) {
    for (auto& p : cw)
      if (p.second == 0) p.first = 15;
    std::sort(cw.begin(), cw.end());
    std::uint64_t k = 0;
    for (auto& p : cw) k = (k << 20) | (p.first << 16) | p.second;
    return k;
  };
  auto face_key = [&](const std::array<int, 3>& f, std::size_t i, std::size_t j) {
    return key({std::make_pair(std::uint64_t(f[0]), std::uint64_t(n - i - j)),
                std::make_pair(std::uint64_t(f[1]), std::uint64_t(i)),
                std::make_pair(std::uint64_t(f[2]), std::uint64_t(j))});
  };
  std::vector<std::uint64_t> keys;
  keys.reserve(20 * (n + 1) * (n + 2) / 2);
  for (const auto& f : ifaces)
    for (std::size_t i = 0; i <= n; ++i)
      for (std::size_t j = 0; i + j <= n; ++j) keys.push_back(face_key(f, i, j));
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  auto id = [&](std::uint64_t k) {
    return static_cast<std::uint32_t>(std::lower_bound(keys.begin(), keys.end(), k) - keys.begin());
  };

  Tri_soup s;
  s.points.resize(keys.size());
  for (std::size_t v = 0; v < keys.size(); ++v) {
    Vec3 p{0, 0, 0};
    for (int t = 0; t < 3; ++t) {
      std::uint64_t part = (keys[v] >> (20 * (2 - t))) & 0xfffff;
      std::uint64_t corner = part >> 16, weight = part & 0xffff;
      if (corner < 12) p = p + (static_cast<double>(weight) / static_cast<double>(n)) * ico[corner];
    }
    Vec3 d = normalized(p);
    double r = 1 + 0.06 * dsin(3 * d[0] + 1) * dsin(4 * d[1] + 2) * dsin(5 * d[2] + 0.5) +
               0.03 * dcos(7 * d[0] - 2 * d[2]);
    s.points[v] = Vec3{1.15 * r * d[0], r * d[1], 0.9 * r * d[2]};
  }
  s.faces.reserve(20 * n * n);
  std::vector<std::uint32_t> local((n + 1) * (n + 1));  // ids of one face's lattice, searched once each
  for (const auto& f : ifaces) {
    for (std::size_t i = 0; i <= n; ++i)
      for (std::size_t j = 0; i + j <= n; ++j) local[i * (n + 1) + j] = id(face_key(f, i, j));
    auto at = [&](std::size_t i, std::size_t j) { return local[i * (n + 1) + j]; };
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = 0; i + j < n; ++j) {
        s.faces.push_back({at(i, j), at(i + 1, j), at(i, j + 1)});
        if (i + j + 1 < n) s.faces.push_back({at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)});
      }
  }
  return s;
}

/// the subdivision n of `bumpy_sphere` whose 20 n^2 faces are closest to `faces`.
inline std::size_t bumpy_sphere_resolution(std::size_t faces)
{
  std::size_t n = static_cast<std::size_t>(std::sqrt(static_cast<double>(faces) / 20.0));
  n = std::max<std::size_t>(n, 1);
  auto err = [faces](std::size_t k) { return std::abs(20.0 * k * k - static_cast<double>(faces)); };
  if (err(n + 1) < err(n)) ++n;
  return n;
}

/// 1-to-4 midpoint subdivision (new vertices at edge midpoints, shape unchanged).
inline void subdivide(Tri_soup& s)
{
  const std::size_t F = s.faces.size();
  std::vector<std::pair<std::uint64_t, std::uint32_t>> edges(3 * F);
  for (std::size_t f = 0; f < F; ++f)
    for (int k = 0; k < 3; ++k) {
      std::uint64_t a = s.faces[f][k], b = s.faces[f][(k + 1) % 3];
      if (a > b) std::swap(a, b);
      edges[3 * f + k] = {(a << 32) | b, static_cast<std::uint32_t>(3 * f + k)};
    }
  std::sort(edges.begin(), edges.end());
  std::vector<std::uint32_t> mid(3 * F);
  for (std::size_t i = 0; i < edges.size();) {
    std::uint64_t key = edges[i].first;
    std::uint32_t a = static_cast<std::uint32_t>(key >> 32), b = static_cast<std::uint32_t>(key & 0xffffffffu);
    std::uint32_t m = static_cast<std::uint32_t>(s.points.size());
    s.points.push_back(0.5 * (s.points[a] + s.points[b]));
    for (; i < edges.size() && edges[i].first == key; ++i) mid[edges[i].second] = m;
  }
  std::vector<Tri> out;
  out.reserve(4 * F);
  for (std::size_t f = 0; f < F; ++f) {
    std::uint32_t a = s.faces[f][0], b = s.faces[f][1], c = s.faces[f][2];
    std::uint32_t ab = mid[3 * f], bc = mid[3 * f + 1], ca = mid[3 * f + 2];
    out.push_back({a, ab, ca});
    out.push_back({b, bc, ab});
    out.push_back({c, ca, bc});
    out.push_back({ab, bc, ca});
  }
  s.faces.swap(out);
}

}  // namespace generator
}  // namespace mrepair

#endif  // MREPAIR_TOOLS_GENERATOR_SURFACE_H
