// The simulator as a controller on a socket: its link time-outs (the 200 ms inter-byte frame
// time-out, the 2 s link watchdog) count the wall-clock time of the link, as the real
// controller's do, however fast machine time runs between the bytes. A client on a real
// loopback TCP socket writes frames byte by byte and in pieces with real delays, sends line
// noise, and falls silent.
#include <gtest/gtest.h>

#include <chrono>   // steady_clock
#include <cstring>  // std::memcpy
#include <random>   // std::mt19937
#include <thread>   // sleep_for
#include <vector>   // std::vector

#include "firmware/protocol/codec.h"   // proto::write_frame, decode_frame
#include "firmware/protocol/parser.h"  // proto::Parser
#include "host/lib/sim/sim_server.h"
#include "host/lib/stream/link.h"
#include "host_tests/host/sim/served_sim.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

using Clock = std::chrono::steady_clock;
using std::chrono::milliseconds;

template <typename Msg>
std::vector<uint8_t> frame_of(const Msg& msg, uint8_t seq) {
  uint8_t buf[proto::kMaxFrameBytes];
  uint8_t size = 0;
  EXPECT_EQ(proto::write_frame(msg, seq, buf, sizeof buf, &size), proto::ErrorCode::kOk);
  return std::vector<uint8_t>(buf, buf + size);
}

// A client that talks to the simulator over TCP byte by byte, as any program may.
class RawClient {
 public:
  explicit RawClient(uint16_t port)
      : link_(open_link(parse_link_spec("tcp://127.0.0.1:" + std::to_string(port)),
                        milliseconds(2000))),
        parser_(proto::kReplyStart) {}

  void write(const std::vector<uint8_t>& bytes, size_t from = 0, size_t to = SIZE_MAX) {
    to = std::min(to, bytes.size());
    if (from < to) link_->write(bytes.data() + from, to - from);
  }
  // Writes one byte at a time, gap apart.
  void write_bytewise(const std::vector<uint8_t>& bytes, milliseconds gap) {
    for (size_t i = 0; i < bytes.size(); ++i) {
      if (i > 0) std::this_thread::sleep_for(gap);
      write(bytes, i, i + 1);
    }
  }

  // Waits up to timeout for the reply with this letter and seq; its payload, or false.
  template <typename Reply>
  bool reply(uint8_t seq, Reply* out, milliseconds timeout = milliseconds(1000)) {
    const Clock::time_point until = Clock::now() + timeout;
    while (true) {
      for (const Got& g : got_) {
        if (g.letter == Reply::kLetter && g.seq == seq) {
          proto::Frame f{proto::kReplyStart,
                         g.letter,
                         g.seq,
                         static_cast<uint8_t>(g.payload.size()),
                         proto::FrameKind::kImmediate,
                         g.payload.data()};
          return proto::decode_frame(f, out) == proto::ErrorCode::kOk;
        }
      }
      const auto left = std::chrono::duration_cast<milliseconds>(until - Clock::now());
      if (left.count() <= 0) return false;
      take(left);
    }
  }
  // Reads what has arrived without waiting (keeps the socket drained during noise).
  void drain() { take(milliseconds(0)); }

 private:
  struct Got {
    uint8_t letter, seq;
    std::vector<uint8_t> payload;
  };
  void take(milliseconds timeout) {
    uint8_t buf[512];
    const size_t n = link_->read(buf, sizeof buf, timeout);
    for (size_t i = 0; i < n; ++i) {
      for (proto::ParseEvent ev = parser_.feed(buf[i]); ev != proto::ParseEvent::kNone;
           ev = parser_.poll()) {
        if (ev != proto::ParseEvent::kFrame) continue;
        const proto::Frame& f = parser_.frame();
        got_.push_back({f.letter, f.seq, std::vector<uint8_t>(f.payload, f.payload + f.length)});
      }
    }
  }

  std::unique_ptr<Link> link_;
  proto::Parser parser_;
  std::vector<Got> got_;
};

proto::StatusCmd status_query() {
  return proto::StatusCmd{};
}

proto::SessionCmd session_v3() {
  proto::SessionCmd c{};
  c.protocol_version = 3;
  return c;
}

proto::TextCmd lcd_text(const char* text) {
  proto::TextCmd c{};
  c.row = 0;
  c.length = static_cast<uint8_t>(std::strlen(text));
  std::memcpy(c.text, text, c.length);
  return c;
}

