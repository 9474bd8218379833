// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
// A small JSON reader and writer for the `mrepair` program's own files: the
// reports `repair --report` writes and the manifest lines of `batch`. Numbers
// keep their text, so what is read is written back unchanged; objects keep
// their key order. Depth and size are bounded by the input; malformed text
// gives false, never a throw.
#ifndef MREPAIR_TOOLS_JSON_LITE_H
#define MREPAIR_TOOLS_JSON_LITE_H

#include <mrepair/report.h>

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

namespace mrepair {
namespace cli {

struct Json
{
  enum Kind { null_value, boolean, number, string, array, object };
  Kind kind = null_value;
  std::string text;  // number: its literal; string: the decoded value; boolean: "true"/"false"
  std::vector<std::pair<std::string, Json>> members;  // object, in order
  std::vector<Json> items;                            // array

  static Json make_string(const std::string& s)
  {
    Json j;
    j.kind = string;
    j.text = s;
    return j;
  }
  static Json make_number(const std::string& literal)
  {
    Json j;
    j.kind = number;
    j.text = literal;
    return j;
  }

  /// the member `key` of an object, or nullptr.
  const Json* find(const std::string& key) const
  {
    if (kind != object) return nullptr;
    for (const auto& m : members)
      if (m.first == key) return &m.second;
    return nullptr;
  }
  /// `find` along a path of keys.
  const Json* find(std::initializer_list<const char*> path) const
  {
    const Json* j = this;
    for (const char* k : path) {
      j = j->find(k);
      if (!j) return nullptr;
    }
    return j;
  }

  static std::string quote(const std::string& s) { return "\"" + json_escape(s) + "\""; }

  /// one line, `{"a": 1, "b": [2, 3]}`.
  std::string dump() const
  {
    switch (kind) {
      case null_value: return "null";
      case boolean:
      case number: return text;
      case string: return quote(text);
      case array: {
        std::string out = "[";
        for (std::size_t i = 0; i < items.size(); ++i) out += (i ? ", " : "") + items[i].dump();
        return out + "]";
      }
      case object: {
        std::string out = "{";
        for (std::size_t i = 0; i < members.size(); ++i)
          out += (i ? ", " : "") + quote(members[i].first) + ": " + members[i].second.dump();
        return out + "}";
      }
    }
    return "null";
  }
};

namespace internal_json {

class Parser
{
  const std::string& s_;
  std::size_t i_ = 0;

