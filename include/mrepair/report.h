// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_REPORT_H
#define MREPAIR_REPORT_H

#include <mrepair/status.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdint>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

/// \file report.h
/// An ordered tree of named values that every result struct fills through its
/// `to_report(Report&)` member, printed as an aligned text table or as JSON.
/// The CLI and the benchmark harness print results through it, so that one
/// struct yields both outputs with the same keys.

namespace mrepair {

/// \ingroup mrepair_core
/// `in` with JSON's string escapes (no quotes added). `script_safe` also
/// writes '<' as \u003c, so that the JSON can sit in an HTML <script> element.
/// The one JSON escaper of the library, the CLI and the HTML report.
inline std::string json_escape(const std::string& in, bool script_safe = false)
{
  std::string out;
  out.reserve(in.size());
  for (char c : in) {
    switch (c) {
      case '"': out += "\\\""; break;
      case '\\': out += "\\\\"; break;
      case '\n': out += "\\n"; break;
      case '\t': out += "\\t"; break;
      default:
        if (static_cast<unsigned char>(c) < 0x20 || (script_safe && c == '<')) {
          char buf[8];
          std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
          out += buf;
        } else
          out += c;
    }
  }
  return out;
}

/// \ingroup mrepair_core
/// ordered key/value tree rendered as text or JSON.
class Report
{
  struct Entry
  {
    std::string key;
    std::string text;     // value as text (JSON literal for numbers, bools, null)
    bool quoted = false;  // string value: needs quotes in JSON
    std::unique_ptr<Report> child;
  };
  std::vector<Entry> entries_;

  static std::string number(double v)
  {
    if (!std::isfinite(v)) return "null";
    std::ostringstream s;
    s << std::setprecision(10) << v;
    return s.str();
  }
  Entry& slot(const std::string& key)
  {
    for (Entry& e : entries_)
      if (e.key == key) return e;
    entries_.push_back(Entry{key, std::string(), false, nullptr});
    return entries_.back();
  }

public:
  Report() = default;
  Report(const Report& o) { *this = o; }
  Report& operator=(const Report& o)
  {
    if (this == &o) return *this;
    entries_.clear();
    for (const Entry& e : o.entries_)
      entries_.push_back(Entry{e.key, e.text, e.quoted,
                               e.child ? std::make_unique<Report>(*e.child) : nullptr});
    return *this;
  }
  Report(Report&&) = default;
  Report& operator=(Report&&) = default;

  /// sets `key` (replacing an earlier value of the same key, keeping its place).
  template <typename T>
  Report& add(const std::string& key, const T& value)
  {
    Entry& e = slot(key);
    e.child.reset();
    if constexpr (std::is_same_v<T, bool>) {
      e.text = value ? "true" : "false";
      e.quoted = false;
    } else if constexpr (std::is_same_v<T, Status>) {
      e.text = to_string(value);
      e.quoted = true;
    } else if constexpr (std::is_integral_v<T>) {
      e.text = std::to_string(value);
      e.quoted = false;
    } else if constexpr (std::is_floating_point_v<T>) {
      e.text = number(static_cast<double>(value));
      e.quoted = false;
    } else {
      e.text = std::string(value);
      e.quoted = true;
    }
    return *this;
  }

  /// returns the nested report `name`, created empty on first use.
  Report& section(const std::string& name)
  {
    Entry& e = slot(name);
    if (!e.child) e.child = std::make_unique<Report>();
    return *e.child;
  }

  /// returns the value of `key` as text, or an empty string (nested: "a.b").
  std::string get(const std::string& key) const
  {
    auto dot = key.find('.');
    for (const Entry& e : entries_) {
      if (dot != std::string::npos && e.key == key.substr(0, dot) && e.child)
        return e.child->get(key.substr(dot + 1));
      if (dot == std::string::npos && e.key == key) return e.text;
    }
    return std::string();
  }

  /// adds every entry of `other` after the entries of this report (an entry of
  /// the same key is replaced in its place), so that a result can hand over
  /// the sections it built.
  Report& append(const Report& other)
  {
    if (&other == this) return *this;
    for (const Entry& e : other.entries_) {
      Entry& mine = slot(e.key);
      mine.text = e.text;
      mine.quoted = e.quoted;
      mine.child = e.child ? std::make_unique<Report>(*e.child) : nullptr;
    }
    return *this;
  }

  bool empty() const { return entries_.empty(); }

  /// returns every leaf as (dotted key, value text), in order.
  std::vector<std::pair<std::string, std::string>> flatten(const std::string& prefix = "") const
  {
    std::vector<std::pair<std::string, std::string>> out;
    for (const Entry& e : entries_) {
      std::string k = prefix.empty() ? e.key : prefix + "." + e.key;
      if (e.child) {
        auto sub = e.child->flatten(k);
        out.insert(out.end(), sub.begin(), sub.end());
      } else
        out.emplace_back(k, e.text);
    }
    return out;
  }

  /// renders as JSON with two-space indentation.
  std::string to_json(int indent = 0) const
  {
    std::string pad(indent + 2, ' ');
    std::string out = "{";
    for (std::size_t i = 0; i < entries_.size(); ++i) {
      const Entry& e = entries_[i];
      out += (i ? ",\n" : "\n") + pad + "\"" + json_escape(e.key) + "\": ";
      if (e.child)
        out += e.child->to_json(indent + 2);
      else if (e.quoted)
        out += "\"" + json_escape(e.text) + "\"";
      else
        out += e.text;
    }
    out += entries_.empty() ? "}" : "\n" + std::string(indent, ' ') + "}";
    return out;
  }

  /// renders as an aligned two-column table; sections are indented.
  std::string to_text(int indent = 0) const
  {
    std::size_t width = 0;
    for (const Entry& e : entries_)
      if (!e.child) width = std::max(width, e.key.size());
    std::string out;
    for (const Entry& e : entries_) {
      if (e.child) {
        out += std::string(indent, ' ') + e.key + ":\n" + e.child->to_text(indent + 2);
      } else {
        out += std::string(indent, ' ') + e.key + std::string(width - e.key.size() + 2, ' ') +
               e.text + "\n";
      }
    }
    return out;
  }
};

/// returns the report of any result struct that has `to_report(Report&) const`.
template <typename Result>
Report make_report(const Result& r)
{
  Report rep;
  r.to_report(rep);
  return rep;
}

} // namespace mrepair

#endif // MREPAIR_REPORT_H
