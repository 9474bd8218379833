// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_INTERNAL_IO_COMMON_H
#define MREPAIR_INTERNAL_IO_COMMON_H

// Shared machinery of the readers and writers: whole-file buffers, a text
// cursor with hand-written number parsers (std::from_chars, no iostreams per
// token), the flat intermediate soup every reader fills, and error reporting.
//
// Memory is the cost of I/O: touching a fresh page costs more than parsing
// it (measured on the project's VM: 1.6 s to first-touch 100 MB, 0.02 s to
// write it again). So files are mapped rather than copied into a fresh
// buffer (POSIX; read whole elsewhere), and the large arrays of the flat soup
// come from `Big_allocator`, mapped directly and unmapped when freed. They
// are not advised to use transparent huge pages: on the project's VM a fresh
// 2 MB page costs more to fault in than its 512 small pages (10M-face binary
// PLY read: 0.66 s with small pages, 0.89-2.10 s advised; at 1M the advice
// saved 0.02 s).

#include <mrepair/status.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <string_view>
#include <system_error>
#include <type_traits>
#include <utility>
#include <vector>

#if defined(__unix__) || defined(__APPLE__)
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>
#define MREPAIR_IO_HAS_MMAP 1
#endif

namespace mrepair {
namespace internal {
namespace io {

/// status + one-line message of a failed parse; `ok()` while nothing failed.
struct Error
{
  Status status = Status::ok;
  std::string message;
  bool ok() const { return status == Status::ok; }
  bool set(Status s, std::string m)
  {
    status = s;
    message = std::move(m);
    return false;
  }
};

/// a file in memory: mapped read-only when the system allows, else read
/// whole (one allocation, no zero-fill). Not NUL-terminated: parsers stop at
/// `end()`.
struct File_buffer
{
  std::unique_ptr<char[]> data;
  const char* mapped = nullptr;
  std::size_t size = 0;
  File_buffer() = default;
  File_buffer(const File_buffer&) = delete;
  File_buffer& operator=(const File_buffer&) = delete;
  ~File_buffer()
  {
#ifdef MREPAIR_IO_HAS_MMAP
    if (mapped) munmap(const_cast<char*>(mapped), size);
#endif
  }
  const char* begin() const { return mapped ? mapped : data.get(); }
  const char* end() const { return begin() + size; }
};

/// reads `path` into `buf`; on failure fills `err` with an io_error.
inline bool read_file(const std::string& path, File_buffer& buf, Error& err)
{
  std::error_code ec;
  auto st = std::filesystem::status(path, ec);
  if (ec || !std::filesystem::exists(st))
    return err.set(Status::io_error, path + ": cannot open (no such file)");
  if (!std::filesystem::is_regular_file(st))
    return err.set(Status::io_error, path + ": cannot read (not a regular file)");
  std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec) return err.set(Status::io_error, path + ": cannot read size (" + ec.message() + ")");
#ifdef MREPAIR_IO_HAS_MMAP
  if (size > 0 && size < (std::numeric_limits<std::size_t>::max)() / 2) {
    const int fd = ::open(path.c_str(), O_RDONLY);
    if (fd >= 0) {
      void* m = ::mmap(nullptr, static_cast<std::size_t>(size), PROT_READ, MAP_PRIVATE, fd, 0);
      ::close(fd);
      if (m != MAP_FAILED) {
#ifdef MADV_WILLNEED
        ::madvise(m, static_cast<std::size_t>(size), MADV_WILLNEED);
#endif
        buf.mapped = static_cast<const char*>(m);
        buf.size = static_cast<std::size_t>(size);
        return true;
      }
    }
  }
#endif
  std::FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return err.set(Status::io_error, path + ": cannot open (" + std::strerror(errno) + ")");
  buf.size = static_cast<std::size_t>(size);
  buf.data.reset(new (std::nothrow) char[buf.size + 1]);
  if (!buf.data) {
    std::fclose(f);
    return err.set(Status::io_error, path + ": out of memory reading " + std::to_string(size) +
                                         " bytes");
  }
  std::size_t got = buf.size ? std::fread(buf.data.get(), 1, buf.size, f) : 0;
  bool bad = std::ferror(f) != 0;
  std::fclose(f);
  if (bad || got != buf.size)
    return err.set(Status::io_error, path + ": read error after " + std::to_string(got) + " of " +
                                         std::to_string(buf.size) + " bytes");
  buf.data[buf.size] = '\0';
  return true;
}

/// an allocator for the large arrays of I/O: blocks of 4 MB and more are
/// mapped directly (and returned to the system when freed); smaller ones
/// come from `operator new`.
template <typename T>
struct Big_allocator
{
  using value_type = T;
  static constexpr std::size_t big = std::size_t(4) << 20;
  Big_allocator() = default;
  template <typename U>
  Big_allocator(const Big_allocator<U>&) {}
  T* allocate(std::size_t n)
  {
    if (n > (std::numeric_limits<std::size_t>::max)() / sizeof(T)) throw std::bad_alloc();
    const std::size_t bytes = n * sizeof(T);
#if defined(MREPAIR_IO_HAS_MMAP) && defined(MAP_ANONYMOUS)
    if (bytes >= big) {
      void* m = ::mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (m == MAP_FAILED) throw std::bad_alloc();
      return static_cast<T*>(m);
    }
#endif
    return static_cast<T*>(::operator new(bytes));
  }
  void deallocate(T* p, std::size_t n)
  {
#if defined(MREPAIR_IO_HAS_MMAP) && defined(MAP_ANONYMOUS)
    if (n * sizeof(T) >= big) {
      ::munmap(p, n * sizeof(T));
      return;
    }
#endif
    ::operator delete(p);
  }
  /// `resize` leaves new elements default-initialized (not zeroed): every
  /// reader writes what it resizes for, and zeroing costs a pass over memory
  template <typename U>
  void construct(U* p) noexcept(std::is_nothrow_default_constructible<U>::value)
  {
    ::new (static_cast<void*>(p)) U;
  }
  template <typename U, typename... Args>
  void construct(U* p, Args&&... args)
  {
    ::new (static_cast<void*>(p)) U(std::forward<Args>(args)...);
  }
  template <typename U>
  bool operator==(const Big_allocator<U>&) const { return true; }
  template <typename U>
  bool operator!=(const Big_allocator<U>&) const { return false; }
};

template <typename T>
using Big_vector = std::vector<T, Big_allocator<T>>;

/// the flat soup every reader fills; `finish_soup` converts it to the
/// caller's point and polygon types. Indices are already 0-based and
/// resolved (OBJ relative indices), but not yet range-checked.
struct Raw_soup
{
  Big_vector<double> xyz = Big_vector<double>();                   // 3 per point
  Big_vector<std::int64_t> indices = Big_vector<std::int64_t>();    // all polygons, concatenated
  Big_vector<std::size_t> starts = Big_vector<std::size_t>(1, 0);   // polygon k = indices[starts[k], starts[k+1])
  Big_vector<std::uint32_t> polygon_line = Big_vector<std::uint32_t>(); // text formats: line of each polygon
  std::size_t first_non_finite_line = 0;   // text formats: 0 = none or unknown
  bool has_lines = false;

