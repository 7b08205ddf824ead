// Board wiring: which dsPIC30F6014 pin does what (docs/flashing.md has the same table).
//   RF2 U1RX <- XPort TX       RF3 U1TX -> XPort RX            (UART1, ALTIO = 0)
//   RF6 SCK1 -> TMC428 SCK_C   RF7 SDI1 <- SDO_C   RF8 SDO1 -> SDI_C
//   RB2      -> TMC428 nSCS_C (GPIO chip select, idles high)
//   RD0..RD7 <-> LCD DB0..DB7  RD8 -> LCD RS   RD9 -> LCD R/W   RD10 -> LCD E
//   RD11     -> spindle switch (active high, off at reset)
//   RB8..RB14 <- panel contacts to GND (active low, external pull-ups): joystick left,
//   right, down, up, Z button, confirm, clear -- the order of hal::InputBits.
//   RB6/RB7 stay free for in-circuit programming (PGC/PGD).
//   RA12 INT1 <- probe: the clip on the copper blank, pulled up to 5 V (10 kOhm); the clamped
//   tool (spindle frame at GND) touching the copper pulls it low (active low, falling edge).
//   Why not a TMC428 reference input: all three carry the six multiplexed limit switches,
//   and an input there is read over SPI and stops the axis on its own.
#ifndef HAL_DSPIC30F6014_PINS_H
#define HAL_DSPIC30F6014_PINS_H

#include <stdint.h>  // uint8_t, uint16_t

namespace dspic {
namespace pins {

enum {
  kU1RxBit = 2,           // RF2
  kU1TxBit = 3,           // RF3
  kSck1Bit = 6,           // RF6
  kSdi1Bit = 7,           // RF7
  kSdo1Bit = 8,           // RF8
  kTmcCsBit = 2,          // RB2
  kLcdDataMask = 0x00FF,  // RD0..RD7
  kLcdRsBit = 8,          // RD8
  kLcdRwBit = 9,          // RD9
  kLcdEBit = 10,          // RD10
  kSpindleBit = 11,       // RD11
  kPanelFirstBit = 8,     // RB8 = hal::kJoyLeft ... RB14 = hal::kButtonClear
  kPanelMask = 0x7F00,    // RB8..RB14
  kProbeBit = 12          // RA12 = INT1
};

}  // namespace pins
}  // namespace dspic

#endif  // HAL_DSPIC30F6014_PINS_H
