// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The defect generator (mrepair-generate): deterministic output, and the
// files it writes hold exactly the defects its manifest lists.
#include "fixtures.h"

#include <mrepair/inspect.h>
#include <mrepair/io.h>

#include <CGAL/Polygon_mesh_processing/border.h>
#include <CGAL/Polygon_mesh_processing/connected_components.h>
#include <CGAL/Polygon_mesh_processing/self_intersections.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>
#include <unistd.h>

// A namespace of its own: this file is compiled in one translation unit with
// other test files (a unity build, CMakeLists.txt).
namespace {
namespace generator_tests {

namespace {

namespace fs = std::filesystem;
using namespace mrepair_test;

#ifdef MREPAIR_GENERATOR
const char* generator_path() { return MREPAIR_GENERATOR; }
#else
const char* generator_path() { return nullptr; }
#endif

#define REQUIRE_GENERATOR()                                                   \
  if (!generator_path()) GTEST_SKIP() << "mrepair-generate was not built"

/// a scratch directory removed at the end of the test.
struct Temp_dir
{
  fs::path path;
  Temp_dir()
  {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path = fs::temp_directory_path() /
           ("mrepair_gen_" + std::to_string(::getpid()) + "_" + info->name());
    fs::remove_all(path);
    fs::create_directories(path);
  }
  ~Temp_dir() { std::error_code ec; fs::remove_all(path, ec); }
  std::string operator/(const std::string& f) const { return (path / f).string(); }
};

int run_generator(const std::string& args)
{
  std::string cmd = std::string("\"") + generator_path() + "\" " + args + " --quiet 2>/dev/null";
  int rc = std::system(cmd.c_str());
  return WIFEXITED(rc) ? WEXITSTATUS(rc) : -1;
}

std::string slurp(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// the number after `"key": ` inside the object `"section": {...}` of the
/// manifest (the generator writes flat sections, one key per line); -1 when absent.
double manifest_number(const std::string& json, const std::string& section, const std::string& key)
{
  std::size_t s = json.find("\"" + section + "\": {");
  if (s == std::string::npos) return -1;
  std::size_t e = json.find('}', s);
  std::size_t k = json.find("\"" + key + "\": ", s);
  if (k == std::string::npos || k > e) return -1;
  return std::strtod(json.c_str() + k + key.size() + 4, nullptr);
}
std::size_t manifest_count(const std::string& json, const std::string& section, const std::string& key)
{
  double v = manifest_number(json, section, key);
  EXPECT_GE(v, 0) << section << "." << key << " missing from the manifest";
  return v < 0 ? 0 : static_cast<std::size_t>(v);
}

/// the defect objects of the manifest: kind, vertex ids, face ids.
struct Listed_defect
{
  std::string kind;
  std::vector<std::size_t> vertices, faces;
};
std::vector<std::size_t> id_list(const std::string& text)
{
  std::vector<std::size_t> ids;
  std::istringstream in(text);
  std::string tok;
  while (std::getline(in, tok, ','))
    if (tok.find_first_of("0123456789") != std::string::npos) ids.push_back(std::stoul(tok));
  return ids;
}
std::vector<Listed_defect> manifest_defects(const std::string& json)
{
  std::vector<Listed_defect> out;
  std::size_t pos = json.find("\"defects\": [");
  while (pos != std::string::npos) {
    std::size_t k = json.find("\"kind\": \"", pos);
    if (k == std::string::npos) break;
    Listed_defect d;
    k += 9;
    d.kind = json.substr(k, json.find('"', k) - k);
    auto list = [&](const char* key) {
      std::size_t b = json.find(std::string("\"") + key + "\": [", k);
      b = json.find('[', b) + 1;
      return id_list(json.substr(b, json.find(']', b) - b));
    };
    d.vertices = list("vertices");
    d.faces = list("faces");
    out.push_back(d);
    pos = json.find('}', json.find("\"faces\": [", k));
  }
  return out;
}

struct Loaded
{
  std::vector<Point> points;
  std::vector<Polygon> polygons;
  mrepair::Io_result io;
};
Loaded load(const std::string& path)
{
  Loaded l;
  l.io = mrepair::read_polygon_soup(path, l.points, l.polygons);
  return l;
}

bool finite(const Point& p) { return std::isfinite(p.x()) && std::isfinite(p.y()) && std::isfinite(p.z()); }

// ---- determinism -----------------------------------------------------------

TEST(Generator, ScanIsDeterministicPerSeed)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  const std::string common = "scan --faces 3000 --nan-referenced 1 ";
  ASSERT_EQ(0, run_generator(common + "--seed 7 --output " + d / "a.ply" + " --manifest " + d / "a.json"));
  ASSERT_EQ(0, run_generator(common + "--seed 7 --output " + d / "b.ply" + " --manifest " + d / "b.json"));
  ASSERT_EQ(0, run_generator(common + "--seed 8 --output " + d / "c.ply" + " --manifest " + d / "c.json"));
  const std::string a = slurp(d / "a.ply");
  ASSERT_GT(a.size(), 10000u);
  EXPECT_EQ(a, slurp(d / "b.ply"));
  EXPECT_EQ(slurp(d / "a.json"), slurp(d / "b.json"));
  EXPECT_NE(a, slurp(d / "c.ply"));
  EXPECT_NE(slurp(d / "a.json"), slurp(d / "c.json"));
}

// --clean-output writes the base surface (upsampled, before noise and
// defects), the reference for distance measurements, and changes nothing else.
TEST(Generator, ScanCleanOutputIsTheBaseSurface)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  const std::string common = "scan --faces 3000 --seed 7 --nan-referenced 1 --noise 0.2 ";
  ASSERT_EQ(0, run_generator(common + "--output " + d / "a.ply" + " --manifest " + d / "a.json"));
  ASSERT_EQ(0, run_generator(common + "--output " + d / "b.ply" + " --manifest " + d / "b.json" +
                             " --clean-output " + d / "base.off"));
  EXPECT_EQ(slurp(d / "a.ply"), slurp(d / "b.ply"));
  const std::string a = slurp(d / "a.json"), b = slurp(d / "b.json");
  EXPECT_EQ(a.find("clean_output"), std::string::npos);
  const std::string line = ",\n    \"clean_output\": \"base.off\"";
  const std::size_t at = b.find(line);
  ASSERT_NE(at, std::string::npos);
  EXPECT_EQ(b.substr(0, at) + b.substr(at + line.size()), a);  // nothing else differs