TEST(SimServerLinkTime, FramesWrittenInPiecesWithRealDelaysAreAllAnswered) {
  sim::SimMachine machine{sim::SimOptions{}};
  EXPECT_EQ(machine.link_time(), sim::SimMachine::LinkTime::kMachine);  // lockstep clients
  sim::ServerOptions so;
  so.port = 0;
  sim::SimServer server(machine, so);
  EXPECT_EQ(machine.link_time(), sim::SimMachine::LinkTime::kWall);
  test::Serving serving(server);
  RawClient client(server.port());
  int answered = 0;

  // The session frame, one byte every 5 ms.
  client.write_bytewise(frame_of(session_v3(), 0), milliseconds(5));
  proto::SessionReply session{};
  answered += client.reply(0, &session);
  // A queued 22-byte frame, one byte every 2 ms.
  client.write_bytewise(frame_of(lcd_text("in pieces"), 1), milliseconds(2));
  proto::AckReply ack{};
  answered += client.reply(1, &ack);
  // Status queries split in two at different places, 1, 20 and 50 ms between the pieces.
  const int split_at[] = {1, 3, 5};
  const int gap_ms[] = {1, 20, 50};
  for (int i = 0; i < 3; ++i) {
    const uint8_t seq = static_cast<uint8_t>(10 + i);
    const std::vector<uint8_t> f = frame_of(status_query(), seq);
    client.write(f, 0, split_at[i]);
    std::this_thread::sleep_for(milliseconds(gap_ms[i]));
    client.write(f, split_at[i]);
    proto::StatusReply status{};
    answered += client.reply(seq, &status);
  }
  serving.stop();
  EXPECT_EQ(answered, 5) << "frames answered of 5";
}

// Opens a session, zeroes and starts a long, slow feed move; true once the status says running.
bool start_long_move(RawClient& client) {
  client.write(frame_of(session_v3(), 0));
  proto::SessionReply session{};
  if (!client.reply(0, &session)) return false;
  proto::ZeroingCmd zero{};
  zero.axes = 7;
  client.write(frame_of(zero, 1));
  proto::FeedMoveCmd move{};
  move.x_um = 50000;
  move.y_um = 0;
  move.feed_um_per_s = 20;  // 2500 s: still running after the noise, however fast machine time ran
  client.write(frame_of(move, 2));
  proto::AckReply ack{};
  if (!client.reply(1, &ack) || !client.reply(2, &ack)) return false;
  for (uint8_t seq = 100; seq < 200; ++seq) {
    client.write(frame_of(status_query(), seq));
    proto::StatusReply s{};
    if (client.reply(seq, &s) && s.state == proto::MachineState::kRunning) return true;
    std::this_thread::sleep_for(milliseconds(20));
  }
  return false;
}

// Writes line noise for duration: random bytes with start bytes among them, frames with a
// byte changed (their CRC fails), first halves of frames never finished.
void write_noise(RawClient& client, std::mt19937& rng, milliseconds duration) {
  const std::vector<uint8_t> valid = frame_of(lcd_text("noise"), 3);
  const Clock::time_point start = Clock::now();
  for (int bursts = 0; Clock::now() - start < duration; ++bursts) {
    std::vector<uint8_t> burst;
    switch (bursts % 3) {
      case 0:
        for (int i = 0; i < 1 + static_cast<int>(rng() % 24); ++i)
          burst.push_back(rng() % 8 == 0 ? proto::kCommandStart : static_cast<uint8_t>(rng()));
        break;
      case 1:
        burst = valid;
        burst[1 + rng() % (burst.size() - 1)] ^= static_cast<uint8_t>(1 + rng() % 255);
        break;
      default:
        burst.assign(valid.begin(), valid.begin() + static_cast<long>(valid.size() / 2));
        break;
    }
    client.write(burst);
    client.drain();
    std::this_thread::sleep_for(milliseconds(1 + rng() % 20));
  }
}

