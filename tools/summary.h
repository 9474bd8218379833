// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The few lines a command prints by default (issue 53): its status and
// profile, faces and vertices in -> out, each defect count that changed,
// closed, intersection-free, the time, the output and the report written.
// `--verbose` prints the full report instead, `--json` the report as JSON,
// `--quiet` nothing. No CGAL here: every command includes it.
//
//   cli::Summary summary("repair");       // starts the clock
//   summary.set_status(r.status, why);
//   summary.set_sizes(faces_in, faces_out, vertices_in, vertices_out);
//   summary.add_changes(r.before, r.after);
//   ...
//   cli::print_summary(args, summary);    // unless --json, --verbose, --quiet
#ifndef MREPAIR_TOOLS_SUMMARY_H
#define MREPAIR_TOOLS_SUMMARY_H

#include "cli.h"

#include <mrepair/inspection_report.h>
#include <mrepair/io_result.h>
#include <mrepair/status.h>

#include <algorithm>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <iostream>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {
namespace cli {

/// a defect count of `Inspection_report`, by its key in the report's
/// `defects` section (the summary's label is the key with spaces)
struct Defect_count
{
  const char* key;
  std::size_t Inspection_report::*count;
};

/// the defect counts a summary compares or lists, in the report's order;
/// boundary edges are left to boundary loops, the self-intersecting pairs
/// are handled apart (they are not always counted)
inline const std::vector<Defect_count>& summary_defect_counts()
{
  using I = Inspection_report;
  static const std::vector<Defect_count> table = {
      {"invalid_polygons", &I::invalid_polygons},
      {"non_finite_vertices", &I::non_finite_vertices},
      {"isolated_vertices", &I::isolated_vertices},
      {"duplicate_points", &I::duplicate_points},
      {"degenerate_faces", &I::degenerate_faces},
      {"duplicate_faces", &I::duplicate_faces},
      {"non_manifold_edges", &I::non_manifold_edges},
      {"non_manifold_vertices", &I::non_manifold_vertices},
      {"inconsistent_orientation_edges", &I::inconsistent_orientation_edges},
      {"boundary_loops", &I::boundary_loops},
      {"small_holes", &I::small_holes},
      {"connected_components", &I::connected_components},
      {"small_components", &I::small_components},
      {"near_degenerate_faces", &I::near_degenerate_faces},
      {"spiked_vertices", &I::spiked_vertices},
      {"t_junctions", &I::t_junctions}};
  return table;
}

/// "self_intersecting_pairs" -> "self intersecting pairs"
inline std::string summary_label(const std::string& key)
{
  std::string s = key;
  std::replace(s.begin(), s.end(), '_', ' ');
  return s;
}

/// a distance or an angle with six significant digits
inline std::string summary_number(double v)
{
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

/// "out.ply (PLY, binary)" from what a writer (or reader) returned
inline std::string describe_file(const std::string& path, const Io_result& io)
{
  std::string format = io.format;
  std::transform(format.begin(), format.end(), format.begin(), [](unsigned char c) { return char(std::toupper(c)); });
  if (format.empty()) return path;
  const bool has_variants = io.format == "ply" || io.format == "stl";
  return path + " (" + format + (has_variants ? (io.binary ? ", binary" : ", ASCII") : "") + ")";
}

/// the short account of one command's run.
class Summary
{
  std::string command_;
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now();
  Status status_ = Status::ok;
  std::string why_;
  std::vector<std::pair<std::string, std::string>> lines_;

  void line(const std::string& label, const std::string& value) { lines_.emplace_back(label, value); }
  static std::string arrow(std::size_t before, std::size_t after)
  {
    return std::to_string(before) + " -> " + std::to_string(after);
  }

public:
  /// the clock starts here: construct it first thing in the command
  explicit Summary(std::string command) : command_(std::move(command)) {}

  /// `why`: one line, printed after a status other than `ok`
  void set_status(Status s, const std::string& why = std::string())
  {
    status_ = s;
    why_ = why;
    const std::size_t newline = why_.find('\n');
    if (newline != std::string::npos) why_.resize(newline);
  }
  void add_profile(const std::string& profile) { line("profile", profile); }
  void add_sizes(std::size_t faces_in, std::size_t faces_out, std::size_t vertices_in, std::size_t vertices_out)
  {
    line("faces", arrow(faces_in, faces_out));
    line("vertices", arrow(vertices_in, vertices_out));
  }
  /// a count before -> after, only when it changed
  void add_change(const std::string& key, std::size_t before, std::size_t after)
  {
    if (before != after) line(summary_label(key), arrow(before, after));
  }
  /// a count that is not a before/after pair ("holes filled 12")
  void add_count(const std::string& key, std::size_t n) { line(summary_label(key), std::to_string(n)); }
  /// each defect count of the two inspections that changed
  void add_changes(const Inspection_report& before, const Inspection_report& after)
  {
    for (const Defect_count& d : summary_defect_counts()) add_change(d.key, before.*d.count, after.*d.count);
    if (before.self_intersections_counted && after.self_intersections_counted)
      add_change("self_intersecting_pairs", before.self_intersecting_pairs, after.self_intersecting_pairs);
  }
  /// each defect count of one inspection that is not zero ("no defects" when none)
  void add_defects(const Inspection_report& found)
  {
    bool any = false;
    for (const Defect_count& d : summary_defect_counts()) {
      if (std::string(d.key) == "connected_components") continue;  // not a defect: listed apart
      if (found.*d.count == 0) continue;
      add_count(d.key, found.*d.count);
      any = true;
    }
    if (found.self_intersections_counted && found.self_intersecting_pairs > 0) {
      add_count("self_intersecting_pairs", found.self_intersecting_pairs);
      any = true;
    }
    if (!any) line("defects", "none found");
  }
  void add_closed(bool closed) { line("closed", closed ? "yes" : "no"); }
  /// "yes", "no" or "not computed", as the inspection's `intersection_free`
  void add_intersection_free(const Inspection_report& i)
  {
    line("intersection-free", !i.self_intersections_counted ? "not computed"
                              : i.self_intersecting_pairs == i.self_intersecting_pairs_touching ? "yes"
                                                                                             : "no");
  }
  void add_line(const std::string& label, const std::string& value) { line(label, value); }
  void add_output(const std::string& path, const Io_result& written) { line("output", describe_file(path, written)); }
  /// the report file, when `--report` was given
  void add_report(const Arguments& a)
  {
    if (a.has("report")) line("report", a.get("report"));
  }

  /// the summary's lines: "mrepair COMMAND: status[: why]", then the
  /// lines in their order, the time before the output and report lines
  std::string to_text() const
  {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    char time[32];
    std::snprintf(time, sizeof time, "%.2f s", seconds);
    std::vector<std::pair<std::string, std::string>> all;
    for (const auto& l : lines_)
      if (l.first != "output" && l.first != "report") all.push_back(l);
    all.emplace_back("time", time);
    for (const auto& l : lines_)
      if (l.first == "output" || l.first == "report") all.push_back(l);
    std::size_t width = 0;
    for (const auto& l : all) width = std::max(width, l.first.size());
    std::string out = "mrepair " + command_ + ": " + to_string(status_) +
                      (status_ != Status::ok && !why_.empty() ? ": " + why_ : std::string()) + "\n";
    for (const auto& l : all) out += "  " + l.first + std::string(width - l.first.size() + 2, ' ') + l.second + "\n";
    return out;
  }
};

/// prints `s` on stdout in the default mode (not with --json, --verbose or --quiet).
inline void print_summary(const Arguments& a, const Summary& s)
{
  if (verbosity(a) == Verbosity::summary && !a.has("json")) std::cout << s.to_text() << std::flush;
}

} // namespace cli
} // namespace mrepair

#endif // MREPAIR_TOOLS_SUMMARY_H