  std::size_t num_points() const { return xyz.size() / 3; }
  std::size_t num_polygons() const { return starts.size() - 1; }
  void add_point(double x, double y, double z, std::size_t line = 0)
  {
    if (first_non_finite_line == 0 && line != 0 &&
        !(std::isfinite(x) && std::isfinite(y) && std::isfinite(z)))
      first_non_finite_line = line;
    xyz.push_back(x);
    xyz.push_back(y);
    xyz.push_back(z);
  }
  void add_index(std::int64_t i) { indices.push_back(i); }
  void end_polygon(std::size_t line = 0)
  {
    starts.push_back(indices.size());
    if (has_lines) polygon_line.push_back(static_cast<std::uint32_t>(line));
  }
  void reserve(std::size_t points, std::size_t polygons, std::size_t corners)
  {
    xyz.reserve(3 * points);
    starts.reserve(polygons + 1);
    indices.reserve(corners);
    if (has_lines) polygon_line.reserve(polygons);
  }
};

/// caps a count announced by a header by what `bytes` bytes of data can hold
/// at `min_bytes` per item, so that absurd headers never cause huge reservations.
inline std::size_t capped(std::uint64_t announced, std::size_t bytes, std::size_t min_bytes)
{
  std::uint64_t cap = bytes / std::max<std::size_t>(min_bytes, 1) + 1;
  return static_cast<std::size_t>(std::min(announced, cap));
}

inline bool is_blank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\f' || c == '\v'; }
inline bool is_space(char c) { return is_blank(c) || c == '\n'; }

/// a cursor over text with line counting. `comment` starts a comment that
/// runs to the end of the line ('\0' for none).
class Text_cursor
{
public:
  const char* p;
  const char* end;
  std::size_t line = 1;
  char comment;

