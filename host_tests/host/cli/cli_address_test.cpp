// ADDR:PORT on the command line: `sim --listen`, `serve --listen` and `send --to tcp://` read
// one form (an IPv6 address in brackets, as the guide and a URL write it) and print it back
// the same way (a docs-only tester: `sim --listen '[::1]:47907'` was refused, `serve` could
// not listen on [::1] and printed http://::1:47912/, send printed tcp://::1:47909; serve's
// bad ports said only "expected ADDR:PORT" and a bad address ended with exit 1).
#include <arpa/inet.h>  // inet_pton
#include <gtest/gtest.h>
#include <netinet/in.h>  // sockaddr_in6
#include <sys/socket.h>  // socket, bind
#include <unistd.h>      // close, getpid

#include <string>  // std::string

#include "host_tests/host/cli/tool_run.h"

namespace {

using host_tests::ToolRun;

const std::string kExe = ENGRAVER_EXE;
const std::string kWord = std::string(ENGRAVER_SOURCE_DIR) + "/samples/engraver-word.dxf";

// `script` run by sh: its exit code and what it wrote.
ToolRun shell(const std::string& script) {
  return host_tests::run_tool("sh -c", "'" + script + "'");
}

// This PC listens on the IPv6 loopback (a container may have IPv6 switched off).
bool has_ipv6_loopback() {
  const int fd = ::socket(AF_INET6, SOCK_STREAM, 0);
  if (fd < 0) return false;
  sockaddr_in6 a{};
  a.sin6_family = AF_INET6;
  inet_pton(AF_INET6, "::1", &a.sin6_addr);
  const bool ok = ::bind(fd, reinterpret_cast<sockaddr*>(&a), sizeof a) == 0;
  ::close(fd);
  return ok;
}

// A port for this test process: several test processes run at once.
std::string test_port(int offset) {
  return std::to_string(30000 + offset + static_cast<int>(getpid() % 10000) * 3);
}

TEST(CliAddress, TheSimulatorListensOnABracketedIpv6AddressAndSaysItSo) {
  if (!has_ipv6_loopback()) GTEST_SKIP() << "no IPv6 loopback";
  const ToolRun r = shell("timeout -s INT 1 " + kExe + " sim --listen [::1]:0");
  EXPECT_NE(r.err.find("engraver: simulated machine on [::1]:"), std::string::npos) << r.err;
}

TEST(CliAddress, SendReachesASimulatorOnIpv6) {
  if (!has_ipv6_loopback()) GTEST_SKIP() << "no IPv6 loopback";
  const std::string port = test_port(0);
  // --resume on a simulator that never ran a job: answered by the controller (exit 1), so
  // the session was opened over IPv6.
  const ToolRun r = shell(kExe + " sim --listen [::1]:" + port + " >/dev/null 2>&1 & S=$!; " +
                          "sleep 0.5; " + kExe + " send " + kWord + " --to tcp://[::1]:" + port +
                          " --resume; r=$?; kill $S; exit $r");
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.err.find("no job progress"), std::string::npos) << r.err;
}

TEST(CliAddress, ALinkThatCannotConnectIsNamedWithTheBracketedAddress) {
  if (!has_ipv6_loopback()) GTEST_SKIP() << "no IPv6 loopback";
  const ToolRun r = host_tests::run_tool(kExe, "send " + kWord + " --to tcp://[::1]:1");
  EXPECT_EQ(r.code, 6) << r.err;
  EXPECT_NE(r.err.find("engraver: tcp://[::1]:1: cannot connect: Connection refused\n"),
            std::string::npos)
      << r.err;
}

TEST(CliAddress, TheServerListensOnABracketedIpv6AddressAndPrintsAUrl) {
  if (!has_ipv6_loopback()) GTEST_SKIP() << "no IPv6 loopback";
  const std::string data = testing::TempDir() + "/cli_address_" + std::to_string(getpid());
  const ToolRun r =
      shell("timeout -s INT 2 " + kExe + " serve --data " + data + " --listen [::1]:0");
  EXPECT_NE(r.err.find("engraver: serving http://[::1]:"), std::string::npos) << r.err;
  std::system(("rm -rf " + data).c_str());
}

