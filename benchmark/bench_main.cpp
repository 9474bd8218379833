// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// mrepair-bench TASK INPUT [--csv] [--only NAME] [--reference FILE] [--json FILE]: runs every
// variant of TASK on INPUT, each in its own forked process (fresh heap, own peak RSS), and
// prints time, ratio to the mrepair variant, peak memory and the reports side
// by side; --json also writes them to FILE (values as strings, keys section.key).
#include "bench.h"

#include <CGAL/version.h>

#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

namespace {

using mrepair::bench::Measurement;
using mrepair::bench::Task;
using mrepair::bench::Variant;

struct Outcome
{
  bool ran = false;
  std::string failure;
  double seconds = 0;
  double peak_mb = 0;
  std::string status;
  std::vector<std::pair<std::string, std::string>> rows;  // section.key -> value
};

// Child side: run, then write "key\tvalue" lines into the pipe.
void run_child(const Variant& v, const std::string& input, int fd)
{
  std::ostringstream out;
  try {
    Measurement m = v.run(input);
    rusage ru{};
    getrusage(RUSAGE_SELF, &ru);
    out << "seconds\t" << std::setprecision(6) << m.seconds << "\n";
    out << "peak_mb\t" << ru.ru_maxrss / 1024.0 << "\n";
    out << "status\t" << m.status << "\n";
    for (auto& kv : m.before.flatten("before")) out << kv.first << "\t" << kv.second << "\n";
    for (auto& kv : m.result.flatten("result")) out << kv.first << "\t" << kv.second << "\n";
    for (auto& kv : m.after.flatten("after")) out << kv.first << "\t" << kv.second << "\n";
  } catch (const std::exception& e) {
    out << "failure\t" << e.what() << "\n";
  }
  std::string s = out.str();
  const char* p = s.data();
  std::size_t left = s.size();
  while (left > 0) {
    ssize_t w = write(fd, p, left);
    if (w <= 0) break;
    p += w;
    left -= static_cast<std::size_t>(w);
  }
  close(fd);
  _exit(0);
}

Outcome run_variant(const Variant& v, const std::string& input)
{
  Outcome o;
  int fds[2];
  if (pipe(fds) != 0) {
    o.failure = "pipe failed";
    return o;
  }
  std::cout.flush();
  pid_t pid = fork();
  if (pid == 0) {
    close(fds[0]);
    run_child(v, input, fds[1]);
  }
  close(fds[1]);
  std::string text;
  char buf[4096];
  ssize_t r;
  while ((r = read(fds[0], buf, sizeof buf)) > 0) text.append(buf, static_cast<std::size_t>(r));
  close(fds[0]);
  int wstatus = 0;
  waitpid(pid, &wstatus, 0);
  if (!WIFEXITED(wstatus)) {
    // SIGALRM: a task's time bound (e.g. MREPAIR_BENCH_TIME_LIMIT) ran out
    o.failure = WTERMSIG(wstatus) == SIGALRM
                    ? std::string("over the time limit")
                    : "crashed (signal " + std::to_string(WTERMSIG(wstatus)) + ")";
    return o;
  }
  std::istringstream in(text);
  std::string line;
  while (std::getline(in, line)) {
    auto tab = line.find('\t');
    if (tab == std::string::npos) continue;
    std::string k = line.substr(0, tab), val = line.substr(tab + 1);
    if (k == "seconds")
      o.seconds = std::stod(val);
    else if (k == "peak_mb")
      o.peak_mb = std::stod(val);
    else if (k == "status")
      o.status = val;
    else if (k == "failure")
      o.failure = val;
    else
      o.rows.emplace_back(k, val);
  }
  o.ran = o.failure.empty();
  return o;
}

void usage()
{
  std::cout << "usage: mrepair-bench TASK INPUT [--csv] [--only NAME] [--reference FILE] [--json FILE]\n\ntasks:\n";
  for (const Task& t : mrepair::bench::tasks()) {
    std::cout << "  " << t.name << ": " << t.summary << "\n    variants:";
    for (const Variant& v : t.variants) std::cout << " [" << v.name << "]";
    std::cout << "\n";
  }
}

std::string fmt(double v, int prec = 3)
{
  std::ostringstream s;
  s << std::fixed << std::setprecision(prec) << v;
  return s.str();
}

} // namespace