  Text_cursor(const char* b, const char* e, char comment_char = '#')
    : p(b), end(e), comment(comment_char)
  {}

  bool at_end() const { return p >= end; }

  /// skips spaces, newlines and comments.
  void skip_ws()
  {
    while (p < end) {
      char c = *p;
      if (c == '\n') {
        ++line;
        ++p;
      } else if (is_blank(c)) {
        ++p;
      } else if (c == comment && comment != '\0') {
        while (p < end && *p != '\n') ++p;
      } else {
        break;
      }
    }
  }
  /// skips spaces on the current line only.
  void skip_blank()
  {
    while (p < end && is_blank(*p)) ++p;
  }
  /// true when only blanks or a comment remain on the current line.
  bool at_eol()
  {
    skip_blank();
    return p >= end || *p == '\n' || (comment != '\0' && *p == comment);
  }
  /// moves past the next newline.
  void skip_line()
  {
    const void* nl = p < end ? std::memchr(p, '\n', static_cast<std::size_t>(end - p)) : nullptr;
    if (nl) {
      p = static_cast<const char*>(nl) + 1;
      ++line;
    } else {
      p = end;
    }
  }
  /// the next whitespace-delimited token on the current line (not consumed).
  std::string_view peek_token() const
  {
    const char* q = p;
    while (q < end && !is_space(*q)) ++q;
    return std::string_view(p, static_cast<std::size_t>(q - p));
  }
  std::string_view read_token()
  {
    std::string_view t = peek_token();
    p += t.size();
    return t;
  }
  /// the rest of the token at `p`, shortened for messages.
  std::string shown_token() const
  {
    std::string_view t = peek_token();
    if (t.empty()) return p >= end ? std::string("end of file") : std::string("end of line");
    std::string s(t.substr(0, 24));
    if (t.size() > 24) s += "...";
    return "'" + s + "'";
  }

