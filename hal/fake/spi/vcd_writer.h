// Writes recorded SPI datagrams as a Value Change Dump with the wires CS, SCK, MOSI, MISO
// (SPI mode 3: SCK idles high, both lines change after SCK falls and are sampled on the
// rising edge; CS active low), which PulseView and sigrok-cli open, e.g.
//   sigrok-cli -I vcd -i init.vcd -P spi:clk=SCK:mosi=MOSI:miso=MISO:cs=CS:cpol=1:cpha=1:
//     wordsize=32 -A spi=mosi-data
// Timescale 1 ns. The dump starts 1 us before the first datagram (all lines idle); a
// datagram starts at its recorded time, or later if the previous one plus the minimum CS
// high time has not ended yet.
#ifndef HAL_FAKE_SPI_VCD_WRITER_H
#define HAL_FAKE_SPI_VCD_WRITER_H

#include <iosfwd>  // std::ostream
#include <vector>  // std::vector

#include "hal/fake/spi/spi_record.h"  // fake::SpiRecord, fake::SpiTiming

namespace fake {

// Returns false on a stream error.
bool write_spi_vcd(std::ostream& out, const std::vector<SpiRecord>& records,
                   const SpiTiming& timing);

}  // namespace fake

#endif  // HAL_FAKE_SPI_VCD_WRITER_H
