#include "progress_bar.h"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string_view>

#include <unistd.h>

namespace volspline::cli {

ReportSettings report_settings(bool quiet, bool verbose, bool stderr_is_terminal, const char* progress_env,
                               const char* delay_env) {
  ReportSettings s;
  if (quiet) {
    s.quiet = true;
    return s;
  }
  s.verbose = verbose;
  const std::string_view mode = progress_env ? progress_env : "auto";
  s.bar = mode == "always" || (mode != "never" && stderr_is_terminal);
  if (delay_env) {
    char* end = nullptr;
    const double delay = std::strtod(delay_env, &end);
    if (end != delay_env && *end == '\0' && delay >= 0 && std::isfinite(delay)) s.delay = delay;
  }
  return s;
}

ProgressReporter::ProgressReporter(std::ostream& err, ReportSettings settings, std::ostream* flush_first)
    : err_(err),
      flush_first_(flush_first),
      settings_(settings),
      progress_([this](const ProgressEvent& event) { on_event(event); }),
      start_(Clock::now()) {
  if (settings_.bar && !settings_.quiet) ticker_ = std::thread([this] { tick(); });
}

ProgressReporter::~ProgressReporter() { finish(); }

Progress* ProgressReporter::progress() {
  if (settings_.quiet || !(settings_.bar || settings_.verbose)) return nullptr;
  return &progress_;
}

void ProgressReporter::set_label(std::string label) {
  std::lock_guard lock(mutex_);
  label_ = std::move(label);
}

void ProgressReporter::warn(const std::string& message) {
  if (settings_.quiet) return;
  std::lock_guard lock(mutex_);
  erase();
  err_ << "volspline: warning: " << message << "\n" << std::flush;
}

int ProgressReporter::drawings() const {
  std::lock_guard lock(mutex_);
  return drawings_;
}

void ProgressReporter::on_event(const ProgressEvent& event) {
  const auto now = Clock::now();
  std::lock_guard lock(mutex_);
  switch (event.kind) {
    case ProgressEvent::Kind::PhaseBegin:
      phase_ = event.phase;
      unit_ = event.unit;
      in_phase_ = true;
      phase_start_ = now;
      break;
    case ProgressEvent::Kind::Advance:
      break;
    case ProgressEvent::Kind::PhaseEnd:
      in_phase_ = false;
      erase();
      if (settings_.verbose) {
        err_ << "volspline: " << (label_.empty() ? "" : label_ + " ") << event.phase << " " << std::fixed
             << std::setprecision(3) << event.seconds << " s\n"
             << std::defaultfloat << std::flush;
      }
      return;
  }
  draw_if_due(now);
}

void ProgressReporter::draw_if_due(Clock::time_point now) {
  if (!settings_.bar || settings_.quiet || finished_ || !in_phase_) return;
  if (std::chrono::duration<double>(now - start_).count() < settings_.delay) return;
  if (drawn_once_ && std::chrono::duration<double>(now - last_draw_).count() < settings_.interval) return;
  std::ostringstream line;
  std::string name = (label_.empty() ? "" : label_ + " ") + phase_;
  if (name.size() > 28) name = name.substr(0, 27) + "~";
  line << "volspline: " << std::left << std::setw(28) << name << std::right << " ";
  // The latest figures, also between events (a phase that only counts sends none).
  const double fraction = progress_.fraction(), done = progress_.done();
  if (fraction > 0) {
    constexpr int kWidth = 24;
    const int filled = static_cast<int>(std::lround(fraction * kWidth));
    line << "[" << std::string(static_cast<std::size_t>(filled), '#') << std::string(static_cast<std::size_t>(kWidth - filled), '.')
         << "] " << std::setw(3) << static_cast<int>(std::floor(fraction * 100)) << "% ";
  } else if (done > 0) {
    line << std::fixed << std::setprecision(0) << done << (unit_.empty() ? "" : " " + unit_) << " ";
  }
  line << std::fixed << std::setprecision(1) << std::chrono::duration<double>(now - phase_start_).count() << " s";
  const std::string text = line.str();
  if (flush_first_) flush_first_->flush();
  err_ << '\r' << text;
  if (shown_width_ > text.size()) err_ << std::string(shown_width_ - text.size(), ' ');
  err_ << std::flush;
  shown_width_ = std::max(shown_width_, text.size());
  last_draw_ = now;
  drawn_once_ = true;
  ++drawings_;
}

void ProgressReporter::erase() {
  if (shown_width_ == 0) return;
  err_ << '\r' << std::string(shown_width_, ' ') << '\r' << std::flush;
  shown_width_ = 0;
}

void ProgressReporter::tick() {
  std::unique_lock lock(mutex_);
  const auto period = std::chrono::duration_cast<Clock::duration>(std::chrono::duration<double>(settings_.interval));
  while (!stopping_) {
    wake_.wait_for(lock, period, [this] { return stopping_; });
    if (!stopping_) draw_if_due(Clock::now());
  }
}

void ProgressReporter::finish() {
  {
    std::lock_guard lock(mutex_);
    if (finished_) return;
    stopping_ = true;
  }
  wake_.notify_all();
  if (ticker_.joinable()) ticker_.join();
  std::lock_guard lock(mutex_);
  erase();
  finished_ = true;
  if (settings_.verbose) {
    err_ << "volspline: total " << std::fixed << std::setprecision(3)
         << std::chrono::duration<double>(Clock::now() - start_).count() << " s\n"
         << std::defaultfloat << std::flush;
  }
}

namespace {
std::unique_ptr<ProgressReporter>& reporter_instance() {
  static std::unique_ptr<ProgressReporter> instance;
  return instance;
}
}  // namespace

GlobalFlags& global_flags() {
  static GlobalFlags flags;
  return flags;
}

ProgressReporter& reporter() {
  auto& instance = reporter_instance();
  if (!instance) {
    const ReportSettings settings = report_settings(global_flags().quiet, global_flags().verbose, isatty(fileno(stderr)) == 1,
                                                    std::getenv("VOLSPLINE_PROGRESS"), std::getenv("VOLSPLINE_PROGRESS_DELAY"));
    instance = std::make_unique<ProgressReporter>(std::cerr, settings, &std::cout);
  }
  return *instance;
}

Progress* command_progress() { return reporter().progress(); }

void finish_reporting() {
  if (auto& instance = reporter_instance()) instance->finish();
}

}  // namespace volspline::cli