  /// parses a double at `p` (after a possible '+'); the token must end at
  /// whitespace, '#', or (when `stop` != 0) at `stop`. Accepts nan / inf.
  bool parse_double(double& v, char stop = '\0')
  {
    const char* q = p;
    if (q < end && *q == '+') ++q;
    auto r = std::from_chars(q, end, v, std::chars_format::general);
    if (r.ec == std::errc::result_out_of_range) {
      // from_chars leaves v untouched on overflow/underflow; keep the sign.
      const char* e = r.ptr;
      bool neg = *q == '-';
      double mag = std::strtod(std::string(q, e).c_str(), nullptr);
      v = std::isfinite(mag) ? mag : (neg ? -HUGE_VAL : HUGE_VAL);
    } else if (r.ec != std::errc()) {
      return false;
    }
    if (r.ptr < end && !is_space(*r.ptr) && *r.ptr != comment && (stop == '\0' || *r.ptr != stop))
      return false;
    p = r.ptr;
    return true;
  }
  /// parses an integer token at `p` like `parse_double`.
  bool parse_int(std::int64_t& v, char stop = '\0')
  {
    const char* q = p;
    bool neg = false;
    if (q < end && (*q == '+' || *q == '-')) {
      neg = *q == '-';
      ++q;
    }
    const char* digits = q;
    std::uint64_t x = 0;
    while (q < end && static_cast<unsigned>(*q - '0') < 10u) {
      x = 10 * x + static_cast<unsigned>(*q - '0');
      ++q;
    }
    if (q == digits) return false;
    if (q - digits > 18) {  // may overflow: let from_chars decide
      const char* b = *p == '+' ? p + 1 : p;
      auto r = std::from_chars(b, end, v);
      if (r.ec != std::errc() || r.ptr != q) return false;
    } else {
      v = neg ? -static_cast<std::int64_t>(x) : static_cast<std::int64_t>(x);
    }
    if (q < end && !is_space(*q) && *q != comment && (stop == '\0' || *q != stop)) return false;
    p = q;
    return true;
  }
  /// skips whitespace and comments, then parses a double.
  bool next_double(double& v)
  {
    skip_ws();
    return parse_double(v);
  }
  bool next_int(std::int64_t& v)
  {
    skip_ws();
    return parse_int(v);
  }
};

/// lowercase copy of `s`.
inline std::string lower(std::string s)
{
  for (char& c : s)
    if (c >= 'A' && c <= 'Z') c = static_cast<char>(c - 'A' + 'a');
  return s;
}

/// file extension of `path` in lowercase, without the dot ("" when none).
inline std::string extension(const std::string& path)
{
  std::string name = std::filesystem::path(path).filename().string();
  auto dot = name.rfind('.');
  if (dot == std::string::npos || dot == 0) return std::string();
  return lower(name.substr(dot + 1));
}

// ---- binary scalars ---------------------------------------------------------

inline bool host_is_little_endian()
{
  const std::uint16_t one = 1;
  unsigned char b;
  std::memcpy(&b, &one, 1);
  return b == 1;
}

/// loads a `T` from unaligned memory, swapping bytes when `swap`.
template <typename T>
inline T load(const char* p, bool swap)
{
  static_assert(std::is_trivially_copyable<T>::value, "");
  unsigned char b[sizeof(T)];
  std::memcpy(b, p, sizeof(T));
  if (swap) std::reverse(b, b + sizeof(T));
  T v;
  std::memcpy(&v, b, sizeof(T));
  return v;
}

/// stores `v` into memory as little-endian.
template <typename T>
inline void store_le(char* p, T v)
{
  unsigned char b[sizeof(T)];
  std::memcpy(b, &v, sizeof(T));
  if (!host_is_little_endian()) std::reverse(b, b + sizeof(T));
  std::memcpy(p, b, sizeof(T));
}

// ---- output -----------------------------------------------------------------

/// buffered writer over a FILE*, with shortest round-trip double formatting.
class Out_file
{
  std::FILE* f_ = nullptr;
  std::string buf_;
  bool failed_ = false;

public:
  explicit Out_file(const std::string& path) : f_(std::fopen(path.c_str(), "wb"))
  {
    buf_.reserve(1 << 20);
  }
  ~Out_file()
  {
    if (f_) std::fclose(f_);
  }
  Out_file(const Out_file&) = delete;
  Out_file& operator=(const Out_file&) = delete;

  bool is_open() const { return f_ != nullptr; }
  void flush()
  {
    if (!f_ || buf_.empty()) return;
    if (std::fwrite(buf_.data(), 1, buf_.size(), f_) != buf_.size()) failed_ = true;
    buf_.clear();
  }
  void maybe_flush()
  {
    if (buf_.size() >= (1u << 20)) flush();
  }
  Out_file& put(std::string_view s)
  {
    buf_.append(s.data(), s.size());
    maybe_flush();
    return *this;
  }
  Out_file& put(char c)
  {
    buf_.push_back(c);
    return *this;
  }
  /// shortest text that parses back to exactly `v` ("nan", "inf" for non-finite).
  Out_file& put_double(double v)
  {
    char tmp[64];
    auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
    buf_.append(tmp, static_cast<std::size_t>(r.ptr - tmp));
    return *this;
  }
  Out_file& put_uint(std::uint64_t v)
  {
    char tmp[24];
    auto r = std::to_chars(tmp, tmp + sizeof tmp, v);
    buf_.append(tmp, static_cast<std::size_t>(r.ptr - tmp));
    return *this;
  }
  /// appends `n` bytes; large blocks go to the file directly.
  Out_file& put_bytes(const char* p, std::size_t n)
  {
    if (n >= (1u << 16)) {
      flush();
      if (f_ && n && std::fwrite(p, 1, n, f_) != n) failed_ = true;
      return *this;
    }
    buf_.append(p, n);
    maybe_flush();
    return *this;
  }
  /// flushes and closes; false when any write failed.
  bool close()
  {
    flush();
    bool ok = !failed_;
    if (f_ && std::fclose(f_) != 0) ok = false;
    f_ = nullptr;
    return ok;
  }
};

} // namespace io
} // namespace internal
} // namespace mrepair

#endif // MREPAIR_INTERNAL_IO_COMMON_H
