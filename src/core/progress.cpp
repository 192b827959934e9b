#include "volspline/core/progress.h"

#include <algorithm>
#include <cmath>

namespace volspline {

Progress::Progress(Listener listener) : listener_(std::move(listener)) {}

void Progress::begin_phase(std::string_view name, double total, std::string_view unit) {
  std::lock_guard lock(mutex_);
  end_phase();
  phase_ = name;
  unit_ = unit;
  open_ = true;
  start_ = Clock::now();
  total_ = total > 0 && std::isfinite(total) ? total : 0;
  done_ = 0;
  fraction_ = 0;
  published_ = 0;
  if (listener_) listener_({ProgressEvent::Kind::PhaseBegin, phase_, 0.0, 0.0, 0.0, unit_});
}

void Progress::advance(double units) {
  if (!(units > 0)) return;
  const double done = done_.fetch_add(units, std::memory_order_relaxed) + units;
  const double total = total_.load(std::memory_order_relaxed);
  if (total > 0) set_fraction(done / total);
}

void Progress::set_fraction(double fraction) {
  if (!(fraction > 0)) return;
  fraction = std::min(fraction, 1.0);
  double seen = fraction_.load(std::memory_order_relaxed);
  while (fraction > seen && !fraction_.compare_exchange_weak(seen, fraction, std::memory_order_relaxed)) {
  }
  if (fraction <= seen) return;
  // Only the thread that moves the published thousandths forward calls the listener.
  const int step = static_cast<int>(std::floor(fraction * 1000));
  int last = published_.load(std::memory_order_relaxed);
  while (step > last) {
    if (published_.compare_exchange_weak(last, step, std::memory_order_relaxed)) {
      publish(fraction);
      return;
    }
  }
}

void Progress::publish(double fraction) {
  if (!listener_) return;
  std::lock_guard lock(mutex_);
  if (!open_) return;
  // Another thread may have published a larger fraction meanwhile: report the largest.
  fraction = std::max(fraction, fraction_.load(std::memory_order_relaxed));
  listener_({ProgressEvent::Kind::Advance, phase_, fraction, std::chrono::duration<double>(Clock::now() - start_).count(),
             done_.load(std::memory_order_relaxed), unit_});
}

void Progress::end_phase() {
  std::lock_guard lock(mutex_);
  if (!open_) return;
  open_ = false;
  const double seconds = std::chrono::duration<double>(Clock::now() - start_).count();
  if (listener_) {
    listener_({ProgressEvent::Kind::PhaseEnd, phase_, fraction_.load(std::memory_order_relaxed), seconds,
               done_.load(std::memory_order_relaxed), unit_});
  }
  total_ = 0;
}

double Progress::fraction() const { return fraction_.load(std::memory_order_relaxed); }

double Progress::done() const { return done_.load(std::memory_order_relaxed); }

std::string Progress::phase() const {
  std::lock_guard lock(mutex_);
  return open_ ? phase_ : std::string();
}

}  // namespace volspline
