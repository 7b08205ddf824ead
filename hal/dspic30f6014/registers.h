// dsPIC30F6014 special function registers used by the port: addresses and bit positions
// with the data sheet's names, from Microchip's p30F6014A.gld and p30F6014A.h (XC16) and the
// dsPIC30F Family Reference Manual (UART sec. 19, SPI sec. 20, Timers sec. 12). Only this folder
// names registers; drivers see hal/interfaces.
#ifndef HAL_DSPIC30F6014_REGISTERS_H
#define HAL_DSPIC30F6014_REGISTERS_H

#include "hal/dspic30f6014/sfr.h"  // Sfr16

namespace dspic {

// ---- CPU core (sec. 6 "Other core SFRs") ----
typedef Sfr16<0x0042> SR;      // IPL<2:0> = SR<7:5>
typedef Sfr16<0x0044> CORCON;  // IPL3 = bit 3
typedef Sfr16<0x0740> RCON;    // reset cause
namespace SRbits {
enum { IPL0 = 5, IPL1 = 6, IPL2 = 7 };
}
namespace RCONbits {
enum { POR = 0, BOR = 1, WDTO = 4, SWR = 6, EXTR = 7, TRAPR = 15 };
}

// ---- Interrupt controller (sec. 5) ----
typedef Sfr16<0x0080> INTCON1;
typedef Sfr16<0x0082> INTCON2;
typedef Sfr16<0x0084> IFS0;
typedef Sfr16<0x0086> IFS1;
typedef Sfr16<0x0088> IFS2;
typedef Sfr16<0x008C> IEC0;
typedef Sfr16<0x008E> IEC1;
typedef Sfr16<0x0090> IEC2;
typedef Sfr16<0x0094> IPC0;  // INT0IP<2:0> IC1IP<6:4> OC1IP<10:8> T1IP<14:12>
typedef Sfr16<0x0096> IPC1;
typedef Sfr16<0x0098> IPC2;  // SPI1IP<2:0> U1RXIP<6:4> U1TXIP<10:8> ADCIP<14:12>
typedef Sfr16<0x009C> IPC4;  // INT1IP<2:0> IC7IP<6:4> IC8IP<10:8> OC3IP<14:12>
namespace INTCON1bits {
enum { OSCFAIL = 1, STKERR = 2, ADDRERR = 3, MATHERR = 4, NSTDIS = 15 };
}
namespace INTCON2bits {
enum { INT0EP = 0, INT1EP = 1, ALTIVT = 15 };  // INTxEP 1: falling edge
}
namespace IFS1bits {  // and IEC1
enum { INT1IF = 0 };
}
namespace IEC1bits {
enum { INT1IE = 0 };
}
namespace IPC4bits {
enum { INT1IP = 0 };
}
namespace IFS0bits {  // and IEC0: the same positions with ...IE names
enum { T1IF = 3, SPI1IF = 8, U1RXIF = 9, U1TXIF = 10 };
}
namespace IEC0bits {
enum { T1IE = 3, SPI1IE = 8, U1RXIE = 9, U1TXIE = 10 };
}
namespace IPC0bits {  // shift of each 3-bit priority field
enum { INT0IP = 0, IC1IP = 4, OC1IP = 8, T1IP = 12 };
}
namespace IPC2bits {
enum { SPI1IP = 0, U1RXIP = 4, U1TXIP = 8, ADCIP = 12 };
}

// ---- Timer1 (sec. 4) ----
typedef Sfr16<0x0100> TMR1;
typedef Sfr16<0x0102> PR1;
typedef Sfr16<0x0104> T1CON;
namespace T1CONbits {
enum { TCS = 1, TSYNC = 2, TCKPS0 = 4, TCKPS1 = 5, TGATE = 6, TSIDL = 13, TON = 15 };
}

// ---- UART1 (sec. 2) ----
typedef Sfr16<0x020C> U1MODE;
typedef Sfr16<0x020E> U1STA;
typedef Sfr16<0x0210> U1TXREG;
typedef Sfr16<0x0212> U1RXREG;
typedef Sfr16<0x0214> U1BRG;
namespace U1MODEbits {
enum {
  STSEL = 0,
  PDSEL0 = 1,
  PDSEL1 = 2,
  ABAUD = 5,
  LPBACK = 6,
  WAKE = 7,
  ALTIO = 10,
  USIDL = 13,
  UARTEN = 15
};
}
namespace U1STAbits {
enum {
  URXDA = 0,
  OERR = 1,
  FERR = 2,
  PERR = 3,
  RIDLE = 4,
  ADDEN = 5,
  URXISEL0 = 6,
  URXISEL1 = 7,
  TRMT = 8,
  UTXBF = 9,
  UTXEN = 10,
  UTXBRK = 11,
  UTXISEL = 15
};
}

// ---- SPI1 (sec. 3) ----
typedef Sfr16<0x0220> SPI1STAT;
typedef Sfr16<0x0222> SPI1CON;
typedef Sfr16<0x0224> SPI1BUF;
namespace SPI1STATbits {
enum { SPIRBF = 0, SPITBF = 1, SPIROV = 6, SPISIDL = 13, SPIEN = 15 };
}
namespace SPI1CONbits {
enum {
  PPRE0 = 0,
  PPRE1 = 1,
  SPRE0 = 2,
  SPRE1 = 3,
  SPRE2 = 4,
  MSTEN = 5,
  CKP = 6,
  SSEN = 7,
  CKE = 8,
  SMP = 9,
  MODE16 = 10,
  DISSDO = 11,
  SPIFSD = 13,
  FRMEN = 14
};
}

// ---- A/D port configuration and I/O ports (sec. 6; there is no PORTE on the 6014) ----
typedef Sfr16<0x02A8> ADPCFG;  // bit n = 1: ANn/RBn digital
typedef Sfr16<0x02C0> TRISA;
typedef Sfr16<0x02C2> PORTA;
typedef Sfr16<0x02C6> TRISB;
typedef Sfr16<0x02C8> PORTB;
typedef Sfr16<0x02CA> LATB;
typedef Sfr16<0x02D2> TRISD;
typedef Sfr16<0x02D4> PORTD;
typedef Sfr16<0x02D6> LATD;
typedef Sfr16<0x02DE> TRISF;
typedef Sfr16<0x02E0> PORTF;
typedef Sfr16<0x02E2> LATF;

}  // namespace dspic

#endif  // HAL_DSPIC30F6014_REGISTERS_H