TEST(SimServerLinkTime, NoiseDoesNotTripTheWatchdogWhileValidFramesComeInTime) {
  // 2 s of line noise while a move runs, one valid status query 0.7 s into it, so at most
  // 1.3 s (plus a false candidate's 200 ms) pass without a valid frame: the real
  // controller's 2 s watchdog would not trip, so neither may the simulator's; a valid frame
  // is answered after the noise.
  test::ServedSim served;
  RawClient client(served.port());
  ASSERT_TRUE(start_long_move(client));

  std::mt19937 rng(22);
  const Clock::time_point start = Clock::now();
  proto::StatusReply s{};
  write_noise(client, rng, milliseconds(700));
  client.write(frame_of(status_query(), 249));
  ASSERT_TRUE(client.reply(249, &s)) << "a valid frame amid the noise is not answered";
  EXPECT_EQ(s.flags & proto::kStatusLinkHold, 0) << "the link watchdog tripped within 0.7 s";
  write_noise(client, rng, milliseconds(1300));
  const double noise_ms = std::chrono::duration<double, std::milli>(Clock::now() - start).count();

  client.write(frame_of(status_query(), 250));
  ASSERT_TRUE(client.reply(250, &s)) << "a valid frame after the noise is not answered";
  served.stop();
  EXPECT_EQ(s.state, proto::MachineState::kRunning) << noise_ms << " ms of noise";
  EXPECT_EQ(s.flags & proto::kStatusLinkHold, 0)
      << "the link watchdog tripped in " << noise_ms << " ms of noise";
  EXPECT_GT(s.rejected_frames, 20) << "the noise did not reach the parser";
}

TEST(SimServerLinkTime, AMachineSlowerThanRealTimeStillAnswersEveryFrame) {
  // A busy computer: each tool position costs the simulation 3 ms of wall clock, so machine
  // time falls ever further behind the wall clock while the tool moves. The machine catches
  // up as it can, and meanwhile still reads the host's frames: every status query is
  // answered, the link watchdog (wall clock) hears them and does not hold the job.
  sim::SimMachine machine{sim::SimOptions{}};
  machine.set_sample_sink(
      [](const sim::ToolSample&) { std::this_thread::sleep_for(milliseconds(3)); });
  sim::ServerOptions so;
  so.port = 0;
  so.realtime = true;
  sim::SimServer server(machine, so);
  test::Serving serving(server);
  RawClient client(server.port());
  client.write(frame_of(session_v3(), 0));
  proto::SessionReply session{};
  ASSERT_TRUE(client.reply(0, &session));
  proto::ZeroingCmd zero{};
  zero.axes = 7;
  client.write(frame_of(zero, 1));
  proto::FeedMoveCmd move{};
  move.x_um = 50000;
  move.feed_um_per_s = 5000;  // a new position every machine millisecond
  client.write(frame_of(move, 2));
  proto::AckReply ack{};
  ASSERT_TRUE(client.reply(1, &ack));
  ASSERT_TRUE(client.reply(2, &ack));
  int answered = 0, running = 0;
  proto::StatusReply s{};
  for (uint8_t seq = 100; seq < 130; ++seq) {  // 3 s of wall clock
    client.write(frame_of(status_query(), seq));
    if (client.reply(seq, &s, milliseconds(100))) {
      ++answered;
      running += s.state == proto::MachineState::kRunning && !(s.flags & proto::kStatusLinkHold);
    }
    std::this_thread::sleep_for(milliseconds(100));
  }
  serving.stop();
  EXPECT_EQ(answered, 30) << "status queries answered within 100 ms, of 30";
  EXPECT_GE(running, 25) << "running, not held, of 30";
  EXPECT_LT(s.x_um, 10000) << "machine time did not fall behind the wall clock";
}

TEST(SimServerLinkTime, SilenceLongerThanTheWatchdogStillTripsIt) {
  // The safety stays: 2.5 s of wall-clock silence while a move runs hold the machine.
  test::ServedSim served;
  RawClient client(served.port());
  ASSERT_TRUE(start_long_move(client));
  std::this_thread::sleep_for(milliseconds(2500));
  client.write(frame_of(status_query(), 251));
  proto::StatusReply s{};
  ASSERT_TRUE(client.reply(251, &s));
  served.stop();
  EXPECT_NE(s.flags & proto::kStatusLinkHold, 0) << "2.5 s of silence did not trip the watchdog";
  EXPECT_TRUE(s.state == proto::MachineState::kHolding || s.state == proto::MachineState::kHeld)
      << "state " << static_cast<int>(s.state);
}

}  // namespace
}  // namespace host
