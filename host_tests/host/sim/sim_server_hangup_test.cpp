// The simulator's TCP server when a client hangs up with replies still on their way (an
// `engraver send` whose job was refused, killed): its writes to the dead socket must not
// raise SIGPIPE (which ends the process: `engraver sim` died of it), and the next client is
// served. The server runs in this test's process, so SIGPIPE would end the test.
#include <gtest/gtest.h>

#include <sys/socket.h>  // shutdown
#include <unistd.h>      // close, read

#include <chrono>  // milliseconds
#include <thread>  // sleep_for
#include <vector>  // std::vector

#include "host/lib/sim/sim_server.h"
#include "host/lib/stream/sender.h"
#include "host_tests/host/sim/raw_client.h"  // append_frame, connect_to, write_all
#include "host_tests/host/sim/served_sim.h"
#include "host_tests/host/sim/sim_test_jobs.h"

namespace host {
namespace {

using std::chrono::milliseconds;

// Connects, sends frames the controller answers over the next few hundred milliseconds (a
// session and status queries), and hangs up as a client that exits does: its end closed
// (FIN: the server's socket is in CLOSE_WAIT), then gone (the server's next bytes are
// answered with a reset, after which a write is EPIPE: SIGPIPE unless the server asks for
// none).
void hang_up_with_replies_in_flight(uint16_t port) {
  const int fd = test::connect_to(port);
  ASSERT_GE(fd, 0);
  std::vector<uint8_t> bytes;
  test::append_frame(proto::SessionCmd{proto::kProtocolVersion}, 0, &bytes);
  for (int i = 0; i < 600; ++i) test::append_frame(proto::StatusCmd{}, 1, &bytes);
  test::write_all(fd, bytes);
  // The first reply: the server has taken every byte and is answering the rest (the end of
  // the stream is not among what it read).
  uint8_t reply[64];
  ASSERT_GT(::read(fd, reply, sizeof reply), 0);
  ::shutdown(fd, SHUT_WR);
  ::close(fd);
}

TEST(SimServer, AClientHangingUpWithRepliesInFlightDoesNotEndTheServer) {
  test::ServedSim served;
  // Whether the server writes before it reads the end of the stream is a race: try often.
  // Each time the bytes the client left on the wire (the simulated UART, 115200 baud) are
  // answered into the void within the pause.
  for (int i = 0; i < 5; ++i) {
    hang_up_with_replies_in_flight(served.port());
    std::this_thread::sleep_for(milliseconds(500));
  }
  // Still here (SIGPIPE would have ended the process), and the next client is served.
  auto link = open_link(parse_link_spec(served.address()), milliseconds(2000));
  Sender sender(*link, SenderOptions{});
  const proto::SessionReply caps = sender.open_session();
  EXPECT_GT(caps.max_payload, 0);
  EXPECT_EQ(sender.read_status().state, proto::MachineState::kIdle);
  served.stop();
}

}  // namespace
}  // namespace host