  Loaded base = load(d / "base.off");
  ASSERT_EQ(base.io.status, mrepair::Status::ok) << base.io.message;
  EXPECT_EQ(base.points.size(), manifest_count(a, "base", "upsampled_vertices"));
  EXPECT_EQ(base.polygons.size(), manifest_count(a, "base", "upsampled_faces"));
  // the procedural bumpy sphere: closed, one component, no defect
  mrepair::Inspection_report r = mrepair::inspect_polygon_soup(base.points, base.polygons);
  EXPECT_TRUE(r.closed);
  EXPECT_EQ(r.connected_components, 1u);
  EXPECT_EQ(r.non_finite_vertices, 0u);
  EXPECT_EQ(r.isolated_vertices, 0u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.self_intersecting_pairs, 0u);
  EXPECT_EQ(r.spiked_vertices, 0u);
  EXPECT_EQ(r.near_degenerate_faces, 0u);
  EXPECT_EQ(run_generator("cad --faces 3000 --output " + d / "c.ply" + " --clean-output " + d / "x.ply"),
            2);  // scan only
}

TEST(Generator, CadIsDeterministicPerSeed)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  ASSERT_EQ(0, run_generator("cad --faces 3000 --seed 7 --output " + d / "a.stl" + " --manifest " + d / "a.json"));
  ASSERT_EQ(0, run_generator("cad --faces 3000 --seed 7 --output " + d / "b.stl" + " --manifest " + d / "b.json"));
  ASSERT_EQ(0, run_generator("cad --faces 3000 --seed 9 --output " + d / "c.stl" + " --manifest " + d / "c.json"));
  const std::string a = slurp(d / "a.stl");
  ASSERT_GT(a.size(), 10000u);
  EXPECT_EQ(a, slurp(d / "b.stl"));
  EXPECT_EQ(slurp(d / "a.json"), slurp(d / "b.json"));
  EXPECT_NE(a, slurp(d / "c.stl"));
}

TEST(Generator, BadArgumentsFailWithoutOutput)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  EXPECT_NE(0, run_generator("frobnicate --output " + d / "x.ply"));
  EXPECT_NE(0, run_generator("scan --faces 3000"));                               // no --output
  EXPECT_NE(0, run_generator("scan --faces lots --output " + d / "x.ply"));
  EXPECT_NE(0, run_generator("cad --spikes 3 --output " + d / "x.ply"));           // scan-only option
  EXPECT_NE(0, run_generator("scan --input " + d / "missing.off" + " --output " + d / "x.ply"));
  EXPECT_NE(0, run_generator("scan --output " + d / "x.xyz"));                     // unknown format
  EXPECT_FALSE(fs::exists(d / "x.ply"));
}

