// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_READ_PLY_H
#define MREPAIR_INTERNAL_IO_READ_PLY_H

// PLY reader: ascii, binary_little_endian and binary_big_endian. From element
// `vertex` it takes the scalar properties x, y, z (any numeric type); from
// element `face` the list property `vertex_indices` (or `vertex_index`) with
// any integer count type and any index type. Every other property and element
// is skipped by its type, so files with normals, colors, flags, edges or
// materials read fine. Faces with fewer than 3 vertices (list count 0, 1 or 2)
// are left out of the soup and counted in `Ply_skipped_faces`.

#include <mrepair/internal/io/common.h>

namespace mrepair {
namespace internal {
namespace io {

enum class Ply_type { none, i8, u8, i16, u16, i32, u32, f32, f64 };

inline Ply_type ply_type(std::string_view s)
{
  if (s == "char" || s == "int8") return Ply_type::i8;
  if (s == "uchar" || s == "uint8") return Ply_type::u8;
  if (s == "short" || s == "int16") return Ply_type::i16;
  if (s == "ushort" || s == "uint16") return Ply_type::u16;
  if (s == "int" || s == "int32") return Ply_type::i32;
  if (s == "uint" || s == "uint32") return Ply_type::u32;
  if (s == "float" || s == "float32") return Ply_type::f32;
  if (s == "double" || s == "float64") return Ply_type::f64;
  return Ply_type::none;
}

inline std::size_t ply_size(Ply_type t)
{
  switch (t) {
    case Ply_type::i8: case Ply_type::u8: return 1;
    case Ply_type::i16: case Ply_type::u16: return 2;
    case Ply_type::i32: case Ply_type::u32: case Ply_type::f32: return 4;
    case Ply_type::f64: return 8;
    default: return 0;
  }
}

struct Ply_property
{
  std::string name;
  Ply_type type = Ply_type::none;        // value type (list items for lists)
  Ply_type count_type = Ply_type::none;  // != none for lists
  int role = -1;                         // 0,1,2: x,y,z; 3: face indices; -1: skipped
  bool is_list() const { return count_type != Ply_type::none; }
};

struct Ply_element
{
  std::string name;
  std::uint64_t count = 0;
  std::vector<Ply_property> properties;
};

/// faces with fewer than 3 vertices that `read_ply` left out of the soup.
struct Ply_skipped_faces
{
  std::size_t count = 0;
  std::uint64_t first = 0;      ///< index of the first one in its face element
  std::size_t first_line = 0;   ///< ascii: its line (0 for binary)
  void add(std::uint64_t face, std::size_t line)
  {
    if (count++ == 0) {
      first = face;
      first_line = line;
    }
  }
};

/// binary values of one PLY file.
struct Ply_binary
{
  const char* p;
  const char* end;
  bool swap;

