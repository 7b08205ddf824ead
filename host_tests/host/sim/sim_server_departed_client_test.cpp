// The simulator's TCP server when a client hangs up with frames it sent still unread: they
// are dropped with the connection (a `#F` sent just before the hang-up ran after the client
// had gone, and its replies went to the next client); the next client starts clean.
#include <gtest/gtest.h>

#include <netinet/tcp.h>  // TCP_CORK
#include <sys/socket.h>   // setsockopt
#include <unistd.h>       // close, read

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
using test::append_frame;
using test::connect_to;
using test::write_all;

Sender open_sender(Link& link) {
  SenderOptions o;
  o.status_interval = milliseconds(5);
  return Sender(link, o);
}

TEST(SimServer, ADepartedClientsUnreadFramesAreDroppedAndTheNextClientStartsClean) {
  test::ServedSim served;
  const std::string address = served.address();
  {
    // A first client zeroes the machine (the simulated operator confirms) and leaves.
    auto link = open_link(parse_link_spec(address), milliseconds(2000));
    Sender sender = open_sender(*link);
    sender.open_session();
    ASSERT_EQ(sender.run(std::vector<QueuedCommand>{}, [](const Progress&) {}),
              JobOutcome::kCompleted);
    EXPECT_EQ(sender.read_status().x_um, 0);
  }
  // A client sends a session and a rapid move to X 20 mm, and hangs up at once: the bytes
  // and the end of the stream reach the server together (corked until the close).
  const int fd = connect_to(served.port());
  ASSERT_GE(fd, 0);
  const int on = 1;
  ASSERT_EQ(::setsockopt(fd, IPPROTO_TCP, TCP_CORK, &on, sizeof on), 0);
  std::vector<uint8_t> bytes;
  append_frame(proto::SessionCmd{proto::kProtocolVersion}, 0, &bytes);
  append_frame(proto::RapidMoveCmd{20000, 0}, 1, &bytes);
  write_all(fd, bytes);
  ::close(fd);
  std::this_thread::sleep_for(milliseconds(500));  // time enough to run it, were it read
  // The next client: its first reply answers its own status query, no *I or *O of the
  // departed client's.
  const int next = connect_to(served.port());
  ASSERT_GE(next, 0);
  std::vector<uint8_t> query;
  append_frame(proto::StatusCmd{}, 7, &query);
  write_all(next, query);
  uint8_t reply[2] = {0, 0};
  size_t got = 0;
  while (got < sizeof reply) {
    const ssize_t n = ::read(next, reply + got, sizeof reply - got);
    ASSERT_GT(n, 0);
    got += static_cast<size_t>(n);
  }
  EXPECT_EQ(reply[0], '*');
  EXPECT_EQ(reply[1], '?') << "the first reply is '*" << char(reply[1]) << "'";
  ::close(next);
  // The machine did not run the departed client's move.
  auto link = open_link(parse_link_spec(address), milliseconds(2000));
  Sender sender = open_sender(*link);
  sender.open_session();
  const proto::StatusReply s = sender.read_status();
  EXPECT_EQ(s.x_um, 0);
  EXPECT_EQ(s.state, proto::MachineState::kIdle);
  served.stop();
}

}  // namespace
}  // namespace host
