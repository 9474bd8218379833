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
// Binary elements of fixed-size records are checked against the data once and
// decoded in parallel blocks (float or double x, y, z without a per-value
// type switch); face elements are walked once to check every list and note
// where each block of faces starts, then decoded in parallel. ASCII bodies
// are parsed in parallel chunks of lines when each element is on one line.

#include <mrepair/internal/io/common.h>
#include <mrepair/internal/io/text_chunks.h>

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

/// parses an ascii PLY body [b, e) starting on line `line`, one element per
/// line, in parallel chunks (text_chunks.h); false when an element is not on
/// one line or anything is wrong (nothing is kept then).
inline bool read_ply_ascii_in_chunks(const char* b, const char* e, std::size_t line,
                                     const std::vector<Ply_element>& elements, Raw_soup& soup,
                                     Ply_skipped_faces& skipped)
{
  std::vector<Text_chunk> chunks = split_text(b, e, line, '\0');
  // element k holds records [first[k], first[k + 1])
  std::vector<std::uint64_t> first(elements.size() + 1, 0);
  for (std::size_t k = 0; k < elements.size(); ++k) {
    first[k + 1] = first[k] + elements[k].count;
    if (first[k + 1] < first[k]) return false;
  }
  const std::uint64_t total = first.back();
  const std::uint64_t records = chunks.empty() ? 0 : chunks.back().first_record + chunks.back().records;
  if (records < total) return false;
  std::vector<Ply_skipped_faces> part_skipped(chunks.size());
  const bool ok = parse_chunks(chunks.size(), soup, [&](std::size_t k, Raw_soup& part) {
    const Text_chunk& ch = chunks[k];
    if (ch.first_record >= total) return true;
    std::size_t el = static_cast<std::size_t>(
        std::upper_bound(first.begin(), first.end(), ch.first_record) - first.begin() - 1);
    const std::uint64_t n = std::min<std::uint64_t>(ch.records, total - ch.first_record);
    part.reserve(n, n, 3 * n);
    bool bad = false;
    for_each_record(ch, '\0', [&](std::uint64_t r, const char* lb, const char* le, std::size_t ln) {
      if (r >= total) return false;  // after the last element: ignored
      while (r >= first[el + 1]) ++el;
      const Ply_element& elem = elements[el];
      bad = true;  // until the record is read
      Text_cursor c(lb, le, '\0');
      double xyz[3] = {0, 0, 0};
      bool polygon = false;
      const std::size_t first_corner = part.indices.size();
      for (const Ply_property& prop : elem.properties) {
        c.skip_blank();
        if (c.at_end()) return false;
        if (prop.is_list()) {
          std::int64_t m, idx;
          if (!c.parse_int(m) || m < 0) return false;
          for (std::int64_t i = 0; i < m; ++i) {
            c.skip_blank();
            if (prop.role == 3) {
              if (!c.parse_int(idx)) return false;
              part.add_index(idx);
            } else if (c.read_token().empty()) {
              return false;
            }
          }
          polygon = polygon || prop.role == 3;
        } else if (prop.role >= 0) {
          if (!c.parse_double(xyz[prop.role])) return false;
        } else {
          c.read_token();
        }
      }
      c.skip_blank();
      if (!c.at_end()) return false;  // more on the line: not one element per line
      if (elem.name == "vertex") part.add_point(xyz[0], xyz[1], xyz[2], ln);
      if (polygon) end_ply_face(part, first_corner, r - first[el], ln, part_skipped[k]);
      bad = false;
      return true;
    });
    return !bad;
  });
  if (!ok) return false;
  for (const Ply_skipped_faces& s : part_skipped) {
    if (s.count && skipped.count == 0) {
      skipped.first = s.first;
      skipped.first_line = s.first_line;
    }
    skipped.count += s.count;
  }
  return true;
}

/// one scalar of type `t` at `p` as double.
inline double ply_scalar(const char* p, Ply_type t, bool swap)
{
  Ply_binary in{p, p + 8, swap};
  return in.value(t);
}

/// decodes the x, y, z of `n` fixed-size records of `stride` bytes at `p`
/// into `soup` (in parallel); float and double coordinates without the
/// per-value type switch.
inline void read_ply_fixed_points(const char* p, std::size_t stride, std::size_t n,
                                  const Ply_element& e, bool swap, Raw_soup& soup)
{
  std::size_t off[3] = {0, 0, 0}, at = 0;
  Ply_type type[3] = {Ply_type::none, Ply_type::none, Ply_type::none};
  for (const Ply_property& prop : e.properties) {
    if (prop.role >= 0 && prop.role <= 2) {
      off[prop.role] = at;
      type[prop.role] = prop.type;
    }
    at += ply_size(prop.type);
  }
  const std::size_t first = soup.xyz.size();
  soup.xyz.resize(first + 3 * n);
  double* out = soup.xyz.data() + first;
  const bool same = type[0] == type[1] && type[1] == type[2];
  const std::size_t block = 16384;
  parallel_for_index((n + block - 1) / block, 1, [&](std::size_t k) {
    const std::size_t b = k * block, e = std::min(n, b + block);
    const char* r = p + b * stride;
    double* o = out + 3 * b;
    if (same && type[0] == Ply_type::f32 && !swap) {
      for (std::size_t i = b; i < e; ++i, r += stride, o += 3)
        for (int d = 0; d < 3; ++d) {
          float f;
          std::memcpy(&f, r + off[d], 4);
          o[d] = static_cast<double>(f);
        }
    } else if (same && type[0] == Ply_type::f64 && !swap) {
      for (std::size_t i = b; i < e; ++i, r += stride, o += 3)
        for (int d = 0; d < 3; ++d) std::memcpy(o + d, r + off[d], 8);
    } else {
      for (std::size_t i = b; i < e; ++i, r += stride, o += 3)
        for (int d = 0; d < 3; ++d) o[d] = ply_scalar(r + off[d], type[d], swap);
    }
  });
}