// ---- scan: the file against the manifest ------------------------------------

/// expected Euler characteristic V - E + F of the referenced part: the closed
/// genus-0 base loses 2 per tunnel and 1 per hole; open patches add 1, tetrahedra 2.
long long expected_euler(const std::string& m)
{
  return 2 - 2 * static_cast<long long>(manifest_count(m, "counts", "tunnel")) -
         static_cast<long long>(manifest_count(m, "counts", "hole") + manifest_count(m, "counts", "jagged_hole")) +
         static_cast<long long>(manifest_count(m, "counts", "island_open_patch")) +
         2 * static_cast<long long>(manifest_count(m, "counts", "island_tetrahedron"));
}

TEST(Generator, ScanFileMatchesManifest)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  ASSERT_EQ(0, run_generator("scan --faces 6000 --seed 11 --spikes 4 --foldovers 3 --tunnels 2 --holes 4 "
                             "--jagged-holes 2 --islands 4 --slivers 6 --isolated 5 --nan 2 "
                             "--nan-referenced 1 --output " + d / "s.ply" + " --manifest " + d / "s.json"));
  const std::string m = slurp(d / "s.json");
  // every requested defect was placed
  for (const char* k : {"spike", "foldover", "tunnel", "hole", "jagged_hole", "island", "sliver",
                        "isolated_vertex", "nan_vertex", "nan_referenced_vertex"})
    EXPECT_EQ(manifest_count(m, "requested", k), manifest_count(m, "counts", k)) << k;
  EXPECT_EQ(m.find("\"shortfalls\": {}"), m.find("\"shortfalls\""));

  Loaded l = load(d / "s.ply");
  EXPECT_EQ(l.io.status, mrepair::Status::non_finite_input) << l.io.message;
  EXPECT_TRUE(l.io.binary);
  ASSERT_EQ(l.points.size(), manifest_count(m, "output", "vertices"));
  ASSERT_EQ(l.polygons.size(), manifest_count(m, "output", "faces"));
  EXPECT_EQ(l.io.non_finite_points, 3u);  // 2 unreferenced + 1 referenced, as asked
  EXPECT_EQ(l.io.non_finite_points, manifest_count(m, "expected", "non_finite_vertices"));

  // hand count: unreferenced points, and among them the NaN ones
  std::vector<int> uses(l.points.size(), 0);
  for (const Polygon& p : l.polygons) {
    ASSERT_EQ(p.size(), 3u);
    for (std::size_t v : p) ++uses[v];
  }
  std::size_t isolated = 0, isolated_nan = 0, referenced_nan = 0;
  for (std::size_t v = 0; v < l.points.size(); ++v) {
    if (uses[v] == 0) ++isolated, isolated_nan += !finite(l.points[v]);
    else referenced_nan += !finite(l.points[v]);
  }
  EXPECT_EQ(isolated, manifest_count(m, "expected", "isolated_vertices"));
  EXPECT_EQ(isolated, 7u);
  EXPECT_EQ(isolated_nan, 2u);
  EXPECT_EQ(referenced_nan, 1u);

  // the listed ids point at what they say
  const auto defects = manifest_defects(m);
  ASSERT_EQ(defects.size(), 4u + 3 + 2 + 4 + 2 + 4 + 6 + 5 + 2 + 1);
  for (const Listed_defect& df : defects) {
    for (std::size_t v : df.vertices) ASSERT_LT(v, l.points.size()) << df.kind;
    for (std::size_t f : df.faces) ASSERT_LT(f, l.polygons.size()) << df.kind;
    if (df.kind == "spike" || df.kind == "nan_referenced_vertex") {
      ASSERT_EQ(df.vertices.size(), 1u);
      ASSERT_FALSE(df.faces.empty());
      for (std::size_t f : df.faces)
        EXPECT_NE(std::find(l.polygons[f].begin(), l.polygons[f].end(), df.vertices[0]), l.polygons[f].end());
    }
    if (df.kind == "nan_referenced_vertex") {
      EXPECT_FALSE(finite(l.points[df.vertices[0]]));
    }
    if (df.kind == "isolated_vertex" || df.kind == "nan_vertex") {
      EXPECT_EQ(uses[df.vertices[0]], 0);
    }
    if (df.kind == "sliver") {
      EXPECT_EQ(df.faces.size(), 3u);
    }
    if (df.kind == "tunnel") {
      EXPECT_EQ(df.faces.size(), 42u);     // 7 segments of 6 faces
      EXPECT_EQ(df.vertices.size(), 24u);  // 8 rings of 3: f1, 6 new, f2
    }
  }

  // the same counts from mrepair's own inspection of the soup
  mrepair::Inspection_report r = mrepair::inspect_polygon_soup(l.points, l.polygons);
  EXPECT_EQ(r.non_finite_vertices, 3u);
  EXPECT_EQ(r.isolated_vertices, isolated);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.non_manifold_vertices, 0u);
  EXPECT_EQ(r.inconsistent_orientation_edges, 0u);
  EXPECT_EQ(r.duplicate_faces, 0u);
  EXPECT_EQ(r.boundary_loops, manifest_count(m, "expected", "boundary_loops"));
  EXPECT_EQ(r.connected_components, manifest_count(m, "expected", "connected_components"));
  EXPECT_EQ(r.small_components, manifest_count(m, "counts", "island"));
}

