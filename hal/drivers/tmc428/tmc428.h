// TMC428 motion controller with three TMC246 on its driver chain, behind hal::MotionAxes.
// Axis X/Y/Z = TMC428 motor 1/2/3 (SMDA 00/01/10). Velocity mode, automatic hard stop on
// the reference switches (six switches multiplexed, refmux), continuous driver update.
//
// Use:  drivers::Tmc428 chip(spi, config::default_machine_config());
//       if (chip.init() != drivers::Tmc428InitResult::kOk) -> alarm with the code;
//       then the MotionAxes calls (each is 3 datagrams; read_limits is 1).
// Not reentrant: all calls from one context (the 1 ms control tick, or init before it runs).
#ifndef HAL_DRIVERS_TMC428_TMC428_H
#define HAL_DRIVERS_TMC428_TMC428_H

#include <stdint.h>  // uint8_t, int32_t

#include "firmware/config/machine_config.h"   // config::MachineConfig
#include "hal/drivers/tmc428/tmc428_units.h"  // tmc428::AxisSettings
#include "hal/interfaces/motion_axes.h"       // hal::MotionAxes
#include "hal/interfaces/spi_master.h"        // hal::SpiMaster

namespace drivers {

// Outcome of Tmc428::init(); anything but kOk leaves the motors stopped (v_max = 0 where
// the chip answered at all) and the driver refusing motion commands.
enum class Tmc428InitResult : uint8_t {
  kOk = 0,
  kBadConfig = 1,         // the machine configuration gives no valid chip setting
  kNoResponse = 2,        // MISO stuck: every answer 0x00000000 or 0xFFFFFFFF (no chip/power)
  kRegisterReadback = 3,  // a written register read back different
  kRamReadback = 4,       // a RAM table entry read back different
  kChainTimeout = 5,      // no driver-chain datagram completed (CDGW stayed 1)
  kChainReadback = 6      // a TMC246 status lacks its always-1 bit 8: chain broken/unpowered
};

// A concrete driver: never deleted through a base pointer (no heap), so the host build's
// -Wnon-virtual-dtor is silenced here (GCC >= 5 only; XC16's GCC 4.5 lacks push/pop and is
// built without that warning).
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wnon-virtual-dtor"
#endif
class Tmc428 : public hal::MotionAxes {
 public:
  // Keeps references to both; computes nothing until init().
  Tmc428(hal::SpiMaster& spi, const config::MachineConfig& machine);

  // Proves the chip is there, loads RAM tables and registers, checks the driver chain.
  Tmc428InitResult init();
  bool ready() const { return ready_; }
  // Which axis/why when init() returned kBadConfig.
  tmc428::SettingsError settings_error() const { return settings_error_; }
  uint8_t settings_error_axis() const { return settings_error_axis_; }
  // Chip settings of an axis (valid after init() passed the configuration stage).
  const tmc428::AxisSettings& settings(uint8_t axis) const { return settings_[axis]; }
  // 12-bit TMC246 status word of an axis from the last chain read-back (TMC246B data sheet sec. 4).
  uint16_t driver_status(uint8_t axis) const { return driver_status_[axis]; }
  // Status byte of the last datagram answer ([428DS] §6.4).
  uint8_t last_status() const { return last_status_; }

  // Re-reads the three TMC246 status words through datagram_low/high_word ([428DS] §9.1).
  // False on timeout or a missing always-1 bit.
  bool read_driver_status();
  // Classifies one 12-bit TMC246 status word as a hal::DriverCheck (Ok/Fault/Undervoltage).
  static uint8_t classify_driver_status(uint16_t status12);
  // Reads and clears the interrupt flags of an axis (INT_STOP = stopped on a switch).
  bool take_interrupt_flags(uint8_t axis, uint8_t* flags);

  // hal::MotionAxes
  virtual bool read_actual_usteps(int32_t out[config::kAxisCount]);
  virtual bool write_velocity_units(const int16_t v[config::kAxisCount]);
  virtual bool read_velocity_units(int16_t out[config::kAxisCount]);
  virtual bool set_actual_usteps(const int32_t usteps[config::kAxisCount]);
  virtual bool read_limits(uint8_t* bits);
  virtual uint32_t usteps_per_s_per_unit_q16(uint8_t axis) const;
  virtual int16_t max_velocity_units(uint8_t axis) const;
  virtual uint16_t accel_units_per_ms(uint8_t axis) const;
  // The chain read-back of read_driver_status() split into steps of one datagram each:
  // re-arm the capture; read datagram_low_word until its answer shows CDGW clear (the chain
  // datagram can take tens of ms: no waiting here); read datagram_high_word and classify.
  // Open-load flags are ignored (they also show at speed: TMC246B data sheet sec. 4).
  virtual uint8_t poll_driver_check();

 private:
  uint32_t transfer(uint32_t mosi);
  uint32_t write_reg(uint8_t address, uint32_t data);
  bool read_reg(uint8_t address, uint32_t* data);
  // The signed field (its low `bits`) of one motor register, for every axis.
  bool read_axes(uint8_t reg, uint8_t bits, int32_t out[config::kAxisCount]);
  bool write_and_verify(uint8_t address, uint32_t data, uint32_t readback_mask);
  Tmc428InitResult check_presence();
  void stop_all();
  Tmc428InitResult load_ram();
  Tmc428InitResult configure_motors();
  Tmc428InitResult check_chain();
  bool fetch_chain_words(uint32_t* low, uint32_t* high);
  bool store_driver_status(uint32_t low, uint32_t high);

  hal::SpiMaster& spi_;
  const config::MachineConfig& machine_;
  tmc428::AxisSettings settings_[config::kAxisCount];
  // driver_status_ to settings_error_axis_: zeroed as one block by the constructor.
  uint16_t driver_status_[config::kAxisCount];
  uint16_t chain_poll_limit_;
  uint32_t check_low_word_;  // poll_driver_check(): datagram_low_word, awaiting the high word
  uint8_t check_step_;       // poll_driver_check(): CheckStep
  uint8_t last_status_;
  bool answer_stuck_;  // MISO word all 0s or all 1s seen (chip absent)
  bool ready_;
  tmc428::SettingsError settings_error_;
  uint8_t settings_error_axis_;
};
#if defined(__GNUC__) && __GNUC__ >= 5
#pragma GCC diagnostic pop
#endif

}  // namespace drivers

#endif  // HAL_DRIVERS_TMC428_TMC428_H
