// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The benchmark harness: each task (bench_<task>.cpp) registers variants —
// the mrepair call and its CGAL PMP counterparts — that run on copies of the
// same input. Each variant runs in a forked child so that its peak memory is
// its own; the parent prints one table and CSV rows (`--csv`).
#ifndef MREPAIR_BENCH_H
#define MREPAIR_BENCH_H

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <sys/resource.h>

#include <functional>
#include <stdexcept>
#include <string>
#include <vector>

namespace mrepair {
namespace bench {

/// CPU seconds (all threads, user + system) used by this process so far: on a
/// shared machine the wall time of a parallel call says little alone.
inline double cpu_seconds()
{
  rusage ru{};
  getrusage(RUSAGE_SELF, &ru);
  return double(ru.ru_utime.tv_sec + ru.ru_stime.tv_sec) +
         1e-6 * double(ru.ru_utime.tv_usec + ru.ru_stime.tv_usec);
}

/// reads `path` into a mesh (io.h's reader); throws when it holds no face.
template <typename Mesh, typename Read>
Mesh load_mesh(const std::string& path, Read&& read)
{
  Mesh m;
  const auto r = read(path, m);
  if (r.status != mrepair::Status::ok || faces(m).size() == 0)
    throw std::runtime_error("cannot read " + path + " as a polygon mesh: " + r.message);
  return m;
}

/// what a variant measured: its own timed section and reports.
struct Measurement
{
  double seconds = 0;   // wall time of the timed section only (no I/O)
  Report before;        // inspection of the input (optional)
  Report after;         // inspection of the output (optional)
  Report result;        // the call's own result struct (optional)
  std::string status = "ok";
};

/// one side of a comparison: `run(input_path)` loads the input, times the
/// call with `time_section`, fills the reports.
struct Variant
{
  std::string name;  // e.g. "mrepair::inspect", "CGAL PMP"
  std::function<Measurement(const std::string& input)> run;
};

struct Task
{
  std::string name;     // e.g. "inspect"
  std::string summary;  // one line
  std::vector<Variant> variants;  // first = mrepair, the rest = counterparts
};

inline std::vector<Task>& tasks()
{
  static std::vector<Task> all;
  return all;
}

/// optional reference file given by `--reference FILE` (e.g. the clean base
/// surface written by `mrepair-generate scan --clean-output`); empty if none.
/// Tasks that can use one read it; the others ignore it.
inline std::string& reference_path()
{
  static std::string path;
  return path;
}

/// registers a task at static-initialisation time.
struct Task_registrar
{
  explicit Task_registrar(Task t) { tasks().push_back(std::move(t)); }
};

} // namespace bench
} // namespace mrepair

#endif // MREPAIR_BENCH_H
