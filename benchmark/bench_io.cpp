// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// I/O tasks: mrepair's readers and writers beside CGAL's on the same file.
//
//   read_soup   mrepair::read_polygon_soup, CGAL::IO::read_polygon_soup and
//               the format's own CGAL reader (read_OFF / read_OBJ / read_PLY /
//               read_STL); file to memory
//   read_mesh   mrepair::read_polygon_mesh, CGAL::IO::read_polygon_mesh, and
//               CGAL's soup read + is_polygon_soup_a_polygon_mesh +
//               polygon_soup_to_polygon_mesh (the work mrepair's mesh read does)
//   write_soup  the input read untimed (by mrepair), then written in its
//               format and encoding to a scratch file beside /tmp by
//               mrepair::write_polygon_soup, CGAL::IO::write_polygon_soup and
//               the format's own CGAL writer (ASCII at 17 digits, as mrepair's
//               shortest round-trip text); memory to file
//
// Every variant reports `mb_per_s` (input bytes for reads, output bytes for
// writes, per second of the timed section) and `threads`. MREPAIR_THREADS=N
// limits TBB to N threads (mrepair's parallel parsing and formatting).
#include "bench.h"

#include <mrepair/io.h>

#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/OBJ.h>
#include <CGAL/IO/OFF.h>
#include <CGAL/IO/PLY.h>
#include <CGAL/IO/STL.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Real_timer.h>
#include <CGAL/Surface_mesh.h>
#include <CGAL/boost/graph/IO/polygon_mesh_io.h>

#ifdef CGAL_LINKED_WITH_TBB
#include <tbb/global_control.h>
#include <tbb/task_arena.h>
#endif

#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <string>
#include <vector>

