// Soak: many jobs of random shape and size through the one-process run path (planner,
// encoder, sender, simulated machine in lockstep). Every job must complete: a hang shows as
// the sender's stall watchdog (kStalled), a lost link or a wrong count, never as a test that
// does not end. Soak.Quick runs in the default ctest set (8 jobs, up to 20 000
// segments); Soak.Long is `ctest -C soak -L soak_long` (hundreds of jobs, up to 60 000).
#include <gtest/gtest.h>

#include <chrono>   // steady_clock
#include <cmath>    // M_PI
#include <cstdlib>  // std::getenv
#include <random>   // std::mt19937

#include "host/lib/sim/sim_job.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

using test::line_curve;

// One closed chained contour of n LINE segments (a wavy ring), as a PCB outline is.
Drawing contour(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(0, 1);
  const double r = 20 + 60 * u(rng), wave = 0.3 + 2 * u(rng), phase = 6 * u(rng);
  const int waves = 3 + static_cast<int>(30 * u(rng));
  std::vector<Curve> curves;
  curves.reserve(static_cast<size_t>(n));
  auto at = [&](int i) {
    const double a = 2 * M_PI * (i % n) / n;
    const double rr = r + wave * std::sin(waves * a + phase);
    return Point2(140 + rr * std::cos(a), 100 + rr * std::sin(a));
  };
  for (int i = 0; i < n; ++i) {
    const Point2 p = at(i), q = at(i + 1);
    curves.push_back(line_curve(p.x(), p.y(), q.x(), q.y()));
  }
  return test::drawing_of(std::move(curves));
}

// n short separate lines scattered over the area (n pen lifts).
Drawing scatter(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> x(5, 280), y(5, 190), a(0, 2 * M_PI), len(0.2, 6);
  std::vector<Curve> curves;
  for (int i = 0; i < n; ++i) {
    const double x0 = x(rng), y0 = y(rng), t = a(rng), l = len(rng);
    curves.push_back(line_curve(x0, y0, x0 + l * std::cos(t), y0 + l * std::sin(t)));
  }
  return test::drawing_of(std::move(curves));
}

// Runs `jobs` random jobs of up to max_segments segments; every one must complete.
void soak(int jobs, int max_segments, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(0, 1);
  int completed = 0;
  long segments = 0;
  const auto t0 = std::chrono::steady_clock::now();
  for (int j = 0; j < jobs; ++j) {
    // Sizes spread over decades (log-uniform), so small and large jobs both come up.
    const int n = std::max(3, static_cast<int>(std::exp(u(rng) * std::log(max_segments))));
    const bool lines = u(rng) < 0.3;
    const Drawing d = lines ? scatter(rng, std::min(n, 3000)) : contour(rng, n);
    PlanOptions po;
    po.feed_mm_per_s = 5 + 40 * u(rng);
    const JobPlan plan = plan_job(d, po);
    sim::SimJobOptions o;
    o.sender.status_interval = std::chrono::milliseconds(20 + static_cast<int>(200 * u(rng)));
    o.sender.stall_limit = std::chrono::milliseconds(10000);
    o.trace_step_mm = 0.1;
    const sim::SimJobResult r = sim::run_sim_job(plan, o);
    segments += static_cast<long>(d.curves.size());
    EXPECT_EQ(r.outcome, JobOutcome::kCompleted)
        << "job " << j << " (" << d.curves.size() << (lines ? " lines" : "-segment contour")
        << ", seed " << seed << "): " << r.message;
    if (r.outcome == JobOutcome::kCompleted) ++completed;
    // The path controller's error grows with the feed (the 10 um target is at 10 mm/s).
    const double limit_um = 15.0 * std::max(1.0, po.feed_mm_per_s / 10.0);
    EXPECT_LT(r.max_contour_error_um, limit_um)
        << "job " << j << " at " << po.feed_mm_per_s << " mm/s, seed " << seed;
  }
  const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::printf("soak: %d of %d jobs completed, %ld segments, %.1f s\n", completed, jobs, segments,
              s);
  EXPECT_EQ(completed, jobs);
}

int env_or(const char* name, int fallback) {
  const char* v = std::getenv(name);
  return v != nullptr && *v != '\0' ? std::atoi(v) : fallback;
}

TEST(Soak, QuickRandomJobsAllComplete) {
  soak(env_or("SOAK_JOBS", 8), env_or("SOAK_MAX_SEGMENTS", 20000),
       static_cast<uint32_t>(env_or("SOAK_SEED", 1)));
}

TEST(Soak, LongRandomJobsAllComplete) {
  soak(env_or("SOAK_JOBS", 200), env_or("SOAK_MAX_SEGMENTS", 60000),
       static_cast<uint32_t>(env_or("SOAK_SEED", 7)));
}

}  // namespace
}  // namespace host
