// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// `mrepair batch IN_DIR OUT_DIR`: `mrepair repair` over every mesh of a folder
// tree, in parallel over files, resumable, each file isolated.
//
// Each file is repaired by a child process running this same executable's
// `repair` command (/proc/self/exe), so a file's output is the one `mrepair
// repair` gives, by construction. The child runs in its own process group
// with an address-space limit (--memory) and is killed with its group when
// it overruns --timeout or when the batch dies (PR_SET_PDEATHSIG). It writes
// its output under a temporary name beside the final one and its report to a
// private temporary folder; the batch renames the output when the repair
// succeeded, then appends the file's manifest line and flushes it to disk.
// A batch killed at any point thus leaves no file marked done that is not
// complete, and loses at most the files in flight. Linux only (fork/exec,
// /proc/self/exe, prctl).
#include "cli.h"
#include "json_lite.h"
#include "repair_options.h"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/file.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

namespace {

namespace cli = mrepair::cli;
namespace fs = std::filesystem;
using cli::Json;
using Clock = std::chrono::steady_clock;

const std::vector<cli::Option>& batch_options()
{
  static const std::vector<cli::Option> o = {
      {"jobs", true, "files repaired at the same time (default: the number of cores)"},
      {"manifest", true,
       "the manifest, one JSON line per file (default: OUT_DIR/manifest.jsonl; '-': standard output)"},
      {"timeout", true, "seconds one file may take; its repair is killed after that (default 0: no limit)"},
      {"memory", true,
       "megabytes of address space one repair may use (RLIMIT_AS; default 0: no limit); a repair "
       "that needs more fails as out_of_memory"},
      {"file", true, "repair only this file of IN_DIR (a path relative to it); used by mrepair.batch"},
      {"threads-per-job", true,
       "threads of each repair (MREPAIR_THREADS of the child; default: MREPAIR_THREADS when set, "
       "else the cores divided among the jobs)"}};
  return o;
}

std::vector<cli::Option> all_options()
{
  std::vector<cli::Option> o = batch_options();
  const auto& r = cli::repair_options();
  o.insert(o.end(), r.begin(), r.end());
  return o;
}

// ---------------------------------------------------------------------------
// Statuses. `done` ones are final: a resumed batch skips them (ok and partial
// only when their output exists). The others depend on limits or on the
// machine and are tried again.

struct Status_info
{
  const char* name;
  bool done;
  bool output;  // an output file was written
  const char* meaning;
};

const Status_info kStatuses[] = {
    {"ok", true, true, "repaired; the output is valid and the repair left no defect it aims at"},
    {"partial", true, true, "repaired; the output is valid, some defects are left (see defects_after)"},
    {"failed", true, false, "the repair could not produce an output (the message names the stage)"},
    {"unreadable", true, false, "the input cannot be read (missing, malformed, unsupported)"},
    {"write_error", false, false, "the output could not be written"},
    {"timeout", false, false, "killed after --timeout seconds"},
    {"out_of_memory", false, false, "ran out of memory (--memory, or the machine's)"},
    {"crashed", false, false, "the repair died on a signal or an internal error"},
};

const Status_info* status_info(const std::string& s)
{
  for (const Status_info& i : kStatuses)
    if (s == i.name) return &i;
  return nullptr;
}

bool is_success(const std::string& s) { return s == "ok" || s == "partial"; }

// ---------------------------------------------------------------------------
// Files

bool is_mesh_file(const fs::path& p)
{
  std::string e = p.extension().string();
  std::transform(e.begin(), e.end(), e.begin(), [](unsigned char c) { return std::tolower(c); });
  return e == ".off" || e == ".obj" || e == ".ply" || e == ".stl";
}

/// the temporary name of an output while its repair runs: hidden, the same
/// extension (the writer picks the format by it), and the host and process
/// of the batch, so that two runs on one file (a Dask task tried again while
/// the first attempt still runs) never write into one file.
fs::path partial_name(const fs::path& out)
{
  char host[256] = {0};
  if (::gethostname(host, sizeof host - 1) != 0) host[0] = 0;
  return out.parent_path() / ("." + out.stem().string() + ".mrepair-partial-" + host + "-" +
                              std::to_string(::getpid()) + out.extension().string());
}

bool is_partial_name(const fs::path& p)
{
  return p.filename().string().find(".mrepair-partial") != std::string::npos;
}

/// removes the temporary outputs a killed batch left under `out_dir`; returns
/// how many.
std::size_t remove_stale_partials(const fs::path& out_dir)
{
  std::size_t n = 0;
  std::error_code ec;
  fs::recursive_directory_iterator it(out_dir, fs::directory_options::skip_permission_denied, ec), end;
  for (; !ec && it != end; it.increment(ec)) {
    std::error_code e2;
    if (it->is_regular_file(e2) && is_partial_name(it->path()) && is_mesh_file(it->path()) &&
        fs::remove(it->path(), e2))
      ++n;
  }
  return n;
}

/// removes the private folders (`mrepair-batch.PID.XXXXXX`) of batches that
/// were killed: those whose process no longer exists.
void remove_dead_temporary_folders(const fs::path& tmp_root)
{
  std::error_code ec;
  for (fs::directory_iterator it(tmp_root, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    const std::string prefix = "mrepair-batch.";
    if (name.compare(0, prefix.size(), prefix) != 0) continue;
    const std::size_t dot = name.find('.', prefix.size());
    if (dot == std::string::npos) continue;
    const std::string pid = name.substr(prefix.size(), dot - prefix.size());
    if (pid.empty() || pid.find_first_not_of("0123456789") != std::string::npos || pid.size() > 9) continue;
    std::error_code e2;
    if (::kill(static_cast<pid_t>(std::stol(pid)), 0) != 0 && errno == ESRCH && it->is_directory(e2))
      fs::remove_all(it->path(), e2);
  }
}

struct Input_file
{
  std::string rel;  // relative to IN_DIR, '/'-separated
  std::uintmax_t bytes = 0;
};

/// every mesh file under `root`, recursively (symbolic links to files followed,
/// to folders not), without `skip` (the output folder when it lies inside).
std::vector<Input_file> find_meshes(const fs::path& root, const fs::path& skip)
{
  std::vector<Input_file> files;
  std::error_code ec;
  fs::recursive_directory_iterator it(root, fs::directory_options::skip_permission_denied, ec), end;
  if (ec) throw cli::Usage_error("cannot list '" + root.string() + "': " + ec.message());
  for (; it != end; it.increment(ec)) {
    if (ec) {
      std::cerr << "mrepair batch: " << ec.message() << " (skipped)\n";
      ec.clear();
      continue;
    }
    const fs::path& p = it->path();
    std::error_code e2;
    if (it->is_directory(e2)) {
      if (!skip.empty() && fs::equivalent(p, skip, e2)) it.disable_recursion_pending();
      continue;
    }
    if (!it->is_regular_file(e2) || !is_mesh_file(p) || is_partial_name(p)) continue;
    Input_file f;
    f.rel = p.lexically_relative(root).generic_string();
    f.bytes = it->file_size(e2);
    if (e2) f.bytes = 0;
    files.push_back(std::move(f));
  }
  std::sort(files.begin(), files.end(), [](const Input_file& a, const Input_file& b) { return a.rel < b.rel; });
  return files;
}

std::string read_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

/// the last line of a child's standard error that says something.
std::string last_line(const std::string& text)
{
  std::istringstream in(text);
  std::string line, last;
  while (std::getline(in, line)) {
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    if (!line.empty()) last = line;
  }
  return last.size() > 2000 ? last.substr(0, 2000) + "..." : last;
}

/// flushes a file's data to disk (the output before its rename).
void sync_file(const fs::path& p)
{
  int fd = ::open(p.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return;
  (void)::fsync(fd);
  ::close(fd);
}

std::string fixed(double v, int digits)
{
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*f", digits, v);
  return buf;
}

std::string duration_text(double s)
{
  if (!(s >= 0.)) return "?";
  long t = static_cast<long>(s + 0.5);
  char buf[32];
  if (t >= 3600) std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", t / 3600, (t / 60) % 60, t % 60);
  else std::snprintf(buf, sizeof buf, "%ld:%02ld", t / 60, t % 60);
  return buf;
}

// ---------------------------------------------------------------------------
// The manifest: one JSON object per line, appended and flushed to disk as
// each file finishes. The keys, always all of them, in this order:

struct Record
{
  std::string path, status, message;
  double seconds = 0., cpu_seconds = 0.;
  long peak_memory_mb = 0;
  int exit_code = -1;  // -1: none (signal)
  std::string signal;  // name when the child died on one
  Json faces_in, faces_out, defects_before, defects_after, face_accounting;  // null when unknown

  std::string line() const
  {
    Json j;
    j.kind = Json::object;
    auto add = [&](const char* k, Json v) { j.members.emplace_back(k, std::move(v)); };
    add("path", Json::make_string(path));
    add("status", Json::make_string(status));
    add("message", Json::make_string(message));
    add("seconds", Json::make_number(fixed(seconds, 3)));
    add("cpu_seconds", Json::make_number(fixed(cpu_seconds, 3)));
    add("peak_memory_mb", Json::make_number(std::to_string(peak_memory_mb)));
    add("exit_code", exit_code >= 0 ? Json::make_number(std::to_string(exit_code)) : Json());
    add("signal", signal.empty() ? Json() : Json::make_string(signal));
    add("faces_in", faces_in);
    add("faces_out", faces_out);
    add("defects_before", defects_before);
    add("defects_after", defects_after);
    add("face_accounting", face_accounting);
    return j.dump() + "\n";
  }
};

class Manifest
{
  int fd_ = -1;
  bool stdout_ = false;

public:
  struct Entry
  {
    std::string status;
    double seconds = 0.;
    std::string message;
  };
  std::map<std::string, Entry> last;  // path -> its last line
  std::size_t lines = 0, unreadable_lines = 0;

  /// opens `path` for appending ("-": standard output) after reading what
  /// it holds; locks it so that two batches cannot write one manifest.
  void open(const std::string& path)
  {
    if (path == "-") {
      stdout_ = true;
      return;
    }
    fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_APPEND | O_CLOEXEC, 0644);
    if (fd_ < 0) throw cli::Usage_error("cannot open the manifest '" + path + "': " + std::strerror(errno));
    if (::flock(fd_, LOCK_EX | LOCK_NB) != 0)
      throw cli::Usage_error("the manifest '" + path + "' is in use by another batch");
    std::istringstream in(read_file(path));
    std::string l;
    while (std::getline(in, l)) {
      if (l.find_first_not_of(" \t\r") == std::string::npos) continue;
      ++lines;
      Json j;
      const Json *p, *s;
      // a line cut short (a machine that lost power mid-write) is ignored
      if (!cli::parse_json(l, j) || !(p = j.find("path")) || !(s = j.find("status")) ||
          p->kind != Json::string || s->kind != Json::string) {
        ++unreadable_lines;
        continue;
      }
      Entry e;
      e.status = s->text;
      if (const Json* t = j.find("seconds"))
        if (t->kind == Json::number) e.seconds = std::atof(t->text.c_str());
      if (const Json* m = j.find("message"))
        if (m->kind == Json::string) e.message = m->text;
      last[p->text] = e;
    }
  }
  /// appends one line and flushes it to disk (one write: a kill cannot cut it).
  void append(const Record& r)
  {
    const std::string l = r.line();
    if (stdout_) {
      std::cout << l << std::flush;
      return;
    }
    std::size_t off = 0;
    while (off < l.size()) {
      ssize_t n = ::write(fd_, l.data() + off, l.size() - off);
      if (n < 0 && errno == EINTR) continue;
      if (n <= 0) {
        std::cerr << "mrepair batch: cannot write the manifest: " << std::strerror(errno) << "\n";
        return;
      }
      off += static_cast<std::size_t>(n);
    }
    ::fdatasync(fd_);
  }
  ~Manifest()
  {
    if (fd_ >= 0) ::close(fd_);
  }
};

// ---------------------------------------------------------------------------
// Children

struct Limits
{
  double timeout = 0.;        // seconds, 0: none
  unsigned long memory = 0;   // MB, 0: none
  std::string threads;        // MREPAIR_THREADS of the child, empty: inherited
};

struct Job
{
  std::size_t file = 0;  // index into the work list
  pid_t pid = -1;
  Clock::time_point start;
  bool timed_out = false;
  fs::path input, output, partial, report, errors;
};

const char* signal_name(int s)
{
  switch (s) {
    case SIGSEGV: return "SIGSEGV";
    case SIGABRT: return "SIGABRT";
    case SIGBUS: return "SIGBUS";
    case SIGFPE: return "SIGFPE";
    case SIGILL: return "SIGILL";
    case SIGKILL: return "SIGKILL";
    case SIGTERM: return "SIGTERM";
    case SIGINT: return "SIGINT";
    case SIGPIPE: return "SIGPIPE";
    case SIGXCPU: return "SIGXCPU";
    default: return nullptr;
  }
}

/// starts `mrepair repair INPUT PARTIAL --quiet --report REPORT [options]`
/// in a new process group; returns its pid (-1 with `error` when fork fails).
pid_t start_child(const Job& job, const std::vector<std::string>& repair_args, const Limits& limits,
                  const sigset_t& parent_mask, std::string& error)
{
  std::vector<std::string> args = {"mrepair", "repair", job.input.string(), job.partial.string(),
                                    "--quiet", "--report", job.report.string()};
  args.insert(args.end(), repair_args.begin(), repair_args.end());
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(&a[0]);
  argv.push_back(nullptr);
  // the environment, with MREPAIR_THREADS replaced when the batch sets it
  std::vector<std::string> env_strings;
  for (char** e = environ; *e; ++e)
    if (limits.threads.empty() || std::strncmp(*e, "MREPAIR_THREADS=", 16) != 0) env_strings.push_back(*e);
  if (!limits.threads.empty()) env_strings.push_back("MREPAIR_THREADS=" + limits.threads);
  std::vector<char*> envp;
  for (std::string& e : env_strings) envp.push_back(&e[0]);
  envp.push_back(nullptr);
  const pid_t parent = ::getpid();

  const pid_t pid = ::fork();
  if (pid < 0) {
    error = std::string("fork: ") + std::strerror(errno);
    return -1;
  }
  if (pid == 0) {
    // the child: only async-signal-safe calls from here to exec
    ::setpgid(0, 0);
    ::prctl(PR_SET_PDEATHSIG, SIGKILL);
    if (::getppid() != parent) ::_exit(126);  // the batch died before the line above
    struct sigaction dfl;
    std::memset(&dfl, 0, sizeof dfl);
    dfl.sa_handler = SIG_DFL;
    for (int s : {SIGCHLD, SIGINT, SIGTERM, SIGHUP, SIGPIPE}) ::sigaction(s, &dfl, nullptr);
    ::sigprocmask(SIG_SETMASK, &parent_mask, nullptr);
    int in = ::open("/dev/null", O_RDONLY);
    int out = ::open("/dev/null", O_WRONLY);
    int err = ::open(job.errors.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (in < 0 || out < 0 || err < 0) ::_exit(125);
    ::dup2(in, 0);
    ::dup2(out, 1);
    ::dup2(err, 2);
    if (limits.memory > 0) {
      struct rlimit rl;
      rl.rlim_cur = rl.rlim_max = static_cast<rlim_t>(limits.memory) << 20;
      ::setrlimit(RLIMIT_AS, &rl);
    }
    ::execve("/proc/self/exe", argv.data(), envp.data());
    const char msg[] = "mrepair batch: cannot run /proc/self/exe\n";
    (void)!::write(2, msg, sizeof msg - 1);
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // beside the child's own call: whichever runs first
  return pid;
}

/// the manifest record of a finished child from its exit, report and errors.
Record finish_child(const Job& job, const std::string& rel, int wstatus, const struct rusage& ru,
                    double seconds, const Limits& limits)
{
  Record r;
  r.path = rel;
  r.seconds = seconds;
  r.cpu_seconds = ru.ru_utime.tv_sec + ru.ru_utime.tv_usec * 1e-6 + ru.ru_stime.tv_sec + ru.ru_stime.tv_usec * 1e-6;
  r.peak_memory_mb = ru.ru_maxrss / 1024;  // KiB on Linux
  const std::string errors = read_file(job.errors.string());
  std::string message = last_line(errors);
  const std::string prefix = "mrepair repair: ";
  if (message.compare(0, prefix.size(), prefix) == 0) message = message.substr(prefix.size());
  else if (message.compare(0, 9, "mrepair: ") == 0) message = message.substr(9);

  Json report;
  std::error_code ec;
  const bool have_report = fs::exists(job.report, ec) && cli::parse_json(read_file(job.report.string()), report) &&
                           report.kind == Json::object;
  if (have_report) {
    if (const Json* fa = report.find("face_accounting")) {
      r.face_accounting = *fa;
      if (const Json* n = fa->find("faces_in")) r.faces_in = *n;
      if (const Json* n = fa->find("faces_out")) r.faces_out = *n;
    }
    if (r.faces_in.kind == Json::null_value)
      if (const Json* n = report.find({"before", "input", "faces"})) r.faces_in = *n;
    if (const Json* d = report.find({"before", "defects"})) r.defects_before = *d;
    if (const Json* d = report.find({"after", "defects"})) r.defects_after = *d;
  }

  const bool out_of_memory = errors.find("out of memory") != std::string::npos ||
                             errors.find("std::bad_alloc") != std::string::npos ||
                             errors.find("Cannot allocate memory") != std::string::npos;
  const std::string memory_note =
      limits.memory > 0 ? " (limit: --memory " + std::to_string(limits.memory) + " MB)" : std::string();
  if (WIFSIGNALED(wstatus)) {
    const int s = WTERMSIG(wstatus);
    const char* name = signal_name(s);
    r.signal = name ? name : "signal " + std::to_string(s);
    if (job.timed_out) {
      r.status = "timeout";
      r.message = "killed after " + fixed(limits.timeout, 1) + " s";
    } else if (out_of_memory) {
      r.status = "out_of_memory";
      r.message = message + memory_note;
    } else {
      r.status = "crashed";
      r.message = "killed by " + r.signal +
                  (s == SIGKILL ? " (the kernel's out-of-memory killer, or a user)" : "") +
                  (message.empty() ? "" : "; last message: " + message);
    }
    return r;
  }
  r.exit_code = WEXITSTATUS(wstatus);
  if (job.timed_out) {  // it ended on its own as it was killed
    r.status = "timeout";
    r.message = "killed after " + fixed(limits.timeout, 1) + " s";
  } else if (r.exit_code == 0) {
    // the repair's own status: that of its cleaning, `ok` or `partial`
    const Json* s = have_report ? report.find({"clean", "status"}) : nullptr;
    r.status = s && s->kind == Json::string && s->text == "partial" ? "partial" : "ok";
  } else if (out_of_memory) {
    r.status = "out_of_memory";
    r.message = message + memory_note;
  } else if (r.exit_code == 1) {
    const Json* w = have_report ? report.find({"output", "status"}) : nullptr;
    if (!have_report) r.status = "unreadable";
    else if (w && w->kind == Json::string && w->text != "ok") r.status = "write_error";
    else r.status = "failed";
    r.message = message;
  } else {
    r.status = "crashed";
    r.message = "exit code " + std::to_string(r.exit_code) + (message.empty() ? "" : ": " + message);
  }
  if (r.message.empty() && !is_success(r.status)) r.message = "exit code " + std::to_string(r.exit_code);
  return r;
}

// ---------------------------------------------------------------------------
// Progress on standard error: a bar with an ETA on a terminal, a plain line
// every 10 s otherwise.

class Progress
{
  bool enabled_, tty_;
  std::size_t total_;
  std::uintmax_t total_bytes_;
  Clock::time_point start_ = Clock::now(), last_ = start_;
  bool drawn_ = false;

public:
  Progress(bool enabled, std::size_t total, std::uintmax_t bytes)
    : enabled_(enabled && total > 0), tty_(isatty(fileno(stderr)) != 0), total_(total), total_bytes_(bytes)
  {}
  void update(std::size_t done, std::size_t failed, std::uintmax_t bytes_done, std::size_t running, bool force)
  {
    if (!enabled_) return;
    const auto now = Clock::now();
    const double since = std::chrono::duration<double>(now - last_).count();
    if (!force && since < (tty_ ? 0.25 : 10.)) return;
    last_ = now;
    const double elapsed = std::chrono::duration<double>(now - start_).count();
    // ETA by bytes (file sizes differ by orders of magnitude), by files when none
    double eta = -1.;
    if (bytes_done > 0 && total_bytes_ > bytes_done)
      eta = elapsed * double(total_bytes_ - bytes_done) / double(bytes_done);
    else if (done > 0)
      eta = elapsed * double(total_ - done) / double(done);
    if (done == total_) eta = 0.;
    const double rate = elapsed > 0. ? done / elapsed : 0.;
    std::ostringstream s;
    if (tty_) {
      const int width = 30;
      const int fill = static_cast<int>(width * double(done) / double(total_));
      s << "\r\033[K[" << std::string(fill, '#') << std::string(width - fill, '-') << "] ";
    } else {
      s << "mrepair batch: ";
    }
    s << done << "/" << total_ << " files";
    if (failed) s << " (" << failed << " failed)";
    s << ", " << running << " running, " << fixed(rate, 2) << " files/s, elapsed " << duration_text(elapsed)
      << ", ETA " << (eta < 0. ? std::string("?") : duration_text(eta));
    if (!tty_) s << "\n";
    std::cerr << s.str() << std::flush;
    drawn_ = true;
  }
  void finish()
  {
    if (enabled_ && tty_ && drawn_) std::cerr << "\n";
  }
};

// ---------------------------------------------------------------------------

volatile sig_atomic_t g_signal = 0;
void note_signal(int s) { g_signal = s; }

int run_batch(int argc, char** argv)
{
  static const cli::Command self{
      "batch", "IN_DIR OUT_DIR [--jobs N] [--manifest FILE.jsonl] [--timeout SEC] [--memory MB] [repair options]",
      "repairs every mesh under IN_DIR (OFF/OBJ/PLY/STL, recursively) into OUT_DIR: `mrepair repair` "
      "per file, in parallel, resumable, each file isolated",
      nullptr};
  const std::vector<cli::Option> options = all_options();
  cli::Arguments a = cli::parse(argc, argv, 1, options, 2, 2);
  if (a.has("help")) {
    cli::print_help(self, options);
    std::cout << "statuses in the manifest (done: skipped when the batch is run again):\n";
    for (const Status_info& s : kStatuses)
      std::cout << "  " << s.name << (s.done ? " (done)" : "") << ": " << s.meaning << "\n";
    return 0;
  }
  // the repair options are checked here once, by `repair`'s own code: a typo
  // fails the batch at once rather than every file
  (void)cli::parse_repair_options(a);
  const std::vector<std::string> repair_args = cli::repair_arguments(a);

  const unsigned cores = std::max(1u, std::thread::hardware_concurrency());
  const long long jobs_arg = a.get_int("jobs", cores);
  if (jobs_arg < 1 || jobs_arg > 1024) throw cli::Usage_error("--jobs must be from 1 to 1024");
  const std::size_t jobs = static_cast<std::size_t>(jobs_arg);
  Limits limits;
  limits.timeout = a.get_double("timeout", 0.);
  if (limits.timeout < 0.) throw cli::Usage_error("--timeout must be >= 0 (0: no limit)");
  const long long memory = a.get_int("memory", 0);
  if (memory < 0) throw cli::Usage_error("--memory must be >= 0 (0: no limit)");
  limits.memory = static_cast<unsigned long>(memory);
  if (a.has("threads-per-job")) {
    const long long t = a.get_int("threads-per-job", 0);
    if (t < 1 || t > 4096) throw cli::Usage_error("--threads-per-job must be from 1 to 4096");
    limits.threads = std::to_string(t);
  } else if (jobs > 1 && !a.has("file")) {
    // the cores shared among the jobs, unless MREPAIR_THREADS says otherwise
    // (the outputs do not depend on the number of threads)
    const char* env = std::getenv("MREPAIR_THREADS");
    if (env == nullptr || *env == 0) limits.threads = std::to_string(std::max<std::size_t>(1, cores / jobs));
  }
  const bool quiet = a.has("quiet");

  std::error_code ec;
  const fs::path in_dir = a.positional[0], out_dir = a.positional[1];
  if (!fs::is_directory(in_dir, ec)) throw cli::Usage_error("'" + in_dir.string() + "' is not a folder");
  fs::create_directories(out_dir, ec);
  if (!fs::is_directory(out_dir, ec))
    return cli::fail("cannot create the output folder '" + out_dir.string() + "'");
  if (fs::equivalent(in_dir, out_dir, ec))
    throw cli::Usage_error("OUT_DIR must differ from IN_DIR (the outputs would replace the inputs)");

  std::vector<Input_file> files;
  if (a.has("file")) {
    const fs::path rel = fs::path(a.get("file")).lexically_normal();
    if (rel.is_absolute() || rel.empty() || *rel.begin() == "..")
      throw cli::Usage_error("--file takes a path relative to IN_DIR");
    Input_file f;
    f.rel = rel.generic_string();
    f.bytes = fs::file_size(in_dir / rel, ec);
    if (ec) f.bytes = 0;
    files.push_back(f);
  } else {
    // the output folder is left out when it lies inside the input folder
    files = find_meshes(in_dir, out_dir);
  }

  Manifest manifest;
  const std::string manifest_path = a.get("manifest", (out_dir / "manifest.jsonl").string());
  manifest.open(manifest_path);
  if (manifest.unreadable_lines)
    std::cerr << "mrepair batch: " << manifest.unreadable_lines << " unreadable line(s) in the manifest ignored\n";

  // the temporary outputs of a batch that was killed (the manifest lock says
  // that no other batch of this manifest runs; with --file, mrepair.batch
  // does this under its own lock)
  if (manifest_path != "-" && !a.has("file")) {
    const std::size_t stale = remove_stale_partials(out_dir);
    if (stale && !quiet) std::cerr << "mrepair batch: removed " << stale << " temporary output(s) of an earlier run\n";
  }

  // resume: a file whose last line says done is skipped, when its output exists
  std::vector<std::size_t> todo;
  std::map<std::string, std::string> latest;  // path -> status, over every file
  std::size_t skipped = 0;
  std::uintmax_t todo_bytes = 0;
  for (std::size_t i = 0; i < files.size(); ++i) {
    auto it = manifest.last.find(files[i].rel);
    if (it != manifest.last.end()) {
      const Status_info* s = status_info(it->second.status);
      if (s && s->done && (!s->output || fs::exists(out_dir / files[i].rel, ec))) {
        latest[files[i].rel] = it->second.status;
        ++skipped;
        continue;
      }
    }
    todo.push_back(i);
    todo_bytes += files[i].bytes;
  }
  // largest first: the long repairs start early and the end of the batch is short
  std::stable_sort(todo.begin(), todo.end(),
                   [&](std::size_t x, std::size_t y) { return files[x].bytes > files[y].bytes; });
  if (!quiet && skipped)
    std::cerr << "mrepair batch: " << skipped << " of " << files.size()
              << " files already done (manifest), " << todo.size() << " to repair\n";

  // private folder of the children's reports and messages
  fs::path tmp_root = fs::temp_directory_path(ec);
  if (ec || tmp_root.empty()) tmp_root = "/tmp";
  remove_dead_temporary_folders(tmp_root);
  std::string tmpl = (tmp_root / ("mrepair-batch." + std::to_string(::getpid()) + ".XXXXXX")).string();
  if (!::mkdtemp(&tmpl[0])) return cli::fail(std::string("cannot create a temporary folder: ") + std::strerror(errno));
  const fs::path tmp_dir = tmpl;

  // SIGCHLD, SIGINT, SIGTERM and SIGHUP are taken synchronously by sigtimedwait
  sigset_t wait_set, old_mask;
  sigemptyset(&wait_set);
  for (int s : {SIGCHLD, SIGINT, SIGTERM, SIGHUP}) sigaddset(&wait_set, s);
  struct sigaction sa, old_chld;
  std::memset(&sa, 0, sizeof sa);
  sa.sa_handler = note_signal;
  ::sigaction(SIGCHLD, &sa, &old_chld);  // a handler, so SIGCHLD is never discarded
  ::sigprocmask(SIG_BLOCK, &wait_set, &old_mask);

  const auto t0 = Clock::now();
  Progress progress(!quiet, todo.size(), todo_bytes);
  std::vector<Job> running;
  std::vector<Record> records;  // of this run
  std::size_t next = 0, failed = 0;
  std::uintmax_t bytes_done = 0;
  int interrupted = 0;
  std::vector<std::size_t> slots;  // free slot numbers (names of the temporary files)
  for (std::size_t s = jobs; s-- > 0;) slots.push_back(s);
  std::map<pid_t, std::size_t> slot_of;

  auto finish = [&](Job& job, int wstatus, const struct rusage& ru) {
    const Input_file& f = files[job.file];
    const double seconds = std::chrono::duration<double>(Clock::now() - job.start).count();
    Record r = finish_child(job, f.rel, wstatus, ru, seconds, limits);
    std::error_code e;
    if (is_success(r.status)) {
      sync_file(job.partial);
      fs::rename(job.partial, job.output, e);
      if (e) {
        r.status = "write_error";
        r.message = "cannot rename '" + job.partial.string() + "' to '" + job.output.string() + "': " + e.message();
      }
    }
    fs::remove(job.partial, e);
    fs::remove(job.report, e);
    fs::remove(job.errors, e);
    manifest.append(r);
    latest[r.path] = r.status;
    if (!is_success(r.status)) ++failed;
    bytes_done += f.bytes;
    records.push_back(std::move(r));
  };

  while ((next < todo.size() && !interrupted) || !running.empty()) {
    // reap every finished child (before starting others: their slots are free)
    while (true) {
      int wstatus = 0;
      struct rusage ru;
      const pid_t pid = ::wait4(-1, &wstatus, WNOHANG, &ru);
      if (pid <= 0) break;
      auto it = std::find_if(running.begin(), running.end(), [&](const Job& j) { return j.pid == pid; });
      if (it == running.end()) continue;
      ::kill(-pid, SIGKILL);  // anything the repair left in its group
      if (!interrupted || WIFEXITED(wstatus)) finish(*it, wstatus, ru);
      else {
        std::error_code e;
        fs::remove(it->partial, e);
      }
      slots.push_back(slot_of[pid]);
      slot_of.erase(pid);
      running.erase(it);
    }
    while (!interrupted && running.size() < jobs && next < todo.size()) {
      Job job;
      job.file = todo[next++];
      const Input_file& f = files[job.file];
      job.input = in_dir / f.rel;
      job.output = out_dir / f.rel;
      job.partial = partial_name(job.output);
      const std::size_t slot = slots.back();
      slots.pop_back();
      job.report = tmp_dir / ("report" + std::to_string(slot) + ".json");
      job.errors = tmp_dir / ("stderr" + std::to_string(slot) + ".txt");
      std::error_code e;
      fs::remove(job.report, e);
      fs::create_directories(job.output.parent_path(), e);
      std::string error;
      job.start = Clock::now();
      job.pid = e ? -1 : start_child(job, repair_args, limits, old_mask, error);
      if (job.pid < 0) {
        Record r;
        r.path = f.rel;
        r.status = e ? "write_error" : "crashed";
        r.message = e ? "cannot create '" + job.output.parent_path().string() + "': " + e.message()
                      : "cannot start the repair: " + error;
        manifest.append(r);
        latest[r.path] = r.status;
        ++failed;
        records.push_back(r);
        slots.push_back(slot);
        continue;
      }
      slot_of[job.pid] = slot;
      running.push_back(std::move(job));
    }
    progress.update(records.size(), failed, bytes_done, running.size(), false);
    if (running.empty()) continue;
    // sleep until a child ends, a signal comes, a deadline or the next progress tick
    double wait = quiet ? 3600. : 0.25;
    const auto now = Clock::now();
    if (limits.timeout > 0.)
      for (Job& j : running) {
        const double left = limits.timeout - std::chrono::duration<double>(now - j.start).count();
        if (left <= 0. && !j.timed_out) {
          ::kill(-j.pid, SIGKILL);
          j.timed_out = true;
        }
        if (!j.timed_out) wait = std::min(wait, std::max(left, 0.001));
      }
    struct timespec ts;
    ts.tv_sec = static_cast<time_t>(wait);
    ts.tv_nsec = static_cast<long>((wait - double(ts.tv_sec)) * 1e9);
    siginfo_t info;
    const int s = ::sigtimedwait(&wait_set, &info, &ts);
    if ((s == SIGINT || s == SIGTERM || s == SIGHUP) && !interrupted) {
      interrupted = s;
      for (Job& j : running) ::kill(-j.pid, SIGKILL);
    }
  }
  progress.update(records.size(), failed, bytes_done, 0, true);
  progress.finish();
  const double total_seconds = std::chrono::duration<double>(Clock::now() - t0).count();
  fs::remove_all(tmp_dir, ec);
  ::sigprocmask(SIG_SETMASK, &old_mask, nullptr);
  ::sigaction(SIGCHLD, &old_chld, nullptr);

  // summary: over every file, its latest status (this run or an earlier one)
  std::map<std::string, std::size_t> counts;
  for (const Status_info& s : kStatuses) counts[s.name] = 0;
  std::size_t not_repaired = 0;
  for (const auto& x : latest) {
    ++counts[x.second];
    if (!is_success(x.second)) ++not_repaired;
  }
  std::vector<const Record*> slowest, worst;
  for (const Record& r : records) {
    slowest.push_back(&r);
    if (!is_success(r.status)) worst.push_back(&r);
  }
  std::sort(slowest.begin(), slowest.end(), [](const Record* x, const Record* y) { return x->seconds > y->seconds; });
  if (slowest.size() > 5) slowest.resize(5);
  std::sort(worst.begin(), worst.end(), [](const Record* x, const Record* y) { return x->path < y->path; });

  mrepair::Report report;
  report.add("files", files.size());
  report.add("skipped_as_done", skipped);
  report.add("repaired_now", records.size());
  report.add("not_started", todo.size() - std::min(todo.size(), records.size()));
  mrepair::Report& st = report.section("statuses");
  for (const Status_info& s : kStatuses) st.add(s.name, counts[s.name]);
  report.add("seconds", total_seconds);
  report.add("jobs", jobs);
  report.add("files_per_second", total_seconds > 0. ? records.size() / total_seconds : 0.);
  report.add("manifest", manifest_path);
  if (interrupted) report.add("interrupted_by", signal_name(interrupted) ? signal_name(interrupted) : "signal");
  mrepair::Report& sl = report.section("slowest");
  for (const Record* r : slowest) sl.add(r->path, r->seconds);
  mrepair::Report& nr = report.section("not_repaired");
  for (const Record* r : worst) nr.add(r->path, r->status + ": " + r->message);

  if (a.has("json") || manifest_path == "-") {
    if (a.has("json") && manifest_path != "-") std::cout << report.to_json() << "\n";
  } else if (!quiet || not_repaired) {
    std::cout << "batch: " << files.size() << " files, " << counts["ok"] << " ok, " << counts["partial"]
              << " partial, " << not_repaired << " not repaired";
    if (skipped) std::cout << " (" << skipped << " done before)";
    if (records.size() < todo.size()) std::cout << ", " << todo.size() - records.size() << " left to do";
    std::cout << "; " << records.size() << " repaired in " << fixed(total_seconds, 1) << " s with " << jobs
              << " job" << (jobs > 1 ? "s" : "") << "\n";
    for (const Status_info& s : kStatuses)
      if (!is_success(s.name) && counts[s.name]) std::cout << "  " << s.name << ": " << counts[s.name] << "\n";
    if (!worst.empty()) {
      std::cout << "not repaired:\n";
      std::size_t shown = 0;
      for (const Record* r : worst) {
        if (++shown > 20) {
          std::cout << "  ... " << worst.size() - 20 << " more in the manifest\n";
          break;
        }
        std::cout << "  " << r->path << ": " << r->status << (r->message.empty() ? "" : ": " + r->message) << "\n";
      }
    }
    if (!slowest.empty() && !quiet) {
      std::cout << "slowest:";
      for (const Record* r : slowest) std::cout << " " << r->path << " " << fixed(r->seconds, 2) << " s;";
      std::cout << "\n";
    }
    if (interrupted)
      std::cout << "interrupted by " << (signal_name(interrupted) ? signal_name(interrupted) : "a signal")
                << ": run the same command again to go on\n";
  }
  if (a.has("report")) {
    std::ofstream out(a.get("report"));
    out << report.to_json() << "\n";
    if (!out) return cli::fail("cannot write the report '" + a.get("report") + "'");
  }
  if (interrupted) return 128 + interrupted;
  return not_repaired ? 1 : 0;
}

cli::Registrar reg{{"batch", "IN_DIR OUT_DIR [--jobs N] [--manifest FILE.jsonl] [--timeout SEC] [--memory MB] [repair options]",
                    "repairs every mesh of a folder tree (repair per file, parallel, resumable, isolated)",
                    run_batch}};

}  // namespace