/// one integer of type `t` at `p`.
inline std::int64_t ply_integer(const char* p, Ply_type t, bool swap)
{
  Ply_binary in{p, p + 8, swap};
  return in.integer(t);
}

/// reads a binary face element (records with lists) in two passes: a
/// sequential walk that checks every record against the end of the data and
/// notes where each block of faces starts, then the index lists decoded
/// in parallel, block by block, straight into `soup`. Faces with fewer than
/// 3 vertices are skipped and counted.
template <typename Truncated>
bool read_ply_binary_faces(Ply_binary& in, const Ply_element& e, Raw_soup& soup,
                           Ply_skipped_faces& skipped, const Truncated& truncated, Error& err,
                           const std::string& path)
{
  struct Block
  {
    const char* p;
    std::uint64_t face;
    std::size_t corner, polygon;
  };
  const std::uint64_t block = 16384;
  std::vector<Block> blocks;
  std::size_t corners = 0, polygons = 0;
  const char* const end = in.end;
  const char* p = in.p;
  for (std::uint64_t i = 0; i < e.count; ++i) {
    if (i % block == 0) blocks.push_back(Block{p, i, corners, polygons});
    for (const Ply_property& prop : e.properties) {
      const std::size_t cs = ply_size(prop.count_type), sz = ply_size(prop.type);
      if (!prop.is_list()) {
        if (static_cast<std::size_t>(end - p) < sz) return truncated(i);
        p += sz;
        continue;
      }
      if (static_cast<std::size_t>(end - p) < cs) return truncated(i);
      const std::int64_t n = ply_integer(p, prop.count_type, in.swap);
      p += cs;
      if (n < 0)
        return err.set(Status::parse_error, path + ": element " + e.name + " " +
                                                std::to_string(i) + ": negative list count");
      if (static_cast<std::uint64_t>(n) > static_cast<std::uint64_t>(end - p) / sz)
        return truncated(i);
      p += static_cast<std::size_t>(n) * sz;
      if (prop.role == 3) {
        if (n >= 3) {
          corners += static_cast<std::size_t>(n);
          ++polygons;
        } else {
          skipped.add(i, 0);
        }
      }
    }
  }
  blocks.push_back(Block{p, e.count, corners, polygons});
  in.p = p;
  const std::size_t idx0 = soup.indices.size(), poly0 = soup.num_polygons();
  soup.indices.resize(idx0 + corners);
  soup.starts.resize(poly0 + polygons + 1);
  std::int64_t* const indices = soup.indices.data() + idx0;
  std::size_t* const starts = soup.starts.data() + poly0;
  parallel_for_index(blocks.size() - 1, 1, [&](std::size_t k) {
    const char* r = blocks[k].p;
    std::size_t corner = blocks[k].corner, polygon = blocks[k].polygon;
    for (std::uint64_t i = blocks[k].face; i < blocks[k + 1].face; ++i)
      for (const Ply_property& prop : e.properties) {
        const std::size_t sz = ply_size(prop.type);
        if (!prop.is_list()) {
          r += sz;
          continue;
        }
        const std::size_t n = static_cast<std::size_t>(ply_integer(r, prop.count_type, in.swap));
        r += ply_size(prop.count_type);
        if (prop.role == 3 && n >= 3) {
          if (prop.type == Ply_type::i32 && !in.swap) {
            for (std::size_t j = 0; j < n; ++j, r += 4) {
              std::int32_t v;
              std::memcpy(&v, r, 4);
              indices[corner++] = v;
            }
          } else {
            for (std::size_t j = 0; j < n; ++j, r += sz)
              indices[corner++] = ply_integer(r, prop.type, in.swap);
          }
          starts[++polygon] = idx0 + corner;
        } else {
          r += n * sz;
        }
      }
  });
  return true;
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
    Ply_skipped_faces chunk_skipped;
    if (read_ply_ascii_in_chunks(c.p, c.end, c.line, elements, soup, chunk_skipped)) {
      skipped = chunk_skipped;
      return true;
    }
    soup = Raw_soup();
    soup.has_lines = true;
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
    // fixed-size records: check the whole element at once, then decode in bulk
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
      if (is_vertex) read_ply_fixed_points(in.p, stride, static_cast<std::size_t>(e.count), e, in.swap, soup);
      in.p += stride * e.count;
      continue;
    }
    const bool faces = std::any_of(e.properties.begin(), e.properties.end(),
                                   [](const Ply_property& q) { return q.role == 3; });
    if (faces && !is_vertex) {
      if (!read_ply_binary_faces(in, e, soup, skipped, truncated, err, path)) return false;
      continue;
    }
    for (std::uint64_t i = 0; i < e.count; ++i) {
      double xyz[3] = {0, 0, 0};
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
          in.p += static_cast<std::size_t>(n) * sz;
        } else {
          if (!in.has(ply_size(prop.type))) return truncated(i);
          if (prop.role >= 0)
            xyz[prop.role] = in.value(prop.type);
          else
            in.p += ply_size(prop.type);
        }
      }
      if (is_vertex) soup.add_point(xyz[0], xyz[1], xyz[2]);
    }
  }
  return true;
}

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_READ_PLY_H
