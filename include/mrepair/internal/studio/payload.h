// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_STUDIO_PAYLOAD_H
#define MREPAIR_INTERNAL_STUDIO_PAYLOAD_H

// The JSON of the HTML report's payload (doc/studio.md): base64 arrays of
// float32 / uint32 little-endian numbers, the defect overlay and the mesh
// preview as JSON, the template lookup, and the placeholder replacement.

#include <mrepair/internal/studio/overlay.h>
#include <mrepair/report.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace mrepair {
namespace internal {

// base64 (RFC 4648, with padding) of `n` bytes
inline void append_base64(std::string& out, const unsigned char* data, std::size_t n)
{
  static const char* abc = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  out.reserve(out.size() + 4 * ((n + 2) / 3));
  std::size_t i = 0;
  for (; i + 2 < n; i += 3) {
    const std::uint32_t x = (std::uint32_t(data[i]) << 16) | (std::uint32_t(data[i + 1]) << 8) | data[i + 2];
    out += abc[x >> 18];
    out += abc[(x >> 12) & 63];
    out += abc[(x >> 6) & 63];
    out += abc[x & 63];
  }
  if (i < n) {
    std::uint32_t x = std::uint32_t(data[i]) << 16;
    if (i + 1 < n) x |= std::uint32_t(data[i + 1]) << 8;
    out += abc[x >> 18];
    out += abc[(x >> 12) & 63];
    out += i + 1 < n ? abc[(x >> 6) & 63] : '=';
    out += '=';
  }
}

// base64 of 32-bit values (float or uint32) as little-endian bytes
template <typename T>
std::string base64_le32(const std::vector<T>& values)
{
  static_assert(sizeof(T) == 4, "32-bit values");
  std::vector<unsigned char> bytes(4 * values.size());
  for (std::size_t i = 0; i < values.size(); ++i) {
    std::uint32_t u;
    std::memcpy(&u, &values[i], 4);
    for (int b = 0; b < 4; ++b) bytes[4 * i + b] = static_cast<unsigned char>(u >> (8 * b));
  }
  std::string out;
  append_base64(out, bytes.data(), bytes.size());
  return out;
}

// a JSON string literal; '<' is written \u003c so that the JSON can sit in a
// <script> element
inline std::string json_string(const std::string& s) { return "\"" + json_escape(s, true) + "\""; }

inline std::string json_number(double x)
{
  if (!std::isfinite(x)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.9g", x);
  return buf;
}

// the geometry form of the payload contract
inline std::string overlay_json(const Defect_overlay& o)
{
  std::string out = "{\"kinds\": {";
  bool first_kind = true;
  for (const Overlay_kind& k : o.kinds) {
    out += first_kind ? "\n" : ",\n";
    first_kind = false;
    out += "  " + json_string(k.key) + ": {\"count\": " + std::to_string(k.count) +
           ", \"label\": " + json_string(k.label) + ", \"color\": " + json_string(k.color);
    out += ", \"points\": \"" + base64_le32(k.points) + "\"";
    out += ", \"segments\": \"" + base64_le32(k.segments) + "\"";
    out += ", \"triangles\": \"" + base64_le32(k.triangles) + "\"";
    if (k.has_first)
      out += ", \"first\": [" + json_number(k.first[0]) + ", " + json_number(k.first[1]) + ", " +
             json_number(k.first[2]) + "], \"first_radius\": " + json_number(k.first_radius);
    else
      out += ", \"first\": null, \"first_radius\": null";
    out += ", \"drawn\": " + std::to_string(k.drawn) + ", \"truncated\": " + (k.truncated ? "true" : "false") + "}";
  }
  return out + "\n}}";
}

// M of the payload contract
inline std::string preview_json(const Mesh_preview& p)
{
  return "{\"positions\": \"" + base64_le32(p.positions) + "\", \"indices\": \"" + base64_le32(p.indices) +
         "\", \"faces\": " + std::to_string(p.faces) + ", \"decimated\": " + (p.decimated ? "true" : "false") + "}";
}

// ---- the template -------------------------------------------------------------------

constexpr const char* studio_template_name = "report_template.html";
constexpr const char* studio_placeholder = "/*MREPAIR_PAYLOAD*/";

inline bool is_readable_file(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return static_cast<bool>(in);
}

// The report template: in $MREPAIR_STUDIO_ASSETS when it is set (and then
// only there: a folder named on purpose is not silently replaced), else in the
// first of `dirs` (in order; empty entries skipped) that holds it. Returns its
// path, or "" and in `tried` the folders looked at.
inline std::string find_studio_template(const std::vector<std::string>& dirs, std::string& tried)
{
  std::vector<std::string> candidates;
  const char* env = std::getenv("MREPAIR_STUDIO_ASSETS");
  if (env && *env) {
    candidates.push_back(env);
  } else {
    for (const std::string& d : dirs)
      if (!d.empty()) candidates.push_back(d);
  }
  tried.clear();
  for (const std::string& d : candidates) {
    const std::string p = d + "/" + studio_template_name;
    if (is_readable_file(p)) return p;
    tried += (tried.empty() ? "" : ", ") + d;
  }
  return "";
}

// Writes `out_path`: the template with its placeholder line replaced by
// `payload`. Returns "" or an error message.
inline std::string write_studio_html(const std::string& template_path, const std::string& out_path,
                                     const std::string& payload)
{
  std::ifstream in(template_path, std::ios::binary);
  if (!in) return template_path + ": cannot read the report template";
  std::ostringstream buf;
  buf << in.rdbuf();
  const std::string t = buf.str();
  const std::size_t at = t.find(studio_placeholder);
  if (at == std::string::npos || t.find(studio_placeholder, at + 1) != std::string::npos)
    return template_path + ": the template must hold the line " + studio_placeholder + " exactly once";
  // the whole line goes
  const std::size_t line_begin = t.rfind('\n', at) == std::string::npos ? 0 : t.rfind('\n', at) + 1;
  std::size_t line_end = t.find('\n', at);
  if (line_end == std::string::npos) line_end = t.size();
  std::ofstream out(out_path, std::ios::binary);
  if (!out) return out_path + ": cannot write";
  out.write(t.data(), static_cast<std::streamsize>(line_begin));
  out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
  out.write(t.data() + line_end, static_cast<std::streamsize>(t.size() - line_end));
  out.close();
  if (!out) return out_path + ": write failed";
  return "";
}

// '<' as \u003c everywhere in a JSON text (legal only inside its strings)
inline std::string script_safe_json(const std::string& json)
{
  std::string out;
  out.reserve(json.size());
  for (char c : json) {
    if (c == '<')
      out += "\\u003c";
    else
      out += c;
  }
  return out;
}

} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_STUDIO_PAYLOAD_H
