// Names for TMC428 datagrams ([428DS] Tab. 7-2 register names).
#include "hal/fake/motion/tmc428_describe.h"  // declarations

#include <cstdio>  // std::snprintf

namespace fake {

std::string tmc428_register_name(uint8_t a) {
  char buf[48];
  if (a & 0x80) {
    const int pair = (a >> 1) & 0x3F;
    const bool sine = pair >= 32;
    const int first = 2 * (pair & 31);
    std::snprintf(buf, sizeof buf, "RAM %s[%d,%d]", sine ? "sine" : "chain", first, first + 1);
    return buf;
  }
  static const char* const kMotorRegs[16] = {"x_target",
                                             "x_actual",
                                             "v_min",
                                             "v_max",
                                             "v_target",
                                             "v_actual",
                                             "a_max",
                                             "a_actual",
                                             "is_*/a_threshold",
                                             "pmul/pdiv",
                                             "ref_conf/ramp_mode",
                                             "interrupt_mask/flags",
                                             "pulse_div/ramp_div/usrs",
                                             "dx_ref_tolerance",
                                             "x_latched",
                                             "unused15"};
  static const char* const kCommonRegs[16] = {"datagram_low_word", "datagram_high_word",
                                              "cover_pos/len",     "cover_datagram",
                                              "unused4",           "unused5",
                                              "unused6",           "unused7",
                                              "power_down",        "unused9",
                                              "unused10",          "unused11",
                                              "unused12",          "unused13",
                                              "ref_switches",      "SMGP"};
  const int smda = (a >> 5) & 3;
  const int idx = (a >> 1) & 0xF;
  if (smda == 3) return kCommonRegs[idx];
  std::snprintf(buf, sizeof buf, "M%d %s", smda + 1, kMotorRegs[idx]);
  return buf;
}

std::string describe_tmc428_datagram(const SpiRecord& r) {
  const uint8_t a = (uint8_t)(r.mosi >> 24);
  char buf[96];
  if (a & 1) {
    std::snprintf(buf, sizeof buf, "R %s -> 0x%06X st=%02X", tmc428_register_name(a).c_str(),
                  (unsigned)(r.miso & 0xFFFFFF), (unsigned)(r.miso >> 24));
  } else {
    std::snprintf(buf, sizeof buf, "W %s = 0x%06X", tmc428_register_name(a).c_str(),
                  (unsigned)(r.mosi & 0xFFFFFF));
  }
  return buf;
}

}  // namespace fake
