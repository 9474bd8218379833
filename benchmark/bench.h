// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The benchmark harness: each task (bench_<task>.cpp) registers variants —
// the mrepair call and its CGAL PMP counterparts — that run on copies of the
// same input. Each variant runs in a forked child so that its peak memory is
// its own; the parent prints one table and CSV rows (`--csv`).
#ifndef MREPAIR_BENCH_H
#define MREPAIR_BENCH_H

#include <mrepair/report.h>
#include <mrepair/status.h>

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
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
  /// the generated input the task runs on when none is given (a kind of
  /// bench_main.cpp's input table: "scan", "scan-mesh", "scan-clean",
  /// "cad-soup", "cad-mesh")
  std::string default_input = "scan-mesh";
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

/// A program of the build tree: $`env` when set, else <build>/tools/`name`
/// (the harness is <build>/benchmark/mrepair-bench).
inline std::string build_tool(const char* env, const char* name)
{
  if (const char* e = std::getenv(env)) return e;
  char buf[4096];
  const ssize_t n = readlink("/proc/self/exe", buf, sizeof(buf) - 1);
  if (n <= 0) return name;
  const std::string self(buf, static_cast<std::size_t>(n));
  const std::string dir = self.substr(0, self.find_last_of('/'));
  return dir.substr(0, dir.find_last_of('/')) + "/tools/" + name;
}

/// Runs `args` as a child process with its output sent to /dev/null; wall
/// seconds, exit code (-1: did not start or was killed) and the child's peak
/// resident set (wait4) come back.
struct Child_run
{
  double seconds = 0;
  int exit_code = -1;
  double peak_mb = 0;
};

inline Child_run run_program(const std::vector<std::string>& args)
{
  Child_run c;
  std::vector<char*> argv;
  for (const std::string& s : args) argv.push_back(const_cast<char*>(s.c_str()));
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&actions, 2, "/dev/null", O_WRONLY, 0);
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  const int err = posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  if (err != 0) return c;
  int status = 0;
  rusage ru{};
  wait4(pid, &status, 0, &ru);
  c.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  c.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  c.peak_mb = double(ru.ru_maxrss) / 1024.0;
  return c;
}

/// registers a task at static-initialisation time.
struct Task_registrar
{
  explicit Task_registrar(Task t) { tasks().push_back(std::move(t)); }
};

} // namespace bench
} // namespace mrepair

#endif // MREPAIR_BENCH_H
