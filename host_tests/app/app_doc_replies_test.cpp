// The replies printed in docs/protocol.md section 6 are the controller's: example command
// frames fed, byte for byte, to the Application in the state their text describes are
// answered with the example reply frames that follow them, byte for byte.
#include <gtest/gtest.h>

#include <fstream>  // std::ifstream
#include <sstream>  // std::istringstream
#include <string>   // std::string
#include <vector>   // std::vector

#include "host_tests/app/app_rig.h"

#ifndef ENGRAVER_SOURCE_DIR
#error "ENGRAVER_SOURCE_DIR must point at the repository top"
#endif

namespace fake_app {
namespace {

using Bytes = std::vector<uint8_t>;

// The example frame whose description starts with `what` ("#I seq 0:").
Bytes example(const std::string& what) {
  std::ifstream doc(std::string(ENGRAVER_SOURCE_DIR) + "/docs/protocol.md");
  std::string line;
  bool inside = false;
  while (std::getline(doc, line)) {
    if (line.rfind("```", 0) == 0) {
      inside = line.rfind("```frames", 0) == 0;
      continue;
    }
    const size_t semi = line.find("; ");
    if (!inside || semi == std::string::npos || line.compare(semi + 2, what.size(), what) != 0)
      continue;
    Bytes out;
    std::istringstream hex(line.substr(0, semi));
    std::string byte;
    while (hex >> byte) out.push_back(static_cast<uint8_t>(std::stoul(byte, nullptr, 16)));
    return out;
  }
  ADD_FAILURE() << "no example '" << what << "' in docs/protocol.md";
  return {};
}

// Feeds the bytes and returns what the controller sent back within a few milliseconds.
Bytes answer(AppRig& rig, const Bytes& frame) {
  rig.link.tx.clear();
  rig.link.rx.insert(rig.link.rx.end(), frame.begin(), frame.end());
  for (int ms = 0; ms < 5; ++ms) {
    rig.app.tick_1ms();
    rig.plant.step_1ms();
    rig.app.poll();
  }
  return rig.link.tx;
}

TEST(DocReplies, SessionStartAndAStoredFrameAreAnsweredAsPrinted) {
  AppRig rig;  // the reference machine, as the *I example describes it
  rig.run(5);
  EXPECT_EQ(answer(rig, example("#I seq 0:")), example("*I seq 0:"));
  EXPECT_EQ(answer(rig, example("#S seq 1:")), example("*O seq 1:"));
}

// The #C examples: acknowledged after the alarm notice printed before them; refused with
// bad_state when no alarm is active (the ordered stream expecting seq 19, as printed).
TEST(DocReplies, ClearAlarmIsAcknowledgedInAnAlarmAndRefusedWithoutOne) {
  AppRig rig;
  rig.run(5);
  proto::SessionCmd session{proto::kProtocolVersion};
  proto::Payload p;
  ASSERT_EQ(proto::encode(session, &p), proto::ErrorCode::kOk);
  uint8_t buf[proto::kMaxFrameBytes];
  const uint8_t n = proto::encode_frame(proto::kCommandStart, proto::kCmdSession, 18, p.bytes,
                                        p.length, buf, sizeof buf);
  answer(rig, Bytes(buf, buf + n));  // #I seq 18: the ordered stream expects 19
  rig.plant.fail_reads = true;       // a motion chip fault latches an alarm
  answer(rig, {});
  rig.plant.fail_reads = false;
  ASSERT_EQ(rig.app.state(), proto::MachineState::kAlarm);
  EXPECT_EQ(answer(rig, example("#C real-time seq 4:")), example("*O seq 4:"));
  ASSERT_EQ(rig.app.state(), proto::MachineState::kIdle);
  EXPECT_EQ(answer(rig, example("#C real-time seq 5:")), example("*E seq 5:"));
}

}  // namespace
}  // namespace fake_app
