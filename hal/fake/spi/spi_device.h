// A simulated SPI slave with its own virtual clock, as seen by fake::RecordingSpi.
// The TMC428 model (hal/fake/motion) is one; tests can write trivial ones (absent chip).
#ifndef HAL_FAKE_SPI_SPI_DEVICE_H
#define HAL_FAKE_SPI_SPI_DEVICE_H

#include <cstdint>  // uint32_t, uint64_t

namespace fake {

class SpiDevice {
 public:
  virtual ~SpiDevice() = default;
  // One 32-bit datagram at the device's current time: MOSI in, MISO out.
  virtual uint32_t transfer32(uint32_t mosi) = 0;
  // Device time since power-on, nanoseconds.
  virtual uint64_t now_ns() const = 0;
  // Lets device time pass (motion, driver chain).
  virtual void advance_ns(uint64_t ns) = 0;
};

// A device whose MISO line is stuck at one level: no chip, or no power (tests).
class StuckMisoDevice : public SpiDevice {
 public:
  explicit StuckMisoDevice(uint32_t miso) : miso_(miso) {}
  uint32_t transfer32(uint32_t) override { return miso_; }
  uint64_t now_ns() const override { return now_ns_; }
  void advance_ns(uint64_t ns) override { now_ns_ += ns; }

 private:
  uint32_t miso_;
  uint64_t now_ns_ = 0;
};

}  // namespace fake

#endif  // HAL_FAKE_SPI_SPI_DEVICE_H