TEST(Generator, ScanPinnedDanglersAreNonManifoldVertices)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  ASSERT_EQ(0, run_generator("scan --faces 4000 --seed 3 --jagged-holes 3 --pinned-danglers 2 --nan 0 --output " +
                             d / "s.ply" + " --manifest " + d / "s.json"));
  const std::string m = slurp(d / "s.json");
  EXPECT_EQ(manifest_count(m, "counts", "pinned_dangler"), 2u);
  EXPECT_EQ(manifest_count(m, "expected", "non_manifold_vertices"), 2u);
  EXPECT_LT(manifest_number(m, "expected", "boundary_loops"), 0);  // not defined with bowties
  Loaded l = load(d / "s.ply");
  ASSERT_EQ(l.io.status, mrepair::Status::ok) << l.io.message;
  mrepair::Inspection_report r = mrepair::inspect_polygon_soup(l.points, l.polygons);
  EXPECT_EQ(r.non_manifold_vertices, 2u);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.connected_components, manifest_count(m, "expected", "connected_components"));
}

// Mesh-level check on both mesh types: the scan output (without NaN) builds a
// valid halfedge mesh whose holes, components and Euler characteristic match.
template <class Config>
class Generator_mesh : public ::testing::Test {};
TYPED_TEST_SUITE(Generator_mesh, Mesh_configs);

