// `engraver sim` as a function: its --listen forms, its trace file, and a serve that stops.
#include <gtest/gtest.h>

#include <atomic>      // std::atomic
#include <filesystem>  // temp_directory_path
#include <fstream>     // std::ifstream
#include <sstream>     // std::ostringstream
#include <string>      // std::string

#include "host/lib/commands/exit_codes.h"
#include "host/lib/commands/sim_command.h"

namespace host::commands {
namespace {

int exit_code_of_listen(const std::string& listen) {
  try {
    listen_options(listen);
  } catch (const CommandFailure& e) {
    return e.code;
  }
  return kExitOk;
}

TEST(SimCommandListen, TakesAddressPortSerialAndDevicePaths) {
  const sim::ServerOptions tcp = listen_options("0.0.0.0:2000");
  EXPECT_EQ(tcp.address, "0.0.0.0");
  EXPECT_EQ(tcp.port, 2000);
  EXPECT_TRUE(tcp.device.empty());
  EXPECT_EQ(listen_options("serial:/tmp/sim-tty,115200").device, "/tmp/sim-tty");
  EXPECT_EQ(listen_options("/dev/ttyUSB0").device, "/dev/ttyUSB0");
}

// A port is decimal, leading zeros too (080 is 80, as for --to): a long run of zeros was
// refused with the range message although the number was in range.
TEST(SimCommandListen, APortWithLeadingZerosIsDecimal) {
  EXPECT_EQ(listen_options("127.0.0.1:080").port, 80);
  EXPECT_EQ(listen_options("127.0.0.1:0000000080").port, 80);
  EXPECT_EQ(listen_options("127.0.0.1:000000").port, 0);  // any free port
  EXPECT_EQ(exit_code_of_listen("127.0.0.1:00000065536"), kExitUsage);
  EXPECT_EQ(exit_code_of_listen("127.0.0.1:0080x"), kExitUsage);
}

TEST(SimCommandListen, RefusesWhatIsNeitherAsAUsageError) {
  EXPECT_EQ(exit_code_of_listen("localhost"), kExitUsage);      // no port
  EXPECT_EQ(exit_code_of_listen("127.0.0.1:abc"), kExitUsage);  // bad port
  EXPECT_EQ(exit_code_of_listen("serial:"), kExitUsage);        // no device
}

TEST(SimCommandTrace, AnUnwritableTraceIsAUsageError) {
  try {
    TraceWriter w("/nonexistent-folder/trace.csv");
    FAIL() << "wrote into a missing folder";
  } catch (const CommandFailure& e) {
    EXPECT_EQ(e.code, kExitUsage);
    EXPECT_NE(std::string(e.what()).find("--trace"), std::string::npos);
  }
}

TEST(SimCommand, ServesUntilStoppedAndWritesTheTraceHeaderAndStartPosition) {
  const std::string trace =
      (std::filesystem::temp_directory_path() / "sim_command_test_trace.csv").string();
  SimCommandOptions o;
  o.listen = "127.0.0.1:0";  // any free port
  o.trace = trace;
  o.pause_confirm_ms = 250;
  const std::atomic<bool> stop{true};  // stopped before it starts: returns at once
  std::ostringstream log;
  const SimCommandResult r = run_sim(o, stop, log);
  EXPECT_TRUE(r.trace_ok);
  EXPECT_FALSE(r.spindle_on);
  EXPECT_EQ(r.pauses_confirmed, 0);
  EXPECT_NE(log.str().find("simulated machine on 127.0.0.1:"), std::string::npos) << log.str();
  EXPECT_NE(log.str().find("after 250 ms"), std::string::npos) << log.str();
  std::ifstream in(trace);
  std::string header, first;
  std::getline(in, header);
  std::getline(in, first);
  EXPECT_EQ(header, "t_ms,x_mm,y_mm,z_mm,pen,wall_ms");
  EXPECT_EQ(first.rfind("0,0.0000,0.0000,", 0), 0u) << first;  // machine time 0 at the origin
  std::filesystem::remove(trace);
}

}  // namespace
}  // namespace host::commands
