#pragma once
// Progress of long operations (boundary determination, Jacobian certification, blends): named
// phases, each with the fraction of it done, reported to whoever listens. The library never
// draws anything; the command line turns the reports into a progress bar and phase timings
// (docs/progress.md).
//
// An operation takes an optional `Progress*` (a field of its options, null by default) and
// reports through a ProgressPhase, which costs one null test per call when nobody listens.
#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <string_view>

namespace volspline {

struct ProgressEvent {
  enum class Kind {
    /// A phase began; fraction is 0.
    PhaseBegin,
    /// The fraction done of the current phase grew.
    Advance,
    /// The phase ended; seconds is its duration.
    PhaseEnd,
  };
  Kind kind;
  /// The phase's name ("subdivision", "marching", ...), valid during the call only.
  std::string_view phase;
  /// Fraction of the phase done, in [0, 1], never decreasing within a phase; it stays 0 for a
  /// phase whose amount of work is unknown.
  double fraction;
  /// Seconds since the phase began.
  double seconds;
  /// Units counted by advance() in this phase so far (cells, vertices, ...).
  double done;
  /// What the units are ("cells"), as given to begin_phase; may be empty.
  std::string_view unit;
};

/// Collects the reports of one operation at a time and hands them to a listener.
///
/// Threads: begin_phase and end_phase come from the thread that runs the operation; advance
/// and set_fraction may come from any thread (a TBB loop), and are cheap: an atomic update,
/// and a call to the listener only when the fraction has grown by at least 1/1000 since the
/// last one. The listener is never called by two threads at once.
class Progress {
 public:
  using Listener = std::function<void(const ProgressEvent&)>;

  /// A progress that reports to nobody (calls are still counted: fraction() works). The
  /// listener must not begin or end phases.
  Progress() = default;
  explicit Progress(Listener listener);
  Progress(const Progress&) = delete;
  Progress& operator=(const Progress&) = delete;

  /// Ends the current phase if one is open and begins `name`, with `total` units of work (called
  /// `unit`, e.g. "cells") to be counted by advance(); total <= 0 means unknown: the fraction
  /// then comes from set_fraction or stays 0, while advance() still counts.
  void begin_phase(std::string_view name, double total = 0, std::string_view unit = {});
  /// `units` more units of the current phase are done. With an unknown total the listener hears
  /// of it only at the next other event; done() tells the count at any time.
  void advance(double units = 1);
  /// At least `fraction` of the current phase is done (smaller values than the last are ignored,
  /// so that the reported fraction never decreases).
  void set_fraction(double fraction);
  /// Ends the current phase (nothing if none is open).
  void end_phase();

  /// Fraction done of the current phase, in [0, 1].
  double fraction() const;
  /// Units counted by advance() in the current phase.
  double done() const;
  /// The current phase's name, empty outside phases.
  std::string phase() const;

 private:
  using Clock = std::chrono::steady_clock;
  void publish(double fraction);

  Listener listener_;
  // Guards phase_, open_, start_ and the calls to listener_; recursive so that a listener may
  // ask phase().
  mutable std::recursive_mutex mutex_;
  std::string phase_, unit_;
  bool open_ = false;
  Clock::time_point start_{};
  std::atomic<double> total_{0};
  std::atomic<double> done_{0};
  std::atomic<double> fraction_{0};
  // Thousandths of the phase last published: advance publishes only when it grows.
  std::atomic<int> published_{0};
};

/// One phase of an operation, ended when it goes out of scope (also by an exception). Every
/// call is a no-op when `progress` is null.
class ProgressPhase {
 public:
  ProgressPhase(Progress* progress, std::string_view name, double total = 0, std::string_view unit = {})
      : progress_(progress) {
    if (progress_) progress_->begin_phase(name, total, unit);
  }
  ~ProgressPhase() {
    if (progress_) progress_->end_phase();
  }
  ProgressPhase(const ProgressPhase&) = delete;
  ProgressPhase& operator=(const ProgressPhase&) = delete;

  void advance(double units = 1) const {
    if (progress_) progress_->advance(units);
  }
  void set_fraction(double fraction) const {
    if (progress_) progress_->set_fraction(fraction);
  }
  /// Whether anybody counts: lets a caller skip work done only to compute fractions.
  bool active() const { return progress_ != nullptr; }

 private:
  Progress* progress_;
};

}  // namespace volspline