TYPED_TEST(Generator_mesh, ScanTopologyMatchesManifest)
{
  using Mesh = typename TypeParam::Mesh;
  namespace PMP = CGAL::Polygon_mesh_processing;
  REQUIRE_GENERATOR();
  Temp_dir d;
  // no unreferenced vertices: CGAL::is_valid_polygon_mesh rejects isolated vertices
  ASSERT_EQ(0, run_generator("scan --faces 5000 --seed 5 --nan 0 --isolated 0 --output " + d / "s.off" +
                             " --manifest " + d / "s.json"));
  const std::string m = slurp(d / "s.json");
  Mesh mesh;
  mrepair::Io_result io = mrepair::read_polygon_mesh(d / "s.off", mesh);
  ASSERT_EQ(io.status, mrepair::Status::ok) << io.message;
  ASSERT_TRUE(mrepair_test::valid_polygon_mesh(mesh));
  ASSERT_EQ(face_count(mesh), manifest_count(m, "output", "faces"));

  std::vector<typename boost::graph_traits<Mesh>::halfedge_descriptor> cycles;
  PMP::extract_boundary_cycles(mesh, std::back_inserter(cycles));
  EXPECT_EQ(cycles.size(), manifest_count(m, "expected", "boundary_loops"));
  EXPECT_EQ(cycles.size(), manifest_count(m, "counts", "hole") + manifest_count(m, "counts", "jagged_hole") +
                               manifest_count(m, "counts", "island_open_patch"));

  auto fcc = get(CGAL::dynamic_face_property_t<std::size_t>(), mesh);
  std::size_t ncc = PMP::connected_components(mesh, fcc);
  EXPECT_EQ(ncc, manifest_count(m, "expected", "connected_components"));

  std::size_t used_vertices = 0;
  for (auto v : vertices(mesh))
    if (halfedge(v, mesh) != boost::graph_traits<Mesh>::null_halfedge()) ++used_vertices;
  long long chi = static_cast<long long>(used_vertices) - static_cast<long long>(edges(mesh).size()) +
                  static_cast<long long>(face_count(mesh));
  EXPECT_EQ(chi, expected_euler(m));

  // every hole's listed boundary vertices (ids of the file) are on the border of the mesh
  Loaded l = load(d / "s.off");
  std::map<Point, bool> on_border;
  for (auto v : vertices(mesh)) on_border[get(CGAL::vertex_point, mesh, v)] = bool(CGAL::is_border(v, mesh));
  std::size_t checked = 0;
  for (const Listed_defect& df : manifest_defects(m))
    if (df.kind == "hole" || df.kind == "jagged_hole") {
      EXPECT_GE(df.vertices.size(), 3u);
      for (std::size_t v : df.vertices) {
        ASSERT_LT(v, l.points.size());
        ASSERT_EQ(on_border.count(l.points[v]), 1u);
        EXPECT_TRUE(on_border[l.points[v]]) << df.kind << " vertex " << v;
        ++checked;
      }
    }
  EXPECT_GT(checked, 0u);
}

// Only foldovers are meant to self-intersect: without them the tunnel, spikes,
// islands and slivers leave the surface free of self-intersections.
TYPED_TEST(Generator_mesh, ScanWithoutFoldoversDoesNotSelfIntersect)
{
  using Mesh = typename TypeParam::Mesh;
  namespace PMP = CGAL::Polygon_mesh_processing;
  REQUIRE_GENERATOR();
  Temp_dir d;
  for (int seed : {6, 7, 8}) {
    ASSERT_EQ(0, run_generator("scan --faces 8000 --seed " + std::to_string(seed) +
                               " --foldovers 0 --tunnels 3 --spikes 6 --nan 0 --isolated 0 --output " + d / "s.off" +
                               " --manifest " + d / "s.json"));
    EXPECT_EQ(manifest_count(slurp(d / "s.json"), "counts", "tunnel"), 3u);
    Mesh mesh;
    mrepair::Io_result io = mrepair::read_polygon_mesh(d / "s.off", mesh);
    ASSERT_EQ(io.status, mrepair::Status::ok) << io.message;
    EXPECT_FALSE(PMP::does_self_intersect(mesh)) << "seed " << seed;
  }
}

// ---- cad: the soup against the manifest ---------------------------------------

