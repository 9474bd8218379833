// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Shared machinery of the `mrepair` program: one argument parser, one report
// writer, one progress printer, a registry of commands. Every command has the
// shape `mrepair COMMAND INPUT [OUTPUT] [options] [--report FILE.json]`.
#ifndef MREPAIR_TOOLS_CLI_H
#define MREPAIR_TOOLS_CLI_H

#include <mrepair/report.h>
#include <mrepair/status.h>
#include <mrepair/visitors.h>

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <unistd.h>
#include <vector>
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace mrepair {
namespace cli {

/// a command-line mistake; `main` prints it as one line and exits 2.
struct Usage_error : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

/// one accepted option: `--name VALUE` when `takes_value`, else a flag `--name`.
struct Option
{
  std::string name;
  bool takes_value;
  std::string help;
};

/// parsed command line of one command.
class Arguments
{
public:
  std::vector<std::string> positional;
  std::map<std::string, std::string> values;  // options with a value
  std::map<std::string, bool> flags;          // options without one

  bool has(const std::string& name) const
  {
    return values.count(name) != 0 || flags.count(name) != 0;
  }
  std::string get(const std::string& name, const std::string& fallback = std::string()) const
  {
    auto it = values.find(name);
    return it == values.end() ? fallback : it->second;
  }
  double get_double(const std::string& name, double fallback) const
  {
    auto it = values.find(name);
    if (it == values.end()) return fallback;
    char* end = nullptr;
    double v = std::strtod(it->second.c_str(), &end);
    if (end == it->second.c_str() || *end != '\0' || !std::isfinite(v))
      throw Usage_error("--" + name + " expects a finite number, got '" + it->second + "'");
    return v;
  }
  /// the value of `--name` when given: what the CLI hands the library, which
  /// holds the default (parameters.h: an empty optional is an absent parameter)
  std::optional<double> optional_double(const std::string& name) const
  {
    if (!has(name)) return std::nullopt;
    return get_double(name, 0.);
  }
  /// the same for a count; `min` is the smallest value accepted
  std::optional<std::size_t> optional_count(const std::string& name, long long min) const
  {
    if (!has(name)) return std::nullopt;
    const long long v = get_int(name, 0);
    if (v < min)
      throw Usage_error("--" + name + " must be at least " + std::to_string(min) + ", got " +
                        std::to_string(v));
    return static_cast<std::size_t>(v);
  }
  long long get_int(const std::string& name, long long fallback) const
  {
    auto it = values.find(name);
    if (it == values.end()) return fallback;
    char* end = nullptr;
    long long v = std::strtoll(it->second.c_str(), &end, 10);
    if (end == it->second.c_str() || *end != '\0')
      throw Usage_error("--" + name + " expects an integer, got '" + it->second + "'");
    return v;
  }
};

/// how much a command prints: nothing but errors, a summary of about ten
/// lines (the default), or the full report and a line per phase.
enum class Verbosity { quiet, summary, verbose };

/// `--quiet` (it wins), `--verbose`, else the summary.
inline Verbosity verbosity(const Arguments& a)
{
  if (a.has("quiet")) return Verbosity::quiet;
  return a.has("verbose") ? Verbosity::verbose : Verbosity::summary;
}

/// parses `argv[first..argc)` against `options` (plus the common `--report`,
/// `--json`, `--quiet`, `--verbose`, `--help`); requires between
/// `min_positional` and `max_positional` positional arguments.
inline Arguments parse(int argc, char** argv, int first, std::vector<Option> options,
                       std::size_t min_positional, std::size_t max_positional)
{
  options.push_back({"report", true, "write the report as JSON to FILE"});
  options.push_back({"json", false, "print the report as JSON instead of a summary"});
  options.push_back({"quiet", false, "print nothing but errors"});
  options.push_back({"verbose", false, "print the full report and a line per phase"});
  options.push_back({"help", false, "print this help"});
  Arguments a;
  for (int i = first; i < argc; ++i) {
    std::string s = argv[i];
    if (s.size() > 2 && s.compare(0, 2, "--") == 0) {
      std::string name = s.substr(2), value;
      bool inline_value = false;
      auto eq = name.find('=');
      if (eq != std::string::npos) {
        value = name.substr(eq + 1);
        name = name.substr(0, eq);
        inline_value = true;
      }
      const Option* opt = nullptr;
      for (const Option& o : options)
        if (o.name == name) opt = &o;
      if (!opt) throw Usage_error("unknown option --" + name);
      if (opt->takes_value) {
        if (!inline_value) {
          if (i + 1 >= argc) throw Usage_error("--" + name + " needs a value");
          value = argv[++i];
        }
        a.values[name] = value;
      } else {
        if (inline_value) throw Usage_error("--" + name + " takes no value");
        a.flags[name] = true;
      }
    } else {
      a.positional.push_back(s);
    }
  }
  if (a.has("help")) return a;
  if (a.has("ascii") && a.has("binary")) throw Usage_error("--ascii and --binary exclude each other");
  if (a.positional.size() < min_positional)
    throw Usage_error("missing argument (see --help)");
  if (a.positional.size() > max_positional)
    throw Usage_error("unexpected argument '" + a.positional[max_positional] + "'");
  return a;
}

/// one subcommand of `mrepair`.
struct Command
{
  std::string name;
  std::string synopsis;  // e.g. "INPUT OUTPUT [--epsilon E]"
  std::string summary;   // one line
  std::function<int(int argc, char** argv)> run;  // argv[0] is the command name
};

/// hands the free pages of the heap back to the system. mrepair.cpp keeps
/// freed blocks up to 32 MiB warm and never trims below 1 GiB; after the
/// input soup is freed (10M small polygon vectors, 560 MB at 10M faces) that
/// memory would stay resident through the rest of the job, the peak of
/// which comes later. glibc only; elsewhere nothing to do.
inline void release_freed_memory()
{
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

/// `release_freed_memory()` when the allocator holds more than `bytes`
/// freed (a trim costs the page faults of reusing what it released: on
/// small jobs it is a loss).
inline void release_freed_memory_above(std::size_t bytes)
{
#if defined(__GLIBC__) && (__GLIBC__ > 2 || __GLIBC_MINOR__ >= 33)
  if (mallinfo2().fordblks > bytes) malloc_trim(0);
#else
  (void)bytes;
#endif
}

/// whether glibc serves blocks above its mmap threshold from the heap too
/// (true) or maps each one afresh and unmaps it when freed (false, its
/// default). The heap keeps freed pages warm for the next block, where a
/// fresh map faults every page in again; but a heap fragments, so its
/// resident size can exceed what is live (see `run_repair`).
inline void serve_large_blocks_from_heap(bool heap)
{
#if defined(__GLIBC__)
  mallopt(M_MMAP_MAX, heap ? 0 : 65536);  // 65536: glibc's default
#else
  (void)heap;
#endif
}

inline std::vector<Command>& registry()
{
  static std::vector<Command> commands;
  return commands;
}

/// adds a command at static-initialisation time: `static Registrar r{{...}};`.
struct Registrar
{
  explicit Registrar(Command c) { registry().push_back(std::move(c)); }
};

/// prints the help of a command: synopsis and options.
inline void print_help(const Command& c, const std::vector<Option>& options)
{
  std::cout << "usage: mrepair " << c.name << " " << c.synopsis << "\n" << c.summary << "\n";
  for (const Option& o : options)
    std::cout << "  --" << o.name << (o.takes_value ? " VALUE" : "") << "\n      " << o.help
              << "\n";
  std::cout << "  --report FILE\n      write the report as JSON to FILE\n"
               "  --json\n      print the report as JSON instead of the summary\n"
               "  --verbose\n      print the full report (a table) and a line per phase\n"
               "  --quiet\n      print nothing but errors\n";
}

/// prints `report` (JSON with --json, a table with --verbose; the default
/// summary is the command's, summary.h) and writes it to `--report FILE`
/// when given. Returns false when the file cannot be written.
inline bool emit_report(const Arguments& a, const Report& report)
{
  if (a.has("json"))
    std::cout << report.to_json() << "\n";
  else if (verbosity(a) == Verbosity::verbose)
    std::cout << report.to_text();
  if (a.has("report")) {
    std::ofstream out(a.get("report"));
    out << report.to_json() << "\n";
    if (!out) {
      std::cerr << "mrepair: cannot write report '" << a.get("report") << "'\n";
      return false;
    }
  }
  return true;
}

/// exit code of a finished command from the status of its main call.
inline int exit_code(Status s) { return succeeded(s) ? 0 : 1; }

/// prints "mrepair: reason" and returns the exit code for bad input (1).
inline int fail(const std::string& reason)
{
  std::cerr << "mrepair: " << reason << "\n";
  return 1;
}

/// visitor that prints one line per finished phase with its time on stderr
/// (--verbose), and a percentage while a phase runs when stderr is a
/// terminal (not with --quiet or --json), erased when the phase ends.
class Progress_printer : public Default_visitor
{
  using Clock = std::chrono::steady_clock;
  struct Open
  {
    std::string name;
    Clock::time_point start;
  };
  std::vector<Open> open_;
  bool phases_;   // a line per finished phase
  bool percent_;  // the running percentage
  bool tty_;
  bool line_shown_ = false;  // a percentage is on the terminal's last line
  int last_percent_ = -1;
  std::size_t release_above_ = 0;

public:
  explicit Progress_printer(const Arguments& a)
    : phases_(verbosity(a) == Verbosity::verbose),
      percent_(verbosity(a) != Verbosity::quiet && !a.has("json")),
      tty_(isatty(fileno(stderr)) != 0)
  {}
  ~Progress_printer() { erase_percentage(); }
  void erase_percentage()
  {
    if (line_shown_) std::cerr << "\r\033[K" << std::flush;
    line_shown_ = false;
  }
  void start_phase(const char* name)
  {
    open_.push_back({name, Clock::now()});
    last_percent_ = -1;
  }
  /// frees the memory the allocator holds at the end of every phase, when
  /// it is more than `bytes` (`release_freed_memory_above`; 0: never):
  /// bounds the resident size of a heap that serves large blocks.
  void release_memory_after_phases(std::size_t bytes) { release_above_ = bytes; }
  void end_phase(const char* name)
  {
    if (open_.empty()) return;
    double s = std::chrono::duration<double>(Clock::now() - open_.back().start).count();
    open_.pop_back();
    if (release_above_ > 0) release_freed_memory_above(release_above_);
    erase_percentage();
    last_percent_ = -1;
    if (phases_)
      std::cerr << "  " << std::string(2 * open_.size(), ' ') << name << ": "
                << std::to_string(s).substr(0, 6) << " s\n";
  }
  void progress(double f)
  {
    if (!(phases_ || percent_) || !tty_ || open_.empty()) return;
    int p = static_cast<int>(f * 100.0);
    if (p == last_percent_) return;
    last_percent_ = p;
    std::cerr << "\r\033[K  " << open_.back().name << " " << p << "%" << std::flush;
    line_shown_ = true;
  }
};

/// a default-constructed `T` that lives until the process ends, for the
/// command's mesh: destroying a 1M-face Surface_mesh just before exit unmaps
/// and frees each of its arrays (tens of milliseconds of a one-second
/// command), where the system takes all the pages back at once when the
/// process exits. The objects stay reachable from a global list, so leak
/// checkers report nothing. A command runs once per process (batch runs its
/// files in child processes), so nothing accumulates.
template <typename T>
T& kept_until_exit()
{
  static auto* kept = new std::vector<std::shared_ptr<void>>();
  auto object = std::make_shared<T>();
  kept->push_back(object);
  return *object;
}

/// wall-clock seconds of `f()`.
template <typename F>
double timed(F&& f)
{
  auto t0 = std::chrono::steady_clock::now();
  f();
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

} // namespace cli
} // namespace mrepair

#endif // MREPAIR_TOOLS_CLI_H