  bool has(std::size_t n) const { return static_cast<std::size_t>(end - p) >= n; }
  // reads one value of type `t` as double; the caller checked `has(ply_size(t))`.
  double value(Ply_type t)
  {
    double v = 0;
    switch (t) {
      case Ply_type::i8: v = static_cast<std::int8_t>(*p); break;
      case Ply_type::u8: v = static_cast<std::uint8_t>(*p); break;
      case Ply_type::i16: v = load<std::int16_t>(p, swap); break;
      case Ply_type::u16: v = load<std::uint16_t>(p, swap); break;
      case Ply_type::i32: v = load<std::int32_t>(p, swap); break;
      case Ply_type::u32: v = load<std::uint32_t>(p, swap); break;
      case Ply_type::f32: v = static_cast<double>(load<float>(p, swap)); break;
      case Ply_type::f64: v = load<double>(p, swap); break;
      default: break;
    }
    p += ply_size(t);
    return v;
  }
  std::int64_t integer(Ply_type t)
  {
    std::int64_t v = 0;
    switch (t) {
      case Ply_type::i8: v = static_cast<std::int8_t>(*p); break;
      case Ply_type::u8: v = static_cast<std::uint8_t>(*p); break;
      case Ply_type::i16: v = load<std::int16_t>(p, swap); break;
      case Ply_type::u16: v = load<std::uint16_t>(p, swap); break;
      case Ply_type::i32: v = load<std::int32_t>(p, swap); break;
      case Ply_type::u32: v = load<std::uint32_t>(p, swap); break;
      case Ply_type::f32: {
        float f = load<float>(p, swap);
        v = std::isfinite(f) && std::fabs(f) < 9e18f ? static_cast<std::int64_t>(f) : -1;
        break;
      }
      case Ply_type::f64: {
        double f = load<double>(p, swap);
        v = std::isfinite(f) && std::fabs(f) < 9e18 ? static_cast<std::int64_t>(f) : -1;
        break;
      }
      default: break;
    }
    p += ply_size(t);
    return v;
  }
};

/// ends the face whose corners were added since `first_corner`: a polygon
/// when it has at least 3, otherwise removed again and counted in `skipped`.
inline void end_ply_face(Raw_soup& soup, std::size_t first_corner, std::uint64_t face,
                         std::size_t line, Ply_skipped_faces& skipped)
{
  if (soup.indices.size() - first_corner >= 3) {
    soup.end_polygon(line);
  } else {
    soup.indices.resize(first_corner);
    skipped.add(face, line);
  }
}

inline bool read_ply(const File_buffer& buf, const std::string& path, Raw_soup& soup, Error& err,
                     bool& binary, Ply_skipped_faces* skipped_out = nullptr)
{
  Ply_skipped_faces skipped_local;
  Ply_skipped_faces& skipped = skipped_out ? *skipped_out : skipped_local;
  Text_cursor c(buf.begin(), buf.end(), '\0');
  auto fail_line = [&](Status s, const std::string& why) {
    return err.set(s, path + ":" + std::to_string(c.line) + ": " + why);
  };
  if (buf.size == 0) return err.set(Status::empty_input, path + ": empty file");
  if (c.read_token() != "ply") return fail_line(Status::parse_error, "not a PLY file (no 'ply' magic)");
  c.skip_line();

  enum { ascii, le, be } format = ascii;
  bool have_format = false;
  std::vector<Ply_element> elements;
  bool ended = false;
  while (!c.at_end()) {
    c.skip_blank();
    std::string_view kw = c.read_token();
    if (kw == "format") {
      c.skip_blank();
      std::string_view f = c.read_token();
      if (f == "ascii")
        format = ascii;
      else if (f == "binary_little_endian")
        format = le;
      else if (f == "binary_big_endian")
        format = be;
      else
        return fail_line(Status::unsupported_format, "unknown PLY format '" + std::string(f) + "'");
      have_format = true;
    } else if (kw == "element") {
      Ply_element e;
      c.skip_blank();
      e.name = std::string(c.read_token());
      std::int64_t n;
      c.skip_blank();
      if (e.name.empty() || !c.parse_int(n) || n < 0)
        return fail_line(Status::parse_error, "bad element declaration");
      e.count = static_cast<std::uint64_t>(n);
      elements.push_back(std::move(e));
    } else if (kw == "property") {
      if (elements.empty()) return fail_line(Status::parse_error, "property before any element");
      Ply_property prop;
      c.skip_blank();
      std::string_view t = c.read_token();
      if (t == "list") {
        c.skip_blank();
        prop.count_type = ply_type(c.read_token());
        c.skip_blank();
        prop.type = ply_type(c.read_token());
        if (prop.count_type == Ply_type::none || prop.type == Ply_type::none)
          return fail_line(Status::parse_error, "bad list property type");
        if (prop.count_type == Ply_type::f32 || prop.count_type == Ply_type::f64)
          return fail_line(Status::parse_error, "list count of floating-point type");
      } else {
        prop.type = ply_type(t);
        if (prop.type == Ply_type::none)
          return fail_line(Status::parse_error, "unknown property type '" + std::string(t) + "'");
      }
      c.skip_blank();
      prop.name = std::string(c.read_token());
      Ply_element& e = elements.back();
      if (e.name == "vertex" && !prop.is_list()) {
        if (prop.name == "x") prop.role = 0;
        if (prop.name == "y") prop.role = 1;
        if (prop.name == "z") prop.role = 2;
      }
      if (e.name == "face" && prop.is_list() &&
          (prop.name == "vertex_indices" || prop.name == "vertex_index") &&
          std::none_of(e.properties.begin(), e.properties.end(),
                       [](const Ply_property& q) { return q.role == 3; }))
        prop.role = 3;  // the first of them when a file has both
      e.properties.push_back(std::move(prop));
    } else if (kw == "end_header") {
      c.skip_line();
      ended = true;
      break;
    } else if (kw == "comment" || kw == "obj_info" || kw.empty()) {
      // nothing
    } else {
      return fail_line(Status::parse_error, "unknown header line '" + std::string(kw) + "'");
    }
    c.skip_line();
  }
  if (!ended) return fail_line(Status::parse_error, "header without end_header");
  if (!have_format) return fail_line(Status::parse_error, "header without format line");
  binary = format != ascii;

  const Ply_element* vertex_el = nullptr;
  for (const Ply_element& e : elements) {
    if (e.name == "vertex") {
      vertex_el = &e;
      int roles = 0;
      for (const Ply_property& p : e.properties)
        if (p.role >= 0 && p.role <= 2) roles |= 1 << p.role;
      if (roles != 7)
        return err.set(Status::parse_error, path + ": element vertex lacks x, y or z");
    }
    if (e.name == "face") {
      bool has = false;
      for (const Ply_property& p : e.properties) has = has || p.role == 3;
      if (!has && e.count > 0)
        return err.set(Status::parse_error, path + ": element face lacks vertex_indices");
    }
  }
  if (!vertex_el) return err.set(Status::empty_input, path + ": no vertex element");

  std::size_t rest = static_cast<std::size_t>(c.end - c.p);
  soup.has_lines = !binary;
  {
    std::uint64_t nf = 0;
    for (const Ply_element& e : elements)
      if (e.name == "face") nf += e.count;
    std::size_t min_v = binary ? 3 : 6, min_f = binary ? 4 : 8;
    soup.reserve(capped(vertex_el->count, rest, min_v), capped(nf, rest, min_f),
                 3 * capped(nf, rest, min_f));
  }

  if (!binary) {
    for (const Ply_element& e : elements) {
      const bool is_vertex = e.name == "vertex";
      for (std::uint64_t i = 0; i < e.count; ++i) {
        double xyz[3] = {0, 0, 0};
        std::size_t line = 0;
        bool polygon = false;
        const std::size_t first_corner = soup.indices.size();
        for (const Ply_property& prop : e.properties) {
          c.skip_ws();
          if (c.at_end())
            return fail_line(Status::parse_error, "file ends in element " + e.name + " " +
                                                      std::to_string(i) + " of " +
                                                      std::to_string(e.count));
          if (line == 0) line = c.line;
          if (prop.is_list()) {
            std::int64_t n;
            if (!c.parse_int(n) || n < 0 || n > static_cast<std::int64_t>(c.end - c.p))
              return fail_line(Status::parse_error, "element " + e.name + " " + std::to_string(i) +
                                                        ": bad list count " + c.shown_token());
            for (std::int64_t k = 0; k < n; ++k) {
              c.skip_ws();
              if (prop.role == 3) {
                std::int64_t idx;
                if (!c.parse_int(idx))
                  return fail_line(Status::parse_error, "face " + std::to_string(i) +
                                                            ": expected a vertex index, got " +
                                                            c.shown_token());
                soup.add_index(idx);
              } else {
                if (c.at_end() || c.read_token().empty())
                  return fail_line(Status::parse_error, "file ends in element " + e.name);
              }
            }
            if (prop.role == 3) polygon = true;
          } else if (prop.role >= 0) {
            if (!c.parse_double(xyz[prop.role]))
              return fail_line(Status::parse_error, "vertex " + std::to_string(i) +
                                                        ": expected a number, got " + c.shown_token());
          } else {
            c.read_token();
          }
        }
        if (is_vertex) soup.add_point(xyz[0], xyz[1], xyz[2], line);
        if (polygon) end_ply_face(soup, first_corner, i, line, skipped);
      }
    }
    return true;
  }

  Ply_binary in{c.p, c.end, (format == le) != host_is_little_endian()};
  for (std::size_t ei = 0; ei < elements.size(); ++ei) {
    const Ply_element& e = elements[ei];
    const bool is_vertex = e.name == "vertex";
    auto truncated = [&](std::uint64_t i) {
      return err.set(Status::parse_error, path + ": binary data ends in element " + e.name + " " +
                                              std::to_string(i) + " of " +
                                              std::to_string(e.count));
    };
    // fixed-size records: check the whole element at once, then read unchecked
    std::size_t stride = 0;
    bool fixed = true;
    for (const Ply_property& prop : e.properties) {
      if (prop.is_list()) fixed = false;
      stride += ply_size(prop.type);
    }
    if (fixed) {
      if (stride != 0 && e.count > static_cast<std::uint64_t>(in.end - in.p) / stride) {
        std::uint64_t complete = static_cast<std::uint64_t>(in.end - in.p) / stride;
        return truncated(complete);
      }
      if (!is_vertex) {
        in.p += stride * e.count;
        continue;
      }
      for (std::uint64_t i = 0; i < e.count; ++i) {
        double xyz[3] = {0, 0, 0};
        for (const Ply_property& prop : e.properties) {
          if (prop.role >= 0)
            xyz[prop.role] = in.value(prop.type);
          else
            in.p += ply_size(prop.type);
        }
        soup.add_point(xyz[0], xyz[1], xyz[2]);
      }
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      double xyz[3] = {0, 0, 0};
      bool polygon = false;
      const std::size_t first_corner = soup.indices.size();
      for (const Ply_property& prop : e.properties) {
        if (prop.is_list()) {
          if (!in.has(ply_size(prop.count_type))) return truncated(i);
          std::int64_t n = in.integer(prop.count_type);
          std::size_t sz = ply_size(prop.type);
          if (n < 0)
            return err.set(Status::parse_error, path + ": element " + e.name + " " +
                                                    std::to_string(i) + ": negative list count");
          if (static_cast<std::uint64_t>(n) > static_cast<std::uint64_t>(in.end - in.p) / sz)
            return truncated(i);
          if (prop.role == 3) {
            for (std::int64_t k = 0; k < n; ++k) soup.add_index(in.integer(prop.type));
            polygon = true;
          } else {
            in.p += static_cast<std::size_t>(n) * sz;
          }
        } else {
          if (!in.has(ply_size(prop.type))) return truncated(i);
          if (prop.role >= 0)
            xyz[prop.role] = in.value(prop.type);
          else
            in.p += ply_size(prop.type);
        }
      }
      if (is_vertex) soup.add_point(xyz[0], xyz[1], xyz[2]);
      if (polygon) end_ply_face(soup, first_corner, i, 0, skipped);
    }
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_READ_PLY_H