int main(int argc, char** argv)
{
  if (argc < 3) {
    usage();
    return argc < 2 ? 2 : (std::string(argv[1]) == "--help" ? 0 : 2);
  }
  std::string task_name = argv[1], input = argv[2], only, json_path;
  bool csv = false;
  for (int i = 3; i < argc; ++i) {
    std::string a = argv[i];
    if (a == "--csv")
      csv = true;
    else if (a == "--only" && i + 1 < argc)
      only = argv[++i];
    else if (a == "--json" && i + 1 < argc)
      json_path = argv[++i];
    else if (a == "--reference" && i + 1 < argc)
      mrepair::bench::reference_path() = argv[++i];
    else {
      std::cerr << "mrepair-bench: unknown option " << a << "\n";
      return 2;
    }
  }
  const Task* task = nullptr;
  for (const Task& t : mrepair::bench::tasks())
    if (t.name == task_name) task = &t;
  if (!task) {
    std::cerr << "mrepair-bench: unknown task '" << task_name << "'\n";
    usage();
    return 2;
  }

  std::vector<const Variant*> chosen;
  std::vector<Outcome> outcomes;
  for (const Variant& v : task->variants) {
    if (!only.empty() && v.name.find(only) == std::string::npos) continue;
    std::cerr << "running " << v.name << " ..." << std::endl;
    chosen.push_back(&v);
    outcomes.push_back(run_variant(v, input));
  }

  // Rows: union of keys in first-seen order.
  std::vector<std::string> keys;
  std::vector<std::map<std::string, std::string>> values(outcomes.size());
  for (std::size_t i = 0; i < outcomes.size(); ++i)
    for (auto& kv : outcomes[i].rows) {
      if (std::find(keys.begin(), keys.end(), kv.first) == keys.end()) keys.push_back(kv.first);
      values[i][kv.first] = kv.second;
    }

  const double base = outcomes.empty() || !outcomes[0].ran ? 0 : outcomes[0].seconds;
  if (!json_path.empty()) {
    using mrepair::json_escape;
    std::ofstream js(json_path);
    js << "{\"task\": \"" << json_escape(task->name) << "\", \"input\": \"" << json_escape(input)
       << "\", \"cgal\": \"" << CGAL_VERSION_STR << "\", \"variants\": [";
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
      const Outcome& o = outcomes[i];
      js << (i ? ",\n  " : "\n  ") << "{\"name\": \"" << json_escape(chosen[i]->name)
         << "\", \"ran\": " << (o.ran ? "true" : "false") << ", \"seconds\": " << o.seconds
         << ", \"peak_mb\": " << o.peak_mb << ", \"status\": \""
         << json_escape(o.ran ? o.status : o.failure) << "\", \"values\": {";
      for (std::size_t k = 0; k < o.rows.size(); ++k)
        js << (k ? ", " : "") << "\"" << json_escape(o.rows[k].first) << "\": \""
           << json_escape(o.rows[k].second) << "\"";
      js << "}}";
    }
    js << "\n]}\n";
    if (!js) std::cerr << "mrepair-bench: cannot write " << json_path << "\n";
  }
  if (csv) {
    std::cout << "task,input,variant,seconds,ratio_to_first,peak_mb,status\n";
    for (std::size_t i = 0; i < outcomes.size(); ++i)
      std::cout << task->name << "," << input << ",\"" << chosen[i]->name << "\","
                << (outcomes[i].ran ? fmt(outcomes[i].seconds, 4) : "") << ","
                << (outcomes[i].ran && base > 0 ? fmt(outcomes[i].seconds / base, 2) : "") << ","
                << fmt(outcomes[i].peak_mb, 1) << ","
                << (outcomes[i].ran ? outcomes[i].status : outcomes[i].failure) << "\n";
    return 0;
  }

  std::size_t w0 = 24;
  for (auto& k : keys) w0 = std::max(w0, k.size() + 2);
  const std::size_t w = 22;
  auto cell = [w](const std::string& s) {
    return s.size() >= w ? s.substr(0, w - 1) + " " : s + std::string(w - s.size(), ' ');
  };
  std::cout << "task: " << task->name << "   input: " << input << "   CGAL " << CGAL_VERSION_STR << "\n";
  std::cout << std::string(w0, ' ');
  for (auto* v : chosen) std::cout << cell(v->name);
  std::cout << "\n" << std::left << std::setw(static_cast<int>(w0)) << "time [s]";
  for (auto& o : outcomes) std::cout << cell(o.ran ? fmt(o.seconds, 3) : "FAILED");
  std::cout << "\n" << std::setw(static_cast<int>(w0)) << "time / mrepair time";
  for (auto& o : outcomes) std::cout << cell(o.ran && base > 0 ? fmt(o.seconds / base, 2) : "-");
  std::cout << "\n" << std::setw(static_cast<int>(w0)) << "peak RSS [MB]";
  for (auto& o : outcomes) std::cout << cell(fmt(o.peak_mb, 1));
  std::cout << "\n" << std::setw(static_cast<int>(w0)) << "status";
  for (auto& o : outcomes) std::cout << cell(o.ran ? o.status : o.failure);
  std::cout << "\n";
  for (auto& k : keys) {
    std::cout << std::setw(static_cast<int>(w0)) << k;
    for (std::size_t i = 0; i < outcomes.size(); ++i) {
      auto it = values[i].find(k);
      std::cout << cell(it == values[i].end() ? "" : it->second);
    }
    std::cout << "\n";
  }
  return 0;
}