TEST(Generator, CadSoupMatchesManifest)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  ASSERT_EQ(0, run_generator("cad --faces 8000 --seed 4 --flipped 3 --duplicates 2 --degenerate 4 --fins 2 "
                             "--pinched 2 --output " + d / "c.ply" + " --manifest " + d / "c.json"));
  const std::string m = slurp(d / "c.json");
  Loaded l = load(d / "c.ply");
  ASSERT_EQ(l.io.status, mrepair::Status::ok) << l.io.message;
  ASSERT_EQ(l.points.size(), manifest_count(m, "output", "vertices"));
  ASSERT_EQ(l.polygons.size(), manifest_count(m, "output", "faces"));
  EXPECT_EQ(manifest_count(m, "counts", "patches"), 9u);
  EXPECT_EQ(manifest_count(m, "counts", "seams"), 14u);  // 12 box edges + 2 silo circles
  EXPECT_GE(manifest_count(m, "counts", "gap_seams"), 1u);
  EXPECT_GE(manifest_count(m, "counts", "mismatched_seams"), 1u);

  // hand count of undirected edge multiplicities (self-loop edges of repeated-index faces apart)
  std::map<std::pair<std::size_t, std::size_t>, int> mult;
  for (const Polygon& p : l.polygons)
    for (std::size_t k = 0; k < 3; ++k) {
      std::size_t a = p[k], b = p[(k + 1) % 3];
      if (a != b) ++mult[{std::min(a, b), std::max(a, b)}];
    }
  std::size_t boundary = 0, non_manifold = 0;
  for (const auto& e : mult) boundary += e.second == 1, non_manifold += e.second > 2;
  const std::size_t fins = manifest_count(m, "counts", "fin"), pinched = manifest_count(m, "counts", "pinched_vertex"),
                    dups = manifest_count(m, "counts", "duplicate_face"),
                    repeated = manifest_count(m, "counts", "degenerate_face.repeated_index");
  EXPECT_EQ(fins, 2u);
  EXPECT_EQ(pinched, 2u);
  EXPECT_EQ(dups, 2u);
  EXPECT_EQ(repeated, 2u);
  // open seams; a fin adds 2 border edges, a pinched face 3
  EXPECT_EQ(boundary, manifest_count(m, "counts", "seam_edges") + 2 * fins + 3 * pinched);
  // a duplicated interior face triples its 3 edges; a fin and a repeated-index face add a third face to one edge
  EXPECT_EQ(non_manifold, 3 * dups + fins + repeated);

  mrepair::Inspection_report r = mrepair::inspect_polygon_soup(l.points, l.polygons);
  // inspection leaves repeated-index faces out of the edge counts (they have no proper edges)
  EXPECT_EQ(r.non_manifold_edges, 3 * dups + fins);
  EXPECT_EQ(r.duplicate_faces, dups);
  EXPECT_EQ(r.degenerate_faces, manifest_count(m, "counts", "degenerate_face"));
  EXPECT_EQ(r.repeated_index_faces, repeated);
  EXPECT_EQ(r.inconsistent_orientation_edges, 3 * manifest_count(m, "counts", "flipped_face"));
  EXPECT_GE(r.non_manifold_vertices, pinched);
  EXPECT_EQ(r.isolated_vertices, 0u);
  EXPECT_FALSE(r.closed);
}

TEST(Generator, CadSeamsWithoutPerturbationGiveTheListedTJunctions)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  ASSERT_EQ(0, run_generator("cad --faces 4000 --seed 2 --gap 0 --gap-fraction 0 --flipped 0 --duplicates 0 "
                             "--degenerate 0 --fins 0 --pinched 0 --output " + d / "c.off" + " --manifest " + d / "c.json"));
  const std::string m = slurp(d / "c.json");
  Loaded l = load(d / "c.off");
  ASSERT_EQ(l.io.status, mrepair::Status::ok) << l.io.message;
  EXPECT_EQ(manifest_count(m, "counts", "gap_seams"), 0u);
  const std::size_t straight = manifest_count(m, "counts", "t_junction_vertices"),
                    curved = manifest_count(m, "counts", "curved_seam_unmatched_vertices");
  EXPECT_GT(straight, 0u);
  mrepair::Inspection_report r = mrepair::inspect_polygon_soup(l.points, l.polygons);
  // straight seams: the unmatched vertices lie exactly on the other side's edges;
  // curved seams: off the chords by the sagitta, so only some may count
  EXPECT_GE(r.t_junctions, straight);
  EXPECT_LE(r.t_junctions, straight + curved);
  EXPECT_EQ(r.non_manifold_edges, 0u);
  EXPECT_EQ(r.degenerate_faces, 0u);
  EXPECT_EQ(r.connected_components, 9u);  // one per patch: nothing shares a vertex
}

// ---- the bundled samples (examples/data) --------------------------------------

const char* kSampleScanArgs =
    "scan --faces 15000 --seed 2026 --spikes 4 --foldovers 3 --tunnels 1 --holes 3 --jagged-holes 2 "
    "--islands 3 --slivers 6 --isolated 2 --nan 1 --noise 0.02";
const char* kSampleCadArgs =
    "cad --faces 6000 --seed 2026 --flipped 3 --duplicates 2 --degenerate 4 --fins 2 --pinched 2";

