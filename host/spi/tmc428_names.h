// TMC428 datagram meaning: register names from the address byte, decoded fields, status,
// from the register map shared with the driver (hal/drivers/tmc428/tmc428_map.h).
#ifndef HOST_SPI_TMC428_NAMES_H
#define HOST_SPI_TMC428_NAMES_H

#include <cstdint>  // uint32_t
#include <string>   // std::string
#include <utility>  // std::pair
#include <vector>   // std::vector

namespace host::spi {

// One decoded field: name and value (signed where the register is).
struct Field {
  std::string name;
  int64_t value;
  bool hex;          // print as hex (masks, raw codes)
  std::string text;  // symbolic value when there is one ("VELOCITY", "DAC_A5+NxM")
};

struct Tmc428Datagram {
  std::string reg;            // "M1.v_target", "SMGP", "drv_chain[3]", "ustep_table[0]"
  bool read = false;          // RW bit
  bool ram = false;           // RRS bit
  bool known = true;          // false for unused addresses
  std::vector<Field> fields;  // from MOSI data for writes, MISO data for reads
  bool fields_from_miso = false;
};

// Register name of an address byte (bits 31..24 of MOSI), RW bit ignored.
std::string tmc428_register_name(uint8_t address_byte);

// Decodes a 32-bit datagram. For reads the fields come from miso when has_miso.
Tmc428Datagram decode_tmc428(uint32_t mosi, bool has_miso, uint32_t miso);

// Names of the status bits set in a MISO status byte, MSB first: INT CDGW RS3 xEQt3 ...
std::vector<std::string> tmc428_status_bits(uint8_t status);

// "name=value name=0x.." for text output.
std::string fields_text(const std::vector<Field>& fields);

}  // namespace host::spi

#endif  // HOST_SPI_TMC428_NAMES_H
