// Protocol versions: the host asks for 3 (#Q contour frames); a controller that speaks only 2
// names its version in the refusal, and the host opens the session in 2 and sends its
// splines as #K frames, which such a controller stores.
#include <gtest/gtest.h>

#include <set>     // std::set
#include <vector>  // std::vector

#include "firmware/protocol/codec.h"
#include "firmware/protocol/parser.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/stream/job_encoder.h"
#include "host/lib/stream/sender.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

// A version-2 controller in front of the simulated one: refuses #I 3 as such a firmware
// does (*E version unsupported, detail 2) and records the letters of every frame passed on.
class Version2Link : public Link {
 public:
  explicit Version2Link(sim::SimMachine& m) : inner_(m), parser_(proto::kCommandStart) {}

  void write(const uint8_t* data, size_t size) override {
    bool refused = false;
    for (size_t i = 0; i < size; ++i) {
      for (proto::ParseEvent e = parser_.feed(data[i]); e != proto::ParseEvent::kNone;
           e = parser_.poll()) {
        if (e != proto::ParseEvent::kFrame) continue;
        const proto::Frame& f = parser_.frame();
        if (f.letter == proto::kCmdSession && f.length == 1 && f.payload[0] > 2) {
          refuse(f.seq);
          refused = true;
        } else {
          letters_.insert(f.letter);
        }
      }
    }
    if (!refused) inner_.write(data, size);
  }
  size_t read(uint8_t* buffer, size_t capacity, std::chrono::milliseconds timeout) override {
    if (pending_.empty()) return inner_.read(buffer, capacity, timeout);
    const size_t n = std::min(capacity, pending_.size());
    std::copy(pending_.begin(), pending_.begin() + static_cast<long>(n), buffer);
    pending_.erase(pending_.begin(), pending_.begin() + static_cast<long>(n));
    return n;
  }
  std::string name() const override { return "version-2 controller"; }
  const std::set<uint8_t>& letters() const { return letters_; }

 private:
  void refuse(uint8_t seq) {
    const proto::ErrorReply r{proto::ErrorCode::kVersionUnsupported, 2, 0};
    uint8_t buf[proto::kMaxFrameBytes];
    uint8_t n = 0;
    ASSERT_EQ(proto::write_frame(r, seq, buf, sizeof buf, &n), proto::ErrorCode::kOk);
    pending_.insert(pending_.end(), buf, buf + n);
  }
  sim::SimLink inner_;
  proto::Parser parser_;
  std::vector<uint8_t> pending_;
  std::set<uint8_t> letters_;
};

SenderOptions lockstep(sim::SimMachine& m) {
  SenderOptions o;
  o.clock = [&m] { return sim::machine_clock(m); };
  o.status_interval = std::chrono::milliseconds(50);
  return o;
}

const JobPlan& circles() {
  static const JobPlan plan = test::plan_of(
      test::drawing_of({test::circle_curve(20, 20, 10), test::circle_curve(50, 20, 8)}));
  return plan;
}

TEST(ProtocolVersion, TheSimulatedControllerSpeaks3AndStoresContourFrames) {
  sim::SimMachine m{sim::SimOptions{}};
  sim::SimLink link(m);
  Sender s(link, lockstep(m));
  const proto::SessionReply caps = s.open_session();
  EXPECT_EQ(caps.protocol_version, 3);
  EncodeOptions enc;
  use_session(caps, &enc);
  const std::vector<QueuedCommand> cmds = encode_job(circles(), enc);
  int contour = 0;
  for (const QueuedCommand& c : cmds) contour += c.letter == proto::kCmdSplineContour;
  EXPECT_EQ(contour, 2);  // each circle: four quarter arcs in one #Q frame
  EXPECT_EQ(s.run(cmds, nullptr), JobOutcome::kCompleted) << s.message();
}

TEST(ProtocolVersion, AVersion2ControllerGetsASessionInItsVersionAndCompactFrames) {
  sim::SimMachine m{sim::SimOptions{}};
  Version2Link link(m);
  Sender s(link, lockstep(m));
  const proto::SessionReply caps = s.open_session();
  EXPECT_EQ(caps.protocol_version, 2);
  EncodeOptions enc;
  use_session(caps, &enc);
  EXPECT_EQ(enc.splines, SplineFrames::kCompact);
  EXPECT_EQ(s.run(encode_job(circles(), enc), nullptr), JobOutcome::kCompleted) << s.message();
  EXPECT_EQ(link.letters().count(proto::kCmdSplineContour), 0u);
  EXPECT_EQ(link.letters().count(proto::kCmdSplineCompact), 1u);
}

}  // namespace
}  // namespace host
