// Names for TMC428 datagrams, from the register map the driver uses (tmc428_map.h).
#include "hal/fake/motion/tmc428_describe.h"  // declarations

#include "hal/drivers/tmc428/tmc428_map.h"  // register_name

#include <cstdio>  // std::snprintf

namespace fake {

std::string tmc428_register_name(uint8_t a) {
  char name[drivers::tmc428::kRegisterNameBytes];
  drivers::tmc428::register_name(a, name);
  return name;
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
