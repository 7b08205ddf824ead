// How the sender follows a job: execution read from the status whatever number of frames
// ran between two statuses, and the watchdog that ends a job that stopped making progress.
#include <gtest/gtest.h>

#include <algorithm>  // std::min, std::copy
#include <cmath>      // std::cos

#include "host/lib/sim/sim_job.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

// A closed ring of n short lines: n #G commands in a row.
JobPlan ring_of_lines(int n) {
  std::vector<Curve> curves;
  for (int i = 0; i < n; ++i) {
    const double a = 2 * M_PI * i / n, b = 2 * M_PI * (i + 1) / n;
    curves.push_back(test::line_curve(20 + 3 * std::cos(a), 20 + 3 * std::sin(a),
                                      20 + 3 * std::cos(b), 20 + 3 * std::sin(b)));
  }
  return test::plan_of(test::drawing_of(std::move(curves)));
}

TEST(SenderProgress, CompletesWhenMoreThan127FramesRanBetweenTwoStatuses) {
  // One status at the start, the next a minute later when all ~200 commands have run: the
  // seq of the last executed frame is more than 127 ahead (read forwards from the previous
  // status it looked like an old frame, and the job never completed).
  const JobPlan plan = ring_of_lines(200);
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(60000);
  o.sender.silence_limit = std::chrono::milliseconds(120000);
  o.sender.stall_limit = std::chrono::milliseconds(0);
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  EXPECT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_GT(r.commands, 200u);
}

TEST(SenderProgress, TheSameJobOverTcpAndInLockstepCutsTheSamePath) {
  const JobPlan plan = ring_of_lines(300);
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(2);
  const sim::SimJobResult lockstep = sim::run_sim_job(plan, o);
  o.over_tcp = true;
  const sim::SimJobResult tcp = sim::run_sim_job(plan, o);
  ASSERT_EQ(lockstep.outcome, JobOutcome::kCompleted) << lockstep.message;
  ASSERT_EQ(tcp.outcome, JobOutcome::kCompleted) << tcp.message;
  EXPECT_NEAR(tcp.cut_mm, lockstep.cut_mm, 0.002 * lockstep.cut_mm);
  EXPECT_LT(lockstep.max_contour_error_um, 10.0);
  EXPECT_LT(tcp.max_contour_error_um, 10.0);
}

// Lets only status queries through once `after` bytes were written: the controller answers
// but gets nothing more to do.
class StatusOnlyLink : public Link {
 public:
  StatusOnlyLink(std::unique_ptr<Link> inner, size_t after)
      : inner_(std::move(inner)), after_(after) {}
  void write(const uint8_t* data, size_t size) override {
    written_ += size;
    if (written_ > after_ && size > 1 && data[1] != proto::kCmdStatus) return;
    inner_->write(data, size);
  }
  size_t read(uint8_t* b, size_t c, std::chrono::milliseconds t) override {
    return inner_->read(b, c, t);
  }
  std::string name() const override { return inner_->name(); }

 private:
  std::unique_ptr<Link> inner_;
  size_t after_, written_ = 0;
};

// Hands the replies over a few bytes at a time with an empty read between the pieces, as a
// busy simulator's (or a slow link's) replies arrive: every reply frame comes in pieces.
class DribbleLink : public Link {
 public:
  explicit DribbleLink(std::unique_ptr<Link> inner) : inner_(std::move(inner)) {}
  void write(const uint8_t* data, size_t size) override { inner_->write(data, size); }
  size_t read(uint8_t* b, size_t c, std::chrono::milliseconds t) override {
    give_ = !give_;
    if (!give_ || pending_.empty()) {  // nothing handed over: time passes as on the link
      uint8_t in[512];
      const size_t n = inner_->read(in, sizeof in, t);
      pending_.insert(pending_.end(), in, in + n);
      return 0;
    }
    const size_t n = std::min<size_t>({c, pending_.size(), 4});
    std::copy(pending_.begin(), pending_.begin() + static_cast<long>(n), b);
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(n));
    return n;
  }
  std::string name() const override { return inner_->name(); }

 private:
  std::unique_ptr<Link> inner_;
  std::vector<uint8_t> pending_;
  bool give_ = false;
};

// Statuses 250 ms apart while the machine cuts what it stores: a reply that came in pieces
// was dropped as a stalled partial frame when the last whole reply was over 200 ms old, and
// so was every one after it: "no reply for 10000 ms" (send to a busy `sim --realtime`).
TEST(SenderProgress, RepliesInPiecesAfterAQuietSpellAreAllRead) {
  const JobPlan plan = ring_of_lines(20);
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(250);
  o.wrap_link = [](std::unique_ptr<Link> l) -> std::unique_ptr<Link> {
    return std::make_unique<DribbleLink>(std::move(l));
  };
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  EXPECT_EQ(r.outcome, JobOutcome::kCompleted) << r.message;
  EXPECT_EQ(r.stats.reply_rejects, 0u);
}

TEST(SenderProgress, WatchdogEndsAJobThatMakesNoProgress) {
  const JobPlan plan = ring_of_lines(100);
  sim::SimJobOptions o;
  o.sender.status_interval = std::chrono::milliseconds(50);
  o.sender.stall_limit = std::chrono::milliseconds(3000);
  o.wrap_link = [](std::unique_ptr<Link> l) -> std::unique_ptr<Link> {
    return std::make_unique<StatusOnlyLink>(std::move(l), 400);
  };
  const sim::SimJobResult r = sim::run_sim_job(plan, o);
  EXPECT_EQ(r.outcome, JobOutcome::kStalled) << r.message;
  EXPECT_NE(r.message.find("no progress for 3 s"), std::string::npos) << r.message;
  EXPECT_NE(r.message.find("of " + std::to_string(r.commands) + " commands executed"),
            std::string::npos)
      << r.message;
  // It ended soon after the limit (machine time), not at the 10 s silence limit.
  EXPECT_LT(r.virtual_ms, 10000u);
}

}  // namespace
}  // namespace host
