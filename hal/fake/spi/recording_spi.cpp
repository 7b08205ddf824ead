// Recording SPI master: forwards datagrams to a simulated device and logs them.
#include "hal/fake/spi/recording_spi.h"  // declarations

namespace fake {

RecordingSpi::RecordingSpi(SpiDevice& device, uint32_t spi_clock_hz, uint32_t device_clock_hz)
    : device_(device), timing_(spi_timing(spi_clock_hz, device_clock_hz)) {}

uint32_t RecordingSpi::transfer32(uint32_t mosi) {
  const uint64_t t = device_.now_ns();
  const uint32_t miso = device_.transfer32(mosi);
  if (recording_) records_.push_back(SpiRecord{t, mosi, miso});
  ++transfers_;
  if (advance_device_) device_.advance_ns(timing_.datagram_ns());
  return miso;
}

}  // namespace fake
