// The simulated machine's probe: SimOptions::surface_um is the blank; #Y lowers the tool until
// the fake probe input closes on it, and #T reports the surface height under each point.
#include <gtest/gtest.h>

#include <chrono>      // milliseconds
#include <functional>  // std::function
#include <string>      // std::string

#include "firmware/protocol/codec.h"
#include "firmware/protocol/parser.h"
#include "host/lib/sim/sim_link.h"
#include "host/lib/sim/sim_machine.h"

namespace host {
namespace {

// Frames to the simulated machine and its replies back, in machine time.
struct Wire {
  explicit Wire(sim::SimMachine& m) : machine(m) {}
  template <typename Msg>
  void send(const Msg& msg) {
    uint8_t buf[proto::kMaxFrameBytes];
    uint8_t n = 0;
    const uint8_t s = proto::command_kind(Msg::kLetter) == proto::FrameKind::kQueued ? seq++ : 0;
    ASSERT_EQ(proto::write_frame(msg, s, buf, sizeof buf, &n), proto::ErrorCode::kOk);
    machine.from_host(buf, n);
  }
  // Steps until a reply with this letter arrives (true) or max_ms pass.
  bool await(uint8_t letter, proto::Frame* out, int max_ms = 60000) {
    for (int t = 0; t < max_ms; ++t) {
      machine.step_ms();
      const std::string bytes = machine.take_to_host();
      for (char c : bytes) {
        for (proto::ParseEvent e = parser.feed(static_cast<uint8_t>(c));
             e != proto::ParseEvent::kNone; e = parser.poll()) {
          if (e == proto::ParseEvent::kFrame && parser.frame().letter == letter) {
            *out = parser.frame();
            return true;
          }
        }
      }
    }
    return false;
  }
  bool idle() {
    for (int tries = 0; tries < 600; ++tries) {
      send(proto::StatusCmd{});
      proto::Frame f;
      proto::StatusReply r;
      if (!await(proto::kReplyStatus, &f, 200) ||
          proto::decode_frame(f, &r) != proto::ErrorCode::kOk)
        return false;
      if (r.state == proto::MachineState::kIdle && r.queue_free == 16 &&
          (r.flags & proto::kStatusZeroed))
        return true;
      for (int k = 0; k < 50; ++k) machine.step_ms();
    }
    return false;
  }
  sim::SimMachine& machine;
  proto::Parser parser{proto::kReplyStart};
  uint8_t seq = 1;
};

TEST(SimProbe, ProbesFindTheSimulatedSurfaceUnderEachPoint) {
  sim::SimOptions o;
  const auto board = [](int32_t x, int32_t y) { return -200 - x / 250 + y / 400; };
  o.surface_um = board;
  sim::SimMachine machine(o);
  Wire wire(machine);
  wire.send(proto::SessionCmd{proto::kProtocolVersion});
  proto::Frame f;
  ASSERT_TRUE(wire.await(proto::kReplySession, &f));
  wire.send(proto::ZeroingCmd{7});
  ASSERT_TRUE(wire.idle());
  const int32_t points[3][2] = {{5000, 5000}, {40000, 5000}, {40000, 30000}};
  for (int i = 0; i < 3; ++i) {
    wire.send(proto::ZMoveCmd{1000, 3000});
    wire.send(proto::RapidMoveCmd{points[i][0], points[i][1]});
    wire.send(proto::ProbeCmd{-2000, 300, 500});
    ASSERT_TRUE(wire.idle()) << "point " << i;
    wire.send(proto::ProbeResultCmd{});
    ASSERT_TRUE(wire.await(proto::kReplyProbeResult, &f, 200));
    proto::ProbeResultReply r;
    ASSERT_EQ(proto::decode_frame(f, &r), proto::ErrorCode::kOk);
    EXPECT_EQ(r.result, 1);
    EXPECT_EQ(r.probe_count, i + 1);
    EXPECT_NEAR(r.x_um, points[i][0], 1);
    EXPECT_NEAR(r.z_um, board(points[i][0], points[i][1]), 2) << "point " << i;
    EXPECT_NEAR(machine.position().z_mm * 1000, r.z_um + 500, 2);  // retracted
    EXPECT_FALSE(machine.probe_closed());
  }
}

TEST(SimProbe, WithoutASurfaceTheProbeFindsNothing) {
  sim::SimMachine machine{sim::SimOptions{}};
  Wire wire(machine);
  wire.send(proto::SessionCmd{proto::kProtocolVersion});
  proto::Frame f;
  ASSERT_TRUE(wire.await(proto::kReplySession, &f));
  wire.send(proto::ZeroingCmd{7});
  ASSERT_TRUE(wire.idle());
  wire.send(proto::ProbeCmd{-1000, 2000, 500});
  ASSERT_TRUE(wire.await(proto::kReplyAlarm, &f, 5000));
  proto::AlarmReply a;
  ASSERT_EQ(proto::decode_frame(f, &a), proto::ErrorCode::kOk);
  EXPECT_EQ(a.alarm, proto::Alarm::kProbeNoContact);
}

// SimLink hands the machine's reply bytes over without a string a millisecond: a read with
// less room than has arrived leaves the rest in the machine, and the next read returns them
// at once, without running machine time; together they are the whole reply.
TEST(SimLinkRead, BytesLeftByASmallReadComeNextWithoutMachineTime) {
  sim::SimMachine machine{sim::SimOptions{}};
  sim::SimLink link(machine);
  uint8_t frame[proto::kMaxFrameBytes];
  uint8_t n = 0;
  ASSERT_EQ(proto::write_frame(proto::StatusCmd{}, 0, frame, sizeof frame, &n),
            proto::ErrorCode::kOk);
  link.write(frame, n);
  uint8_t buf[512];
  const size_t first = link.read(buf, 3, std::chrono::milliseconds(1000));
  ASSERT_EQ(first, 3u);
  EXPECT_TRUE(machine.to_host_waiting());
  const uint64_t at = machine.now_ms();
  const size_t rest = link.read(buf + first, sizeof buf - first, std::chrono::milliseconds(1000));
  EXPECT_EQ(machine.now_ms(), at);  // what had arrived, no machine time run for it
  EXPECT_FALSE(machine.to_host_waiting());
  // The rest of the reply as the UART lets it out, a millisecond's bytes at a time.
  size_t got = first + rest;
  proto::Parser parser(proto::kReplyStart);
  bool status = false;
  for (size_t i = 0; i < got && !status; ++i) {
    if (parser.feed(buf[i]) == proto::ParseEvent::kFrame)
      status = parser.frame().letter == proto::kReplyStatus;
  }
  while (!status && got < sizeof buf) {
    const size_t k = link.read(buf + got, sizeof buf - got, std::chrono::milliseconds(1000));
    ASSERT_GT(k, 0u);
    for (size_t i = got; i < got + k && !status; ++i) {
      if (parser.feed(buf[i]) == proto::ParseEvent::kFrame)
        status = parser.frame().letter == proto::kReplyStatus;
    }
    got += k;
  }
  EXPECT_TRUE(status);
  const uint64_t after = machine.now_ms();
  // Nothing waiting: a read runs machine time up to its time-out and returns nothing.
  EXPECT_EQ(link.read(buf, sizeof buf, std::chrono::milliseconds(5)), 0u);
  EXPECT_EQ(machine.now_ms(), after + 5);
}

}  // namespace
}  // namespace host
