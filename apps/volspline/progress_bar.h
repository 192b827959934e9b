#pragma once
// What the command line says on stderr besides errors: a progress bar while long work runs,
// phase timings with -v, warnings; nothing but errors with -q (docs/progress.md).
//
// The bar is drawn only when stderr is a terminal (or VOLSPLINE_PROGRESS=always), only once the
// command has run for `delay` seconds (VOLSPLINE_PROGRESS_DELAY, default 1), at most 10 times a
// second, on one line rewritten with '\r', and it is erased when a phase ends and when the
// command finishes, so that nothing of it is left on the screen.
#include <chrono>
#include <condition_variable>
#include <iosfwd>
#include <memory>
#include <mutex>
#include <string>
#include <thread>

#include "volspline/core/progress.h"

namespace volspline::cli {

struct ReportSettings {
  /// -q: no bar, no timings, no warnings.
  bool quiet = false;
  /// -v: one line per finished phase with its duration.
  bool verbose = false;
  /// Draw the bar.
  bool bar = false;
  /// Seconds of work before the bar first appears.
  double delay = 1.0;
  /// Least seconds between two drawings of the bar.
  double interval = 0.1;
};

/// The settings for the global flags, the environment (VOLSPLINE_PROGRESS = auto, always or
/// never; VOLSPLINE_PROGRESS_DELAY = seconds; null when unset) and whether stderr is a terminal.
/// -q wins over everything; unknown environment values count as unset.
ReportSettings report_settings(bool quiet, bool verbose, bool stderr_is_terminal, const char* progress_env,
                               const char* delay_env);

/// Turns the reports of a Progress into a bar and timing lines on `err`.
class ProgressReporter {
 public:
  /// `flush_first` (std::cout for the command line) is flushed before the bar is drawn, so that
  /// what a command printed appears before the bar, not inside it.
  ProgressReporter(std::ostream& err, ReportSettings settings, std::ostream* flush_first = nullptr);
  /// As finish().
  ~ProgressReporter();
  ProgressReporter(const ProgressReporter&) = delete;
  ProgressReporter& operator=(const ProgressReporter&) = delete;

  /// What long operations report to (pass it in their options); null when nothing would be
  /// shown (-q, or no bar and no -v), so that they skip the reporting.
  Progress* progress();
  /// Put before phase names in the bar and the timings ("object 2", "3/30"); empty for none.
  void set_label(std::string label);
  /// A "volspline: warning: ..." line, unless quiet; the bar is erased first.
  void warn(const std::string& message);
  /// Erases the bar and stops drawing; with -v prints the total time. Idempotent.
  void finish();

  /// How many times the bar was drawn (for tests).
  int drawings() const;

 private:
  using Clock = std::chrono::steady_clock;
  void on_event(const ProgressEvent& event);
  void draw_if_due(Clock::time_point now);  // mutex_ held
  void erase();                             // mutex_ held
  void tick();

  std::ostream& err_;
  std::ostream* flush_first_;
  ReportSettings settings_;
  Progress progress_;
  mutable std::mutex mutex_;
  std::condition_variable wake_;
  bool stopping_ = false, finished_ = false;
  Clock::time_point start_;
  Clock::time_point last_draw_{};
  bool drawn_once_ = false;
  std::size_t shown_width_ = 0;  // characters of the bar on screen, 0 when erased
  int drawings_ = 0;
  std::string label_, phase_, unit_;
  bool in_phase_ = false;
  Clock::time_point phase_start_{};
  std::thread ticker_;
};

/// The flags the main app binds -q and -v to.
struct GlobalFlags {
  bool quiet = false;
  bool verbose = false;
};
GlobalFlags& global_flags();

/// The reporter of this run on std::cerr, made on first use from global_flags(), the
/// environment and isatty(stderr). Subcommands call it from their callbacks, after parsing.
ProgressReporter& reporter();
/// Shorthand for reporter().progress().
Progress* command_progress();
/// Finishes the reporter if one was made (main calls it before printing an error or exiting).
void finish_reporting();

}  // namespace volspline::cli