  void skip_space()
  {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t')) ++i_;
  }
  bool literal(const char* word)
  {
    std::size_t n = std::char_traits<char>::length(word);
    if (s_.compare(i_, n, word) != 0) return false;
    i_ += n;
    return true;
  }
  static void put_utf8(unsigned cp, std::string& out)
  {
    if (cp < 0x80) {
      out += static_cast<char>(cp);
    } else if (cp < 0x800) {
      out += static_cast<char>(0xC0 | (cp >> 6));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else if (cp < 0x10000) {
      out += static_cast<char>(0xE0 | (cp >> 12));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    } else {
      out += static_cast<char>(0xF0 | (cp >> 18));
      out += static_cast<char>(0x80 | ((cp >> 12) & 0x3F));
      out += static_cast<char>(0x80 | ((cp >> 6) & 0x3F));
      out += static_cast<char>(0x80 | (cp & 0x3F));
    }
  }
  bool hex4(unsigned& v)
  {
    if (i_ + 4 > s_.size()) return false;
    v = 0;
    for (int k = 0; k < 4; ++k) {
      char c = s_[i_++];
      v <<= 4;
      if (c >= '0' && c <= '9') v |= unsigned(c - '0');
      else if (c >= 'a' && c <= 'f') v |= unsigned(c - 'a' + 10);
      else if (c >= 'A' && c <= 'F') v |= unsigned(c - 'A' + 10);
      else return false;
    }
    return true;
  }
  bool string_value(std::string& out)
  {
    if (i_ >= s_.size() || s_[i_] != '"') return false;
    ++i_;
    while (i_ < s_.size()) {
      char c = s_[i_++];
      if (c == '"') return true;
      if (static_cast<unsigned char>(c) < 0x20) return false;
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= s_.size()) return false;
      char e = s_[i_++];
      switch (e) {
        case '"': out += '"'; break;
        case '\\': out += '\\'; break;
        case '/': out += '/'; break;
        case 'b': out += '\b'; break;
        case 'f': out += '\f'; break;
        case 'n': out += '\n'; break;
        case 'r': out += '\r'; break;
        case 't': out += '\t'; break;
        case 'u': {
          unsigned cp;
          if (!hex4(cp)) return false;
          if (cp >= 0xD800 && cp < 0xDC00 && s_.compare(i_, 2, "\\u") == 0) {
            i_ += 2;
            unsigned lo;
            if (!hex4(lo) || lo < 0xDC00 || lo >= 0xE000) return false;
            cp = 0x10000 + ((cp - 0xD800) << 10) + (lo - 0xDC00);
          }
          put_utf8(cp, out);
          break;
        }
        default: return false;
      }
    }
    return false;
  }
  bool number_value(std::string& out)
  {
    std::size_t b = i_;
    if (i_ < s_.size() && s_[i_] == '-') ++i_;
    std::size_t digits = i_;
    while (i_ < s_.size() && ((s_[i_] >= '0' && s_[i_] <= '9') || s_[i_] == '.' || s_[i_] == 'e' ||
                              s_[i_] == 'E' || s_[i_] == '+' || s_[i_] == '-'))
      ++i_;
    if (i_ == digits) return false;
    out = s_.substr(b, i_ - b);
    return true;
  }

public:
  explicit Parser(const std::string& s) : s_(s) {}

  bool value(Json& j, int depth)
  {
    if (depth > 64) return false;
    skip_space();
    if (i_ >= s_.size()) return false;
    char c = s_[i_];
    if (c == '{') {
      ++i_;
      j.kind = Json::object;
      skip_space();
      if (i_ < s_.size() && s_[i_] == '}') {
        ++i_;
        return true;
      }
      while (true) {
        skip_space();
        std::string key;
        if (!string_value(key)) return false;
        skip_space();
        if (i_ >= s_.size() || s_[i_] != ':') return false;
        ++i_;
        Json v;
        if (!value(v, depth + 1)) return false;
        j.members.emplace_back(std::move(key), std::move(v));
        skip_space();
        if (i_ < s_.size() && s_[i_] == ',') {
          ++i_;
          continue;
        }
        if (i_ < s_.size() && s_[i_] == '}') {
          ++i_;
          return true;
        }
        return false;
      }
    }
    if (c == '[') {
      ++i_;
      j.kind = Json::array;
      skip_space();
      if (i_ < s_.size() && s_[i_] == ']') {
        ++i_;
        return true;
      }
      while (true) {
        Json v;
        if (!value(v, depth + 1)) return false;
        j.items.push_back(std::move(v));
        skip_space();
        if (i_ < s_.size() && s_[i_] == ',') {
          ++i_;
          continue;
        }
        if (i_ < s_.size() && s_[i_] == ']') {
          ++i_;
          return true;
        }
        return false;
      }
    }
    if (c == '"') {
      j.kind = Json::string;
      return string_value(j.text);
    }
    if (literal("true")) {
      j.kind = Json::boolean;
      j.text = "true";
      return true;
    }
    if (literal("false")) {
      j.kind = Json::boolean;
      j.text = "false";
      return true;
    }
    if (literal("null")) {
      j.kind = Json::null_value;
      return true;
    }
    j.kind = Json::number;
    return number_value(j.text);
  }
  bool at_end()
  {
    skip_space();
    return i_ == s_.size();
  }
};

} // namespace internal_json

/// parses `text` (one JSON value, nothing after it) into `out`; false when malformed.
inline bool parse_json(const std::string& text, Json& out)
{
  internal_json::Parser p(text);
  out = Json();
  return p.value(out, 0) && p.at_end();
}

} // namespace cli
} // namespace mrepair

#endif // MREPAIR_TOOLS_JSON_LITE_H
