#include "volspline/core/progress.h"

#include <gtest/gtest.h>

#include <atomic>
#include <stdexcept>
#include <string>
#include <vector>

#include <tbb/parallel_for.h>

namespace volspline {
namespace {

struct Recorded {
  ProgressEvent::Kind kind;
  std::string phase;
  double fraction, seconds, done;
  std::string unit;
};

// Records every event; fails the test if two threads ever call it at once.
struct Recorder {
  std::vector<Recorded> events;
  std::atomic<int> inside{0};
  Progress::Listener listener() {
    return [this](const ProgressEvent& e) {
      EXPECT_EQ(inside.fetch_add(1), 0) << "listener called by two threads at once";
      events.push_back({e.kind, std::string(e.phase), e.fraction, e.seconds, e.done, std::string(e.unit)});
      inside.fetch_sub(1);
    };
  }
};

// Within each phase: begins first, ends last, fractions in [0, 1] never decreasing, seconds
// never decreasing. Returns the phase names in order.
std::vector<std::string> check_phases(const std::vector<Recorded>& events) {
  std::vector<std::string> names;
  bool open = false;
  double fraction = 0, seconds = 0;
  for (const Recorded& e : events) {
    if (e.kind == ProgressEvent::Kind::PhaseBegin) {
      EXPECT_FALSE(open) << e.phase << " began inside another phase";
      open = true;
      names.push_back(e.phase);
      EXPECT_EQ(e.fraction, 0.0);
      fraction = 0;
      seconds = 0;
      continue;
    }
    EXPECT_TRUE(open) << "event outside a phase";
    EXPECT_EQ(e.phase, names.back());
    EXPECT_GE(e.fraction, fraction) << e.phase;
    EXPECT_LE(e.fraction, 1.0) << e.phase;
    EXPECT_GE(e.seconds, seconds) << e.phase;
    fraction = e.fraction;
    seconds = e.seconds;
    if (e.kind == ProgressEvent::Kind::PhaseEnd) open = false;
  }
  EXPECT_FALSE(open) << "a phase was never ended";
  return names;
}

TEST(Progress, PhasesInOrderWithMonotoneFractions) {
  Recorder r;
  Progress progress(r.listener());
  {
    const ProgressPhase a(&progress, "first", 10, "items");
    for (int i = 0; i < 10; ++i) a.advance();
    EXPECT_DOUBLE_EQ(progress.fraction(), 1.0);
    EXPECT_EQ(progress.done(), 10.0);
    EXPECT_EQ(progress.phase(), "first");
  }
  EXPECT_EQ(progress.phase(), "");
  {
    const ProgressPhase b(&progress, "second");
    b.set_fraction(0.5);
    b.set_fraction(0.25);  // smaller: ignored
    EXPECT_DOUBLE_EQ(progress.fraction(), 0.5);
    b.set_fraction(7);  // clamped
    EXPECT_DOUBLE_EQ(progress.fraction(), 1.0);
  }
  EXPECT_EQ(check_phases(r.events), (std::vector<std::string>{"first", "second"}));
  // first: begin, ten advances (each a new thousandth), end with all ten counted
  ASSERT_EQ(r.events.size(), 1u + 10u + 1u + 1u + 2u + 1u);
  EXPECT_EQ(r.events[11].kind, ProgressEvent::Kind::PhaseEnd);
  EXPECT_EQ(r.events[11].done, 10.0);
  EXPECT_EQ(r.events[11].unit, "items");
  EXPECT_DOUBLE_EQ(r.events[11].fraction, 1.0);
  for (int i = 1; i <= 10; ++i) EXPECT_DOUBLE_EQ(r.events[static_cast<std::size_t>(i)].fraction, i / 10.0);
}

TEST(Progress, ListenerHearsAtMostAThousandAdvancesPerPhase) {
  Recorder r;
  Progress progress(r.listener());
  progress.begin_phase("many", 1e6);
  for (int i = 0; i < 1000000; ++i) progress.advance();
  progress.end_phase();
  check_phases(r.events);
  EXPECT_LE(r.events.size(), 1002u);
  EXPECT_GE(r.events.size(), 1000u);
  EXPECT_DOUBLE_EQ(r.events.back().fraction, 1.0);
}

TEST(Progress, UnknownTotalCountsWithoutFraction) {
  Recorder r;
  Progress progress(r.listener());
  progress.begin_phase("counting", 0, "cells");
  for (int i = 0; i < 500; ++i) progress.advance(2);
  EXPECT_EQ(progress.done(), 1000.0);
  EXPECT_EQ(progress.fraction(), 0.0);
  progress.end_phase();
  ASSERT_EQ(r.events.size(), 2u);  // begin and end only: counts are read, not pushed
  EXPECT_EQ(r.events[1].done, 1000.0);
}

TEST(Progress, ConcurrentAdvancesFromTbbCountEveryUnit) {
  Recorder r;
  Progress progress(r.listener());
  constexpr int n = 200000;
  {
    const ProgressPhase phase(&progress, "parallel", n);
    tbb::parallel_for(0, n, [&](int) { phase.advance(); });
    EXPECT_EQ(progress.done(), static_cast<double>(n));
    EXPECT_DOUBLE_EQ(progress.fraction(), 1.0);
  }
  check_phases(r.events);
  EXPECT_DOUBLE_EQ(r.events.back().fraction, 1.0);
}

TEST(Progress, BeginningAPhaseEndsTheOpenOneAndExceptionsEndPhases) {
  Recorder r;
  Progress progress(r.listener());
  progress.begin_phase("a");
  progress.begin_phase("b");
  try {
    const ProgressPhase c(&progress, "c");
    throw std::runtime_error("failed");
  } catch (const std::runtime_error&) {
  }
  EXPECT_EQ(check_phases(r.events), (std::vector<std::string>{"a", "b", "c"}));
  // Outside phases, advances are counted nowhere visible and reach nobody.
  const std::size_t before = r.events.size();
  progress.advance(5);
  progress.set_fraction(0.5);
  EXPECT_EQ(r.events.size(), before);
}

TEST(Progress, NullProgressAndNoListenerAreHarmless) {
  const ProgressPhase nobody(nullptr, "nothing", 10);
  nobody.advance();
  nobody.set_fraction(0.5);
  EXPECT_FALSE(nobody.active());
  Progress silent;
  const ProgressPhase phase(&silent, "quiet", 4);
  phase.advance(2);
  EXPECT_DOUBLE_EQ(silent.fraction(), 0.5);
}

}  // namespace
}  // namespace volspline
