// Port setup. TRIS bit 1 = input (the reset state), outputs written through LATx: dsPIC30F
// Family Reference Manual, section "I/O Ports"; addresses from Microchip's p30F6014A.gld.
#include "hal/dspic30f6014/ports.h"

#include "hal/dspic30f6014/pins.h"       // pin numbers
#include "hal/dspic30f6014/registers.h"  // ADPCFG, TRISx, LATx

namespace dspic {

void init_ports() {
  // No ADC in use: every ANn/RBn pin digital, or PORTB reads 0 (all panel contacts closed).
  ADPCFG::write(0xFFFF);

  // TMC428 nSCS_C on RB2: idle high, then output.
  LATB::set_bit<pins::kTmcCsBit>();
  TRISB::clear_bit<pins::kTmcCsBit>();

  // LCD: RD0..RD10 low (E low, write mode); spindle RD11 low (off); then outputs.
  // RD12..RD15 stay inputs.
  const uint16_t lcd_lines =
      (uint16_t)(pins::kLcdDataMask | bit(pins::kLcdRsBit) | bit(pins::kLcdRwBit) |
                 bit(pins::kLcdEBit) | bit(pins::kSpindleBit));
  LATD::modify(lcd_lines, 0);
  TRISD::modify(lcd_lines, 0);

  // UART1 TX idles high; SPI1 SCK idles high (CKP = 1); SDO1 low. U1RX, SDI1 inputs.
  LATF::modify(bit(pins::kSdo1Bit), (uint16_t)(bit(pins::kU1TxBit) | bit(pins::kSck1Bit)));
  TRISF::modify((uint16_t)(bit(pins::kU1TxBit) | bit(pins::kSck1Bit) | bit(pins::kSdo1Bit)),
                (uint16_t)(bit(pins::kU1RxBit) | bit(pins::kSdi1Bit)));
}

}  // namespace dspic