// An unbracketed IPv6 address is ambiguous (::1:47907 is an address too): refused, saying how.
TEST(CliAddress, AnIpv6AddressWithoutBracketsIsRefusedSayingHowToWriteIt) {
  const ToolRun r = host_tests::run_tool(kExe, "sim --listen ::1:47907");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_EQ(r.err.rfind("engraver: --listen: '::1:47907': an IPv6 address goes in brackets, as "
                        "in a URL: [::1]:47907",
                        0),
            0u)
      << r.err;
}

// serve reads --listen as sim does: the same messages, exit 2, before the data folder is made.
TEST(CliAddress, ServesBadListenAddressesAreUsageErrorsWithSimsMessages) {
  const std::string data = testing::TempDir() + "/cli_address_bad_" + std::to_string(getpid());
  const struct {
    const char* listen;
    const char* says;
  } bad[] = {{"127.0.0.1:65536", "the port must be 0 .. 65535 (0: any free port)"},
             {"127.0.0.1:80x", "the port must be 0 .. 65535 (0: any free port)"},
             {"127.0.0.1:-80", "the port must be 0 .. 65535 (0: any free port)"},
             {"127.0.0.1:99999999999999999999", "the port must be 0 .. 65535 (0: any free port)"},
             {"-80", "expected ADDR:PORT"},
             {"nowhere.example:8080", "listen address 'nowhere.example' is not a numeric address"}};
  for (const auto& b : bad) {
    for (const std::string command : {"serve --data " + data, std::string("sim")}) {
      const ToolRun r = host_tests::run_tool(kExe, command + " --listen '" + b.listen + "'");
      EXPECT_EQ(r.code, 2) << command << " " << b.listen << "\n" << r.err;
      EXPECT_EQ(r.err.rfind(std::string("engraver: --listen: '") + b.listen + "': " + b.says, 0),
                0u)
          << command << "\n"
          << r.err;
    }
  }
  for (const std::string command : {"serve --data " + data, std::string("sim")}) {
    const ToolRun r = host_tests::run_tool(kExe, command + " --listen ''");
    EXPECT_EQ(r.code, 2) << command << "\n" << r.err;
    EXPECT_EQ(r.err.rfind("engraver: --listen: an empty value", 0), 0u) << command << "\n" << r.err;
  }
}

// An address that parses but cannot be listened on (not this PC's) is 2 for serve as for sim.
TEST(CliAddress, AnAddressThisPcCannotListenOnIsAUsageErrorForServeAsForSim) {
  const std::string data = testing::TempDir() + "/cli_address_far_" + std::to_string(getpid());
  for (const std::string command : {"serve --data " + data, std::string("sim")}) {
    const ToolRun r = host_tests::run_tool(kExe, command + " --listen 192.0.2.1:8080");
    EXPECT_EQ(r.code, 2) << command << "\n" << r.err;
    EXPECT_EQ(
        r.err.rfind("engraver: --listen: '192.0.2.1:8080': cannot listen on 192.0.2.1:8080", 0), 0u)
        << r.err;
  }
  std::system(("rm -rf " + data).c_str());
}

// A port another server listens on is refused (httplib's SO_REUSEPORT let a second server
// bind it, and the two took turns at its requests).
TEST(CliAddress, AServerRefusesAPortAnotherServerListensOn) {
  const std::string dir = testing::TempDir() + "/cli_address_twice_" + std::to_string(getpid());
  const std::string listen = "127.0.0.1:" + test_port(1);
  const ToolRun r = shell(kExe + " serve --data " + dir + "/1 --listen " + listen +
                          " 2>/dev/null & S=$!; sleep 1; timeout 10 " + kExe + " serve --data " +
                          dir + "/2 --listen " + listen + "; r=$?; kill $S; wait $S; exit $r");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("engraver: --listen: '" + listen + "': cannot listen on " + listen +
                       " (in use or not an address of this PC)\n"),
            std::string::npos)
      << r.err;
  std::system(("rm -rf " + dir).c_str());
}

TEST(CliAddress, ServesHelpSaysWhatThePortIsAsSimsDoes) {
  for (const char* command : {"serve", "sim"}) {
    const ToolRun r = host_tests::run_tool(kExe, std::string(command) + " --help");
    EXPECT_NE(r.out.find("PORT in decimal, 080 is 80, 0 any free port"), std::string::npos)
        << r.out;
    EXPECT_NE(r.out.find("IPv6 in brackets"), std::string::npos) << r.out;
  }
}

}  // namespace
