// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// The file of a gap closing sequence (`Gap_sequence_file`,
// gap_closing_sequence.h): its writer and parser, and what the sequence
// records with: the order-independent hashes of the fingerprints and the
// point map that keeps each contraction's position.
#ifndef MREPAIR_INTERNAL_CLOSE_GAPS_SEQUENCE_FILE_H
#define MREPAIR_INTERNAL_CLOSE_GAPS_SEQUENCE_FILE_H

#include <mrepair/status.h>

#include <boost/property_map/property_map.hpp>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <istream>
#include <ostream>
#include <sstream>
#include <string>
#include <vector>

namespace mrepair {

inline std::uint64_t Gap_sequence_file::checksum(const std::string& s)
{
  std::uint64_t h = 1469598103934665603ull;
  for (unsigned char ch : s) {
    h ^= ch;
    h *= 1099511628211ull;
  }
  return h;
}

inline bool Gap_sequence_file::write(std::ostream& out) const
{
  std::string s;
  char buf[160];
  auto line = [&](const char* fmt, auto... args) {
    std::snprintf(buf, sizeof buf, fmt, args...);
    s += buf;
  };
  line("mrepair-gap-sequence %d\n", format_version);
  line("input %zu %zu %016llx\n", input_vertices, input_faces, (unsigned long long)input_fingerprint);
  line("region %016llx\n", (unsigned long long)region_fingerprint);
  line("tolerance %.17g\n", tolerance);
  line("lambda %.17g\n", lambda);
  line("snap %.17g\n", snap);
  line("contractions %zu\n", contractions.size());
  for (const Gap_contraction_record& c : contractions)
    line("c %.17g %.17g %.17g %.17g\n", c.distance, c.position[0], c.position[1], c.position[2]);
  line("end %016llx\n", (unsigned long long)checksum(s));
  out << s;
  return bool(out);
}

inline Status Gap_sequence_file::read(std::istream& in, std::string& error)
{
  std::ostringstream all;
  all << in.rdbuf();
  if (in.bad()) {
    error = "cannot read the sequence";
    return Status::io_error;
  }
  const std::string text = all.str();
  std::size_t at = 0, lineno = 0;
  std::string ln;
  auto next_line = [&]() {
    if (at >= text.size()) return false;
    std::size_t e = text.find('\n', at);
    if (e == std::string::npos) return false;  // a last line without newline: truncated
    ln.assign(text, at, e - at);
    at = e + 1;
    ++lineno;
    return true;
  };
  auto fail = [&](const std::string& what) {
    error = "line " + std::to_string(lineno) + ": " + what;
    return Status::parse_error;
  };
  // fields of the current line after the keyword
  std::vector<std::string> f;
  auto expect = [&](const char* keyword, std::size_t n) {
    if (!next_line()) return false;
    f.clear();
    std::istringstream ss(ln);
    std::string w;
    while (ss >> w) f.push_back(w);
    return !f.empty() && f[0] == keyword && f.size() == n + 1;
  };
  auto num = [](const std::string& w, double& v) {
    char* e = nullptr;
    v = std::strtod(w.c_str(), &e);
    return e != w.c_str() && *e == '\0' && std::isfinite(v);
  };
  auto count = [](const std::string& w, std::size_t& v) {
    if (w.empty() || w.size() > 18 || w.find_first_not_of("0123456789") != std::string::npos)
      return false;
    v = std::size_t(std::strtoull(w.c_str(), nullptr, 10));
    return true;
  };
  auto hex = [](const std::string& w, std::uint64_t& v) {
    if (w.size() != 16 || w.find_first_not_of("0123456789abcdef") != std::string::npos) return false;
    v = std::strtoull(w.c_str(), nullptr, 16);
    return true;
  };
  if (!next_line() || ln.compare(0, 21, "mrepair-gap-sequence ") != 0)
    return fail("not a gap sequence file (no 'mrepair-gap-sequence' header)");
  if (ln != "mrepair-gap-sequence " + std::to_string(format_version))
    return fail("unsupported version '" + ln.substr(21) + "' (this build reads version " +
                std::to_string(format_version) + ")");
  // the last line: the checksum of everything before it (checked before the content)
  const std::size_t body = text.size() >= 2 ? text.rfind('\n', text.size() - 2) + 1 : 0;
  std::uint64_t sum = 0;
  {
    const std::string tail = text.substr(body);
    if (text.back() != '\n' || tail.compare(0, 4, "end ") != 0 || !hex(tail.substr(4, tail.size() - 5), sum)) {
      error = "the file is truncated (no 'end <checksum>' line at its end)";
      return Status::parse_error;
    }
    if (sum != checksum(text.substr(0, body))) {
      error = "checksum mismatch: the file is corrupt";
      return Status::parse_error;
    }
  }
  if (!expect("input", 3) || !count(f[1], input_vertices) || !count(f[2], input_faces) ||
      !hex(f[3], input_fingerprint))
    return fail("expected 'input <vertices> <faces> <fingerprint>'");
  if (!expect("region", 1) || !hex(f[1], region_fingerprint))
    return fail("expected 'region <fingerprint>'");
  if (!expect("tolerance", 1) || !num(f[1], tolerance) || tolerance < 0)
    return fail("expected 'tolerance <finite distance >= 0>'");
  if (!expect("lambda", 1) || !num(f[1], lambda) || lambda < 0 || lambda > 1)
    return fail("expected 'lambda <number in [0,1]>'");
  if (!expect("snap", 1) || !num(f[1], snap)) return fail("expected 'snap <number>'");
  std::size_t n = 0;
  if (!expect("contractions", 1) || !count(f[1], n)) return fail("expected 'contractions <count>'");
  // every contraction line has at least 10 bytes: a count beyond that is corrupt
  if (n > text.size() / 10) return fail("contraction count " + f[1] + " exceeds the file");
  contractions.clear();
  contractions.reserve(n);
  double last = 0;
  for (std::size_t i = 0; i < n; ++i) {
    Gap_contraction_record c;
    if (!expect("c", 4) || !num(f[1], c.distance) || !num(f[2], c.position[0]) ||
        !num(f[3], c.position[1]) || !num(f[4], c.position[2]))
      return fail("expected contraction " + std::to_string(i + 1) + " of " + std::to_string(n) +
                  " as 'c <distance> <x> <y> <z>'" + (at >= text.size() ? " (file truncated)" : ""));
    if (c.distance < last || c.distance > tolerance)
      return fail("contraction distances must increase and stay within the tolerance");
    last = c.distance;
    contractions.push_back(c);
  }
  if (at != body) return fail("unexpected data after the contractions");
  return Status::ok;
}

namespace internal {

// 64-bit mix (splitmix64 finaliser)
inline std::uint64_t gap_mix(std::uint64_t x)
{
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
inline std::uint64_t gap_hash_point(double x, double y, double z)
{
  auto bits = [](double d) {
    if (d == 0) d = 0;  // -0 and +0 alike
    std::uint64_t b;
    std::memcpy(&b, &d, sizeof b);
    return b;
  };
  return gap_mix(bits(x) ^ gap_mix(bits(y) ^ gap_mix(bits(z))));
}

// The vertex point map the sequence hands its worker: it forwards to `base`
// and keeps the last position written. The last write of a contraction is
// the position of the contracted vertex.
template <class VertexPointMap>
struct Gap_recording_point_map
{
  using key_type = typename boost::property_traits<VertexPointMap>::key_type;
  using value_type = typename boost::property_traits<VertexPointMap>::value_type;
  using reference = typename boost::property_traits<VertexPointMap>::reference;
  using category = boost::read_write_property_map_tag;

  VertexPointMap base;
  value_type* last = nullptr;

  friend reference get(const Gap_recording_point_map& m, const key_type& k) { return get(m.base, k); }
  friend void put(const Gap_recording_point_map& m, const key_type& k, const value_type& p)
  {
    put(m.base, k, p);
    *m.last = p;
  }
};

} // namespace internal

}  // namespace mrepair

#endif  // MREPAIR_INTERNAL_CLOSE_GAPS_SEQUENCE_FILE_H
