// hal::SpiMaster for host builds: forwards each 32-bit datagram to a simulated device (the
// TMC428 model) and records (time, MOSI, MISO). Datagram timing follows the configured SPI
// clock and the TMC428 timing table ([428DS] Tab. 6-1), so the recording can be written as
// a VCD (vcd_writer.h) and as the text record file (spi_record.h).
//
// Use:  fake::Tmc428Model chip;  fake::RecordingSpi spi(chip, 1250000);
//       drivers::Tmc428 driver(spi, cfg);  driver.init();  spi.records() ...
#ifndef HAL_FAKE_SPI_RECORDING_SPI_H
#define HAL_FAKE_SPI_RECORDING_SPI_H

#include <cstdint>  // uint32_t
#include <vector>   // std::vector

#include "hal/fake/spi/spi_device.h"    // fake::SpiDevice
#include "hal/fake/spi/spi_record.h"    // fake::SpiRecord, fake::SpiTiming
#include "hal/interfaces/spi_master.h"  // hal::SpiMaster

namespace fake {

class RecordingSpi : public hal::SpiMaster {
 public:
  // device_clock_hz: the slave's clock (TMC428 f_clk) for the 3-CLK setup/hold minimums.
  RecordingSpi(SpiDevice& device, uint32_t spi_clock_hz, uint32_t device_clock_hz = 10000000);

  // hal::SpiMaster: records at the device's current time, then (by default) lets the
  // device's time pass by one datagram period, as the real bus would.
  uint32_t transfer32(uint32_t mosi) override;

  // Off: transfers take no device time (the caller advances the device itself).
  void set_advance_device(bool on) { advance_device_ = on; }
  // Off: transfers are not recorded (long simulations).
  void set_recording(bool on) { recording_ = on; }
  const std::vector<SpiRecord>& records() const { return records_; }
  void clear() { records_.clear(); }
  const SpiTiming& timing() const { return timing_; }
  uint32_t transfers() const { return transfers_; }

 private:
  SpiDevice& device_;
  SpiTiming timing_;
  std::vector<SpiRecord> records_;
  bool advance_device_ = true;
  bool recording_ = true;
  uint32_t transfers_ = 0;
};

}  // namespace fake

#endif  // HAL_FAKE_SPI_RECORDING_SPI_H