namespace {
namespace io_task {  // a namespace of its own: the harness is a unity build

using K = CGAL::Epick;
using Point = K::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
using Polygon = std::vector<std::size_t>;
using mrepair::bench::Measurement;

/// the thread limit of MREPAIR_THREADS, held for the variant's lifetime.
struct Threads
{
#ifdef CGAL_LINKED_WITH_TBB
  std::unique_ptr<tbb::global_control> control;
#endif
  std::size_t count = 1;
  Threads()
  {
#ifdef CGAL_LINKED_WITH_TBB
    if (const char* t = std::getenv("MREPAIR_THREADS"))
      if (std::atoi(t) > 0)
        control = std::make_unique<tbb::global_control>(
            tbb::global_control::max_allowed_parallelism, static_cast<std::size_t>(std::atoi(t)));
    count = static_cast<std::size_t>(tbb::this_task_arena::max_concurrency());
    if (control)
      count = std::min(count, tbb::global_control::active_value(
                                  tbb::global_control::max_allowed_parallelism));
#endif
  }
};

std::string extension(const std::string& path)
{
  std::string e = std::filesystem::path(path).extension().string();
  for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return e.empty() ? e : e.substr(1);
}

/// whether `path` is a binary PLY or STL (sniffed, untimed).
bool is_binary(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::string head(1024, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<std::size_t>(in.gcount()));
  const std::string ext = extension(path);
  if (ext == "ply") return head.find("format ascii") == std::string::npos;
  if (ext == "stl") {
    const auto size = std::filesystem::file_size(path);
    std::uint32_t n = 0;
    if (head.size() >= 84) std::memcpy(&n, head.data() + 80, 4);
    return head.compare(0, 5, "solid") != 0 || size == 84 + 50 * std::uint64_t(n);
  }
  return false;
}

void finish(Measurement& m, const CGAL::Real_timer& t, std::uintmax_t bytes, const Threads& th,
            std::size_t points, std::size_t polygons)
{
  m.seconds = t.time();
  m.result.add("mb_per_s", m.seconds > 0 ? static_cast<double>(bytes) / 1e6 / m.seconds : 0.0);
  m.result.add("threads", th.count);
  m.after.add("points", points);
  m.after.add("polygons", polygons);
}

// ---- read_soup ----------------------------------------------------------------

Measurement soup_mrepair(const std::string& input)
{
  Threads th;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  mrepair::Io_result r = mrepair::read_polygon_soup(input, pts, polys);
  t.stop();
  out.status = mrepair::to_string(r.status);
  r.to_report(out.result);
  finish(out, t, std::filesystem::file_size(input), th, pts.size(), polys.size());
  return out;
}

Measurement soup_cgal(const std::string& input)
{
  Threads th;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  bool ok = CGAL::IO::read_polygon_soup(input, pts, polys);
  t.stop();
  out.status = ok ? "ok" : "failed";
  finish(out, t, std::filesystem::file_size(input), th, pts.size(), polys.size());
  return out;
}

Measurement soup_cgal_format(const std::string& input)
{
  Threads th;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  const std::string ext = extension(input);
  const bool binary = is_binary(input);
  const auto np = CGAL::parameters::use_binary_mode(binary);
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  bool ok = false;
  if (ext == "off")
    ok = CGAL::IO::read_OFF(input, pts, polys);
  else if (ext == "obj")
    ok = CGAL::IO::read_OBJ(input, pts, polys);
  else if (ext == "ply")
    ok = CGAL::IO::read_PLY(input, pts, polys, np);
  else if (ext == "stl")
    ok = CGAL::IO::read_STL(input, pts, polys, np);
  t.stop();
  out.status = ok ? "ok" : "failed";
  finish(out, t, std::filesystem::file_size(input), th, pts.size(), polys.size());
  return out;
}

// ---- read_mesh ----------------------------------------------------------------

Measurement mesh_mrepair(const std::string& input)
{
  Threads th;
  Mesh m;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  mrepair::Io_result r = mrepair::read_polygon_mesh(input, m);
  t.stop();
  out.status = mrepair::to_string(r.status);
  r.to_report(out.result);
  finish(out, t, std::filesystem::file_size(input), th, vertices(m).size(), faces(m).size());
  return out;
}

Measurement mesh_cgal(const std::string& input)
{
  Threads th;
  Mesh m;
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  bool ok = CGAL::IO::read_polygon_mesh(input, m);
  t.stop();
  out.status = ok ? "ok" : "failed";
  finish(out, t, std::filesystem::file_size(input), th, vertices(m).size(), faces(m).size());
  return out;
}

Measurement mesh_cgal_checked(const std::string& input)
{
  namespace PMP = CGAL::Polygon_mesh_processing;
  Threads th;
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
  out.status = ok ? "ok" : "failed";
  finish(out, t, std::filesystem::file_size(input), th, vertices(m).size(), faces(m).size());
  return out;
}

// ---- write_soup ---------------------------------------------------------------

/// a scratch output path in the input's format, removed afterwards.
struct Scratch
{
  std::string path;
  explicit Scratch(const std::string& input)
      : path((std::filesystem::temp_directory_path() /
              ("mrepair_bench_io_" + std::to_string(::getpid()) + "." + extension(input)))
                 .string())
  {}
  ~Scratch()
  {
    std::error_code ec;
    std::filesystem::remove(path, ec);
  }
  std::uintmax_t size() const
  {
    std::error_code ec;
    auto s = std::filesystem::file_size(path, ec);
    return ec ? 0 : s;
  }
};

/// writes the input's soup with `write(path, points, polygons, binary)`, timed.
template <typename Write>
Measurement write_with(const std::string& input, const Write& write)
{
  Threads th;
  std::vector<Point> pts;
  std::vector<Polygon> polys;
  mrepair::read_polygon_soup(input, pts, polys);
  const bool binary = is_binary(input);
  Scratch out_file(input);
  Measurement out;
  CGAL::Real_timer t;
  t.start();
  const std::string status = write(out_file.path, pts, polys, binary);
  t.stop();
  out.status = status;
  out.result.add("binary", binary);
  out.result.add("bytes", static_cast<std::size_t>(out_file.size()));
  finish(out, t, out_file.size(), th, pts.size(), polys.size());
  return out;
}

Measurement write_mrepair(const std::string& input)
{
  return write_with(input, [](const std::string& path, const std::vector<Point>& pts,
                              const std::vector<Polygon>& polys, bool binary) {
    return std::string(mrepair::to_string(mrepair::write_polygon_soup(path, pts, polys, binary).status));
  });
}

Measurement write_cgal(const std::string& input)
{
  return write_with(input, [](const std::string& path, const std::vector<Point>& pts,
                              const std::vector<Polygon>& polys, bool binary) {
    const auto np = CGAL::parameters::use_binary_mode(binary).stream_precision(17);
    return std::string(CGAL::IO::write_polygon_soup(path, pts, polys, np) ? "ok" : "failed");
  });
}

Measurement write_cgal_format(const std::string& input)
{
  return write_with(input, [&input](const std::string& path, const std::vector<Point>& pts,
                                    const std::vector<Polygon>& polys, bool binary) {
    const auto np = CGAL::parameters::use_binary_mode(binary).stream_precision(17);
    const std::string ext = extension(input);
    bool ok = false;
    if (ext == "off")
      ok = CGAL::IO::write_OFF(path, pts, polys, np);
    else if (ext == "obj")
      ok = CGAL::IO::write_OBJ(path, pts, polys, np);
    else if (ext == "ply")
      ok = CGAL::IO::write_PLY(path, pts, polys, np);
    else if (ext == "stl")
      ok = CGAL::IO::write_STL(path, pts, polys, np);
    return std::string(ok ? "ok" : "failed");
  });
}

mrepair::bench::Task_registrar reg_soup{
    {"read_soup",
     "read a polygon soup (OFF/OBJ/PLY/STL); mb_per_s of the input",
     {{"mrepair::read_polygon_soup", soup_mrepair},
      {"CGAL::IO::read_polygon_soup", soup_cgal},
      {"CGAL::IO::read_<format>", soup_cgal_format}}}};

mrepair::bench::Task_registrar reg_mesh{
    {"read_mesh",
     "read a Surface_mesh (OFF/OBJ/PLY/STL), checked to be a polygon mesh",
     {{"mrepair::read_polygon_mesh", mesh_mrepair},
      {"CGAL::IO::read_polygon_mesh", mesh_cgal},
      {"CGAL check+build", mesh_cgal_checked}}}};

mrepair::bench::Task_registrar reg_write{
    {"write_soup",
     "write the input's soup in its format and encoding; mb_per_s of the output",
     {{"mrepair::write_polygon_soup", write_mrepair},
      {"CGAL::IO::write_polygon_soup", write_cgal},
      {"CGAL::IO::write_<format>", write_cgal_format}}}};

} // namespace io_task
} // namespace
