// Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
#ifndef MREPAIR_VISITORS_H
#define MREPAIR_VISITORS_H

#include <CGAL/Named_function_parameters.h>
#include <CGAL/boost/graph/named_params_helper.h>

#include <chrono>
#include <functional>
#include <type_traits>

/// \file visitors.h
/// Progress, cancellation and per-operation hooks shared by every algorithm.
/// Users derive from `Default_visitor`, override what they need and pass
/// `CGAL::parameters::visitor(std::ref(v))` (packs store copies: without
/// `std::ref` the state of `v` is lost).

namespace mrepair {

/// \ingroup mrepair_core
/// a visitor whose hooks all do nothing.
struct Default_visitor
{
  /// a named phase (for example "collapse", "relax") starts.
  void start_phase(const char* /*name*/) {}
  /// the phase started last ends.
  void end_phase(const char* /*name*/) {}
  /// fraction in [0,1] of the current phase done.
  void progress(double /*fraction*/) {}
  /// polled between operations; returning `true` stops the call cleanly with
  /// `Status::cancelled` and a valid mesh.
  bool stop_requested() { return false; }
};

namespace internal {

// Unwraps `std::reference_wrapper` so that algorithms call hooks on the user's object.
template <typename V> V& unwrap_visitor(V& v) { return v; }
template <typename V> V& unwrap_visitor(std::reference_wrapper<V>& v) { return v.get(); }
template <typename V> V& unwrap_visitor(const std::reference_wrapper<V>& v) { return v.get(); }

// The visitor type stored in a named-parameter pack, or `Default_visitor`.
template <typename NamedParameters>
struct Visitor_of
{
  using type = typename CGAL::internal_np::Lookup_named_param_def<
      CGAL::internal_np::visitor_t, NamedParameters, Default_visitor>::type;
};

// Holds the visitor of a pack (a copy, or the user's object through std::ref)
// and forwards every hook to it. Algorithms keep one of these by value.
template <typename NamedParameters>
class Visitor_handle
{
  using Stored = typename Visitor_of<NamedParameters>::type;
  Stored stored_;

public:
  explicit Visitor_handle(const NamedParameters& np)
    : stored_(CGAL::parameters::choose_parameter<Default_visitor>(
          CGAL::parameters::get_parameter(np, CGAL::internal_np::visitor)))
  {}
  auto& get() { return unwrap_visitor(stored_); }
  void start_phase(const char* n) { get().start_phase(n); }
  void end_phase(const char* n) { get().end_phase(n); }
  void progress(double f) { get().progress(f); }
  bool stop_requested() { return get().stop_requested(); }
};

// RAII phase marker: start on construction, end on scope exit.
template <typename Handle>
class Phase_scope
{
  Handle& h_;
  const char* name_;

public:
  Phase_scope(Handle& h, const char* name) : h_(h), name_(name) { h_.start_phase(name_); }
  ~Phase_scope() { h_.end_phase(name_); }
  Phase_scope(const Phase_scope&) = delete;
  Phase_scope& operator=(const Phase_scope&) = delete;
};

} // namespace internal

/// \ingroup mrepair_core
/// a visitor that asks every call to stop once `seconds` have passed since its
/// construction (or the last `restart()`), and forwards every hook to `Inner`
/// (which may be a `std::reference_wrapper` of the user's own visitor; its own
/// stop requests are honoured too). Long calls then return `Status::cancelled`
/// with a valid mesh; how far past the budget they run is the time between two
/// polls (a phase or a batch of operations, see each call's `visitor` parameter).
/// \code
/// mrepair::Time_budget_visitor<> budget(2.0);  // two seconds
/// auto r = mrepair::clean_scan_mesh(mesh, CGAL::parameters::visitor(std::ref(budget)));
/// if (r.status == mrepair::Status::cancelled) ...  // budget.expired() is true
/// \endcode
template <typename Inner = Default_visitor>
class Time_budget_visitor
{
  using Clock = std::chrono::steady_clock;
  Inner inner_;
  Clock::time_point start_;
  double budget_;
  bool expired_ = false;

  auto& in() { return internal::unwrap_visitor(inner_); }

public:
  /// \param seconds the budget; 0 or less stops at the first poll
  explicit Time_budget_visitor(double seconds, Inner inner = Inner())
    : inner_(inner), start_(Clock::now()), budget_(seconds)
  {}
  void start_phase(const char* name) { in().start_phase(name); }
  void end_phase(const char* name) { in().end_phase(name); }
  void progress(double fraction) { in().progress(fraction); }
  /// `true` once the budget is spent (and from then on) or when `Inner` asks to stop.
  bool stop_requested()
  {
    if (!expired_ && !(elapsed() < budget_)) expired_ = true;
    return expired_ || in().stop_requested();
  }
  /// `true` when a poll found the budget spent.
  bool expired() const { return expired_; }
  /// seconds since construction or the last `restart()`.
  double elapsed() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }
  /// starts a new budget of `seconds` now.
  void restart(double seconds)
  {
    budget_ = seconds;
    start_ = Clock::now();
    expired_ = false;
  }
  /// the wrapped visitor.
  Inner& inner() { return inner_; }
};

} // namespace mrepair

#endif // MREPAIR_VISITORS_H
