// Human-readable names for TMC428 datagrams ("W M1.v_max = 0x0007FF"), for record-file
// annotations, golden files and test failure messages. Datasheet register names.
#ifndef HAL_FAKE_MOTION_TMC428_DESCRIBE_H
#define HAL_FAKE_MOTION_TMC428_DESCRIBE_H

#include <cstdint>  // uint32_t
#include <string>   // std::string

#include "hal/fake/spi/spi_record.h"  // fake::SpiRecord

namespace fake {

// Register (or RAM table) name of a datagram's address byte, e.g. "M2.a_max", "SMGP",
// "drv_chain[2]" (the bench's names, drivers::tmc428::register_name).
std::string tmc428_register_name(uint8_t address_byte);

// "W M1.v_max = 0x0007FF" or "R M1.x_actual -> 0x000010 st=15".
std::string describe_tmc428_datagram(const SpiRecord& r);

}  // namespace fake

#endif  // HAL_FAKE_MOTION_TMC428_DESCRIBE_H
