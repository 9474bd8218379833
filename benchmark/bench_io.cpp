// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Tasks "read_soup" and "read_mesh": mrepair's readers beside CGAL 5.5's
// CGAL::IO::read_polygon_soup and CGAL::IO::read_polygon_mesh (any format both
// read: OFF, OBJ, PLY, STL). The timed section is the whole read, file to
// memory. mrepair's mesh read also checks that the soup is a polygon mesh
// (CGAL's does not, so "CGAL check+build" adds PMP::is_polygon_soup_a_polygon_mesh
// and polygon_soup_to_polygon_mesh after its soup read, the equivalent work).
#include "bench.h"

#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#include <string>
#include <vector>

namespace {

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;
using mrepair::bench::Measurement;

void counts(Measurement& m, std::size_t points, std::size_t polygons)
{
  m.after.add("points", points);
  m.after.add("polygons", polygons);
}

Measurement soup_mrepair(const std::string& input)
{
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  mrepair::Io_result r = mrepair::read_polygon_soup(input, pts, polys);
  t.stop();
  out.seconds = t.time();
  out.status = mrepair::to_string(r.status);
  r.to_report(out.result);
  counts(out, pts.size(), polys.size());
  return out;
}

Measurement soup_cgal(const std::string& input)
{
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  bool ok = CGAL::IO::read_polygon_soup(input, pts, polys);
  t.stop();
  out.seconds = t.time();
  out.status = ok ? "ok" : "failed";
  counts(out, pts.size(), polys.size());
  return out;
}

Measurement mesh_mrepair(const std::string& input)
{
  Mesh m;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  mrepair::Io_result r = mrepair::read_polygon_mesh(input, m);
  t.stop();
  out.seconds = t.time();
  out.status = mrepair::to_string(r.status);
  r.to_report(out.result);
  counts(out, vertices(m).size(), faces(m).size());
  return out;
}

Measurement mesh_cgal(const std::string& input)
{
  Mesh m;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  bool ok = CGAL::IO::read_polygon_mesh(input, m);
  t.stop();
  out.seconds = t.time();
  out.status = ok ? "ok" : "failed";
  counts(out, vertices(m).size(), faces(m).size());
  return out;
}

Measurement mesh_cgal_checked(const std::string& input)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  Mesh m;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  bool ok = CGAL::IO::read_polygon_soup(input, pts, polys) &&
            PMP::is_polygon_soup_a_polygon_mesh(polys);
  if (ok) PMP::polygon_soup_to_polygon_mesh(pts, polys, m);
  t.stop();
  out.seconds = t.time();
  out.status = ok ? "ok" : "failed";
  counts(out, vertices(m).size(), faces(m).size());
  return out;
}

mrepair::bench::Task_registrar reg_soup{
    {"read_soup",
     "read a polygon soup (OFF/OBJ/PLY/STL)",
     {{"mrepair::read_polygon_soup", soup_mrepair}, {"CGAL::IO::read_polygon_soup", soup_cgal}}}};

mrepair::bench::Task_registrar reg_mesh{
    {"read_mesh",
     "read a Surface_mesh (OFF/OBJ/PLY/STL), checked to be a polygon mesh",
     {{"mrepair::read_polygon_mesh", mesh_mrepair},
      {"CGAL::IO::read_polygon_mesh", mesh_cgal},
      {"CGAL check+build", mesh_cgal_checked}}}};

} // namespace