// The commands documented in examples/data/README.md still produce the committed files.
TEST(Generator, BundledSamplesAreReproducible)
{
  REQUIRE_GENERATOR();
  Temp_dir d;
  const std::string dir = MREPAIR_SAMPLE_DIR;
  ASSERT_EQ(0, run_generator(std::string(kSampleScanArgs) + " --output " + d / "sample_scan.off" +
                             " --manifest " + d / "sample_scan.json"));
  ASSERT_EQ(0, run_generator(std::string(kSampleCadArgs) + " --output " + d / "sample_cad.off" +
                             " --manifest " + d / "sample_cad.json"));
  for (const char* f : {"sample_scan.off", "sample_scan.json", "sample_cad.off", "sample_cad.json"}) {
    const std::string committed = slurp(dir + "/" + f);
    ASSERT_FALSE(committed.empty()) << f;
    EXPECT_TRUE(committed == slurp(d / f)) << f << " differs from a fresh generation";
  }
}

TEST(Generator, BundledScanSampleMatchesItsManifest)
{
  const std::string dir = MREPAIR_SAMPLE_DIR;
  const std::string m = slurp(dir + "/sample_scan.json");
  ASSERT_FALSE(m.empty());
  Loaded l = load(dir + "/sample_scan.off");
  EXPECT_EQ(l.io.status, mrepair::Status::non_finite_input) << l.io.message;  // the NaN vertex
  ASSERT_EQ(l.points.size(), manifest_count(m, "output", "vertices"));
  ASSERT_EQ(l.polygons.size(), manifest_count(m, "output", "faces"));
  EXPECT_LT(slurp(dir + "/sample_scan.off").size(), 1000000u);
  mrepair::Inspection_report r = mrepair::inspect_polygon_soup(l.points, l.polygons);
  EXPECT_EQ(r.non_finite_vertices, 1u);
  EXPECT_EQ(r.isolated_vertices, 3u);
  EXPECT_EQ(r.isolated_vertices, manifest_count(m, "expected", "isolated_vertices"));
  EXPECT_EQ(r.boundary_loops, 6u);
  EXPECT_EQ(r.boundary_loops, manifest_count(m, "expected", "boundary_loops"));
  EXPECT_EQ(r.connected_components, 4u);
  EXPECT_EQ(r.small_components, 3u);
  EXPECT_EQ(r.non_manifold_edges + r.non_manifold_vertices + r.inconsistent_orientation_edges, 0u);
  // each needle sliver has an edge under 0.1 x the mean edge length: both its faces are near-degenerate
  std::size_t needles = 0;
  for (const char* p = m.c_str(); (p = std::strstr(p, "\"needle\"")) != nullptr; ++p) ++needles;
  EXPECT_EQ(needles, 3u);
  EXPECT_GE(r.near_degenerate_faces, 2 * needles);
}

TEST(Generator, BundledCadSampleMatchesItsManifest)
{
  const std::string dir = MREPAIR_SAMPLE_DIR;
  const std::string m = slurp(dir + "/sample_cad.json");
  ASSERT_FALSE(m.empty());
  Loaded l = load(dir + "/sample_cad.off");
  ASSERT_EQ(l.io.status, mrepair::Status::ok) << l.io.message;
  ASSERT_EQ(l.points.size(), manifest_count(m, "output", "vertices"));
  ASSERT_EQ(l.polygons.size(), manifest_count(m, "output", "faces"));
  EXPECT_LT(slurp(dir + "/sample_cad.off").size(), 300000u);
  mrepair::Inspection_report r = mrepair::inspect_polygon_soup(l.points, l.polygons);
  EXPECT_EQ(r.duplicate_faces, 2u);
  EXPECT_EQ(r.degenerate_faces, 4u);
  EXPECT_EQ(r.non_manifold_edges, 3u * 2 + 2);  // two duplicated faces, two fins
  EXPECT_EQ(r.inconsistent_orientation_edges, 3u * 3);
  // components are edge-connected: a face hanging by one vertex is a component of its own
  EXPECT_EQ(r.connected_components, 9u + 2);
  EXPECT_GE(r.t_junctions, 1u);
}

}  // namespace

} // namespace generator_tests
} // namespace

#undef REQUIRE_GENERATOR  // the other files of the unity build do not see it
