// Register access for linking the dsPIC firmware image on the AVR proxy: reads return 0 and
// writes are dropped (the image is linked and measured, never run).
#include "hal/dspic30f6014/sfr.h"  // dspic::host::sfr_*

namespace dspic {
namespace host {

uint16_t sfr_read(uint16_t) {
  return 0;
}
void sfr_write(uint16_t, uint16_t) {}
void sfr_write_low_byte(uint16_t, uint8_t) {}
void sfr_set_bit(uint16_t, uint8_t) {}
void sfr_clear_bit(uint16_t, uint8_t) {}
void delay_cycles(uint32_t) {}

}  // namespace host
}  // namespace dspic
