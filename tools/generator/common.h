// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// Defect generator, shared pieces: a portable random source, small vector
// math, a triangle soup, a minimal JSON writer. Everything here is
// deterministic across machines: random numbers come from the raw bits of
// std::mt19937_64 (whose sequence the standard fixes), and sin/cos are our own
// polynomials so that no libm variant changes a single output bit.
#ifndef MREPAIR_TOOLS_GENERATOR_COMMON_H
#define MREPAIR_TOOLS_GENERATOR_COMMON_H

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace mrepair {
namespace generator {

using Vec3 = std::array<double, 3>;
using Tri = std::array<std::uint32_t, 3>;

inline Vec3 operator+(const Vec3& a, const Vec3& b) { return {a[0] + b[0], a[1] + b[1], a[2] + b[2]}; }
inline Vec3 operator-(const Vec3& a, const Vec3& b) { return {a[0] - b[0], a[1] - b[1], a[2] - b[2]}; }
inline Vec3 operator*(double s, const Vec3& a) { return {s * a[0], s * a[1], s * a[2]}; }
inline double dot(const Vec3& a, const Vec3& b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 cross(const Vec3& a, const Vec3& b)
{
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3& a) { return std::sqrt(dot(a, a)); }
inline Vec3 normalized(const Vec3& a)
{
  double n = norm(a);
  return n > 0 ? (1.0 / n) * a : Vec3{0, 0, 1};
}
/// angle between two vectors in degrees (0 when one is null).
inline double angle_deg(const Vec3& a, const Vec3& b)
{
  double na = norm(a), nb = norm(b);
  if (na == 0 || nb == 0) return 0;
  double c = std::max(-1.0, std::min(1.0, dot(a, b) / (na * nb)));
  return std::acos(c) * 57.29577951308232;  // only reported, never fed back into geometry
}

constexpr double pi = 3.14159265358979323846;

/// sin on [-pi/4, pi/4] and cos likewise, by Taylor polynomials (error < 1e-16).
inline double sin_kernel(double x)
{
  double x2 = x * x;
  return x * (1 + x2 * (-1.0 / 6 + x2 * (1.0 / 120 + x2 * (-1.0 / 5040 + x2 * (1.0 / 362880 +
              x2 * (-1.0 / 39916800 + x2 * (1.0 / 6227020800.0 + x2 * (-1.0 / 1307674368000.0))))))));
}
inline double cos_kernel(double x)
{
  double x2 = x * x;
  return 1 + x2 * (-0.5 + x2 * (1.0 / 24 + x2 * (-1.0 / 720 + x2 * (1.0 / 40320 +
             x2 * (-1.0 / 3628800 + x2 * (1.0 / 479001600.0 + x2 * (-1.0 / 87178291200.0)))))));
}
/// deterministic sine (portable bit for bit: only +, -, *, / and floor).
inline double dsin(double x)
{
  double q = std::floor(x / (pi / 2) + 0.5);
  double r = x - q * (pi / 2);
  long long k = static_cast<long long>(q) & 3;
  switch (k) {
    case 0: return sin_kernel(r);
    case 1: return cos_kernel(r);
    case 2: return -sin_kernel(r);
    default: return -cos_kernel(r);
  }
}
inline double dcos(double x) { return dsin(x + pi / 2); }
/// deterministic arctangent: two half-angle reductions, then a Taylor series (|x| <= 0.2).
inline double datan(double x)
{
  if (x < 0) return -datan(-x);
  if (x > 1) return pi / 2 - datan(1 / x);
  for (int i = 0; i < 2; ++i) x = x / (1 + std::sqrt(1 + x * x));  // atan(x) = 2 atan(x / (1 + sqrt(1 + x^2)))
  double x2 = x * x, term = x, sum = 0;
  for (int k = 0; k < 14; ++k) {
    sum += term / (2 * k + 1);
    term *= -x2;
  }
  return 4 * sum;
}
/// deterministic atan2 in (-pi, pi].
inline double datan2(double y, double x)
{
  if (x > 0) return datan(y / x);
  if (x < 0) return y >= 0 ? datan(y / x) + pi : datan(y / x) - pi;
  return y > 0 ? pi / 2 : (y < 0 ? -pi / 2 : 0);
}

/// seeded random source; uniform numbers from raw 64-bit draws.
class Random
{
public:
  explicit Random(std::uint64_t seed) : engine_(seed) {}
  std::uint64_t bits() { return engine_(); }
  /// uniform in [0, 1)
  double uniform() { return static_cast<double>(engine_() >> 11) * (1.0 / 9007199254740992.0); }
  double uniform(double lo, double hi) { return lo + (hi - lo) * uniform(); }
  /// uniform integer in [0, n), n > 0
  std::uint64_t below(std::uint64_t n)
  {
    return static_cast<std::uint64_t>((static_cast<unsigned __int128>(engine_()) * n) >> 64);
  }
  /// uniform integer in [lo, hi]
  long long between(long long lo, long long hi)
  {
    return lo + static_cast<long long>(below(static_cast<std::uint64_t>(hi - lo + 1)));
  }
  /// uniform direction
  Vec3 direction()
  {
    for (;;) {
      Vec3 v{uniform(-1, 1), uniform(-1, 1), uniform(-1, 1)};
      double n2 = dot(v, v);
      if (n2 > 1e-6 && n2 <= 1) return (1.0 / std::sqrt(n2)) * v;
    }
  }

private:
  std::mt19937_64 engine_;
};

/// triangle soup: the generator's working representation.
struct Tri_soup
{
  std::vector<Vec3> points;
  std::vector<Tri> faces;
};

/// minimal streaming JSON writer (objects, arrays, numbers, strings).
class Json
{
public:
  std::string str() const { return out_.str(); }
  Json& begin_object(const char* key = nullptr) { open(key, '{'); return *this; }
  Json& end_object() { close('}'); return *this; }
  Json& begin_array(const char* key = nullptr) { open(key, '['); return *this; }
  Json& end_array() { close(']'); return *this; }
  Json& value(const char* key, double v) { prefix(key); number(v); return *this; }
  Json& value(const char* key, long long v) { prefix(key); out_ << v; return *this; }
  Json& value(const char* key, std::size_t v) { prefix(key); out_ << v; return *this; }
  Json& value(const char* key, int v) { prefix(key); out_ << v; return *this; }
  Json& value(const char* key, std::uint32_t v) { prefix(key); out_ << v; return *this; }
  Json& value(const char* key, bool v) { prefix(key); out_ << (v ? "true" : "false"); return *this; }
  Json& value(const char* key, const std::string& v) { prefix(key); string(v); return *this; }
  Json& value(const char* key, const char* v) { return value(key, std::string(v)); }
  Json& value(const char* key, const Vec3& p)
  {
    prefix(key);
    out_ << '[';
    for (int i = 0; i < 3; ++i) { if (i) out_ << ", "; number(p[i]); }
    out_ << ']';
    return *this;
  }
  template <class Int>
  Json& ids(const char* key, const std::vector<Int>& v)
  {
    prefix(key);
    out_ << '[';
    for (std::size_t i = 0; i < v.size(); ++i) { if (i) out_ << ", "; out_ << v[i]; }
    out_ << ']';
    return *this;
  }

private:
  void number(double v)
  {
    if (!std::isfinite(v)) { out_ << "null"; return; }
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.12g", v);
    out_ << buf;
  }
  void string(const std::string& s)
  {
    out_ << '"';
    for (char c : s) {
      if (c == '"' || c == '\\') out_ << '\\' << c;
      else if (static_cast<unsigned char>(c) < 0x20) {
        char buf[8];
        std::snprintf(buf, sizeof buf, "\\u%04x", c);
        out_ << buf;
      } else out_ << c;
    }
    out_ << '"';
  }
  void prefix(const char* key)
  {
    if (!first_.empty()) {
      if (!first_.back()) out_ << ',';
      first_.back() = false;
      out_ << '\n' << std::string(2 * first_.size(), ' ');
    }
    if (key) { string(key); out_ << ": "; }
  }
  void open(const char* key, char c)
  {
    prefix(key);
    out_ << c;
    first_.push_back(true);
  }
  void close(char c)
  {
    bool empty = first_.back();
    first_.pop_back();
    if (!empty) out_ << '\n' << std::string(2 * first_.size(), ' ');
    out_ << c;
  }
  std::ostringstream out_;
  std::vector<bool> first_;
};

}  // namespace generator
}  // namespace mrepair

#endif  // MREPAIR_TOOLS_GENERATOR_COMMON_H
