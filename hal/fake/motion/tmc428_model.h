// Behavioural model of a TMC428 with three TMC246 on its driver chain, for host tests and
// the simulator. Answers every 32-bit datagram like the chip ([428DS] §6.4: status byte +
// register data of the same transfer), keeps the register and RAM maps with the data sheet's
// power-on values, ramps and integrates the three motors in virtual time, stops them on
// reference switches at configurable positions, and fills datagram_low/high_word from
// simulated TMC246 status words.
//
// Use:
//   fake::Tmc428Model chip;                 // 10 MHz clock, power-on state
//   chip.set_switch_positions(0, 0, 760320); // motor 1: left switch at 0, right at +760320
//   fake::RecordingSpi spi(chip, 1250000);   // hal::SpiMaster for the driver
//   ... drivers::Tmc428 init / MotionAxes calls ...
//   chip.advance_us(1000);                   // 1 ms of machine time (cheap: closed form)
//
// Timing model (all in f_clk ticks from power-on, [428DS] §8.14):
//   - pulse clock every 32 * 2^pulse_div ticks: an accumulator adds |v_actual| (integer
//     part) and makes a microstep each time it passes 2048 -> R = f_clk v / (2^pd 2048 32);
//   - ramp clock every 32 * 2^ramp_div ticks: the 8-fraction-bit velocity moves a_max/256
//     toward the target (VELOCITY_MODE: v_target clipped to +-v_max);
//   - driver chain: a datagram every 32768 * 2^ramp_div ticks per motor with continuous
//     update, and at once while a motor moves; each lasts (sum(bits+1)+2) * 2 (clk2_div+1).
// Simplifications (docs/tmc428.md): RAMP/SOFT mode positioning is not modelled (the motor
// ramps to rest), a_actual reads the last ramp step (no smoothing), cover datagrams complete
// with the next chain datagram but change nothing, power_down is ignored, dx_ref_tolerance
// suppresses switch stops for switches placed inside |x| < tolerance.
#ifndef HAL_FAKE_MOTION_TMC428_MODEL_H
#define HAL_FAKE_MOTION_TMC428_MODEL_H

#include <cstddef>  // size_t
#include <cstdint>  // uint32_t
#include <vector>   // std::vector

#include "hal/fake/spi/spi_device.h"  // fake::SpiDevice

namespace fake {

class Tmc428Model : public SpiDevice {
 public:
  static constexpr int kMotors = 3;
  static constexpr uint16_t kTmc246StatusDefault = 0xF00;  // LD = 7, always-1 bit 8, no fault

  // One datagram as the model saw it.
  struct Datagram {
    uint64_t time_ns;
    uint32_t mosi;
    uint32_t miso;
  };

  explicit Tmc428Model(uint32_t f_clk_hz = 10000000);

  // SpiDevice: one datagram at the current time.
  uint32_t transfer32(uint32_t mosi) override;
  uint64_t now_ns() const override;
  void advance_ns(uint64_t ns) override;
  // Virtual time: advance by microseconds, or up to an absolute time (no-op if past it).
  void advance_us(uint32_t us) { advance_ns((uint64_t)us * 1000u); }
  void advance_to_ns(uint64_t t_ns);
  uint64_t now_ticks() const { return now_; }

  // Reference switches of a motor (0..2): left active while x_actual <= left_usteps, right
  // active while x_actual >= right_usteps. Default: none (never active).
  void set_switch_positions(int motor, int32_t left_usteps, int32_t right_usteps);
  // Forces a switch input regardless of position (-1 = follow position, 0 = off, 1 = on).
  void force_switch(int motor, bool right, int level);
  // 12-bit status word the TMC246 of a motor shifts back (bit 8 must be 1 on a real one).
  void set_driver_status(int motor, uint16_t status12);
  // SDI_S (chain return line): -1 normal, 0/1 stuck (chain broken, pulled down/up).
  void set_chain_sdi_stuck(int level) { chain_.sdi_stuck = level; }

  // Inspection.
  int32_t x_actual(int motor) const;       // 24-bit sign-extended
  int16_t v_actual(int motor) const;       // integer part, -2047..2047
  int32_t v_actual_q8(int motor) const;    // with 8 fraction bits
  uint32_t reg(int motor, int idx) const;  // what a read of the register returns
  uint32_t common_reg(int jdx) const;      // SMDA = 11 register as read
  uint8_t ram_entry(int index) const;      // 0..127 (0..63 chain, 64..127 sine)
  uint8_t status_byte() const;             // what the next answer's bits 31..24 are
  uint8_t switch_bits() const;             // the 0x7C register: r1 l1 r2 l2 r3 l3
  uint32_t chain_datagrams() const { return chain_.datagrams; }  // captured answers
  // Times a moving motor was integrated up to a later time (what lazy stepping saves).
  uint64_t motor_integrations() const { return motor_integrations_; }
  // Times the model worked out how far a motor is from x_target and its switches (for the
  // status byte and the switch register): once after each change, not per datagram.
  uint64_t reach_checks() const { return reach_checks_; }
  const std::vector<Datagram>& log() const { return log_.entries; }
  void clear_log() { log_.entries.clear(); }
  // Off: datagrams are not logged (long simulations; RecordingSpi can record instead).
  void set_logging(bool on) { log_.on = on; }
  // The log stops growing at this many entries (default 200000, ~5 MB); later datagrams
  // are only counted, so a simulation left logging cannot eat the memory.
  void set_log_limit(size_t entries) { log_.limit = entries; }
  uint64_t log_dropped() const { return log_.dropped; }
  uint32_t f_clk_hz() const { return f_clk_hz_; }

 private:
  // A motor's reference switch input: where it is (active at or beyond that position), a
  // forced level, and the level last noted (for the edge flags and the position latch).
  struct ReferenceSwitch {
    bool placed = false;          // a position was set: else never active by position
    int32_t position_usteps = 0;  // left: active while x <= it; right: while x >= it
    int forced_level = -1;        // -1 follow the position, 0 off, 1 on
    bool was_active = false;
  };
  struct Motor {
    uint32_t x_target = 0;
    int32_t x = 0;  // x_actual (wraps at 24 bits on read)
    uint32_t v_min = 0, v_max = 0, v_target = 0, a_max = 0;
    uint32_t current = 0, pmul_pdiv = 0, ref_ramp = 0, divisors = 0, dx_ref_tol = 0;
    uint8_t int_mask = 0, int_flags = 0;
    bool latch_pending = false;
    uint32_t x_latched = 0;
    int32_t v_q8 = 0;        // internal velocity, 8 fraction bits
    int32_t last_ramp = 0;   // last ramp step (a_actual)
    uint32_t pulse_acc = 0;  // 0..2047
    ReferenceSwitch left = {false, INT32_MIN};
    ReferenceSwitch right = {false, INT32_MAX};
    uint16_t tmc246_status = kTmc246StatusDefault;
  };
  // The driver chain and the cover datagram ([428DS] §9): what SDI_S shifted in, a pending
  // capture or cover datagram, and when the next chain datagram completes.
  struct DriverChain {
    uint64_t words = 0;  // 48-bit shift register from SDI_S
    bool cdgw = false;   // datagram_low/high_word not refreshed yet
    bool cover_waiting = false;
    uint32_t cover_pos_len = 0, cover_datagram = 0;
    bool scheduled = false;
    uint64_t done_tick = 0;
    uint32_t datagrams = 0;  // completed (captured answers)
    int sdi_stuck = -1;      // SDI_S: -1 normal, 0/1 stuck
  };
  // The datagrams the model answered, up to a limit; later ones are only counted.
  struct DatagramLog {
    std::vector<Datagram> entries;
    bool on = true;
    size_t limit = 200000;
    uint64_t dropped = 0;
    void record(const Datagram& d) {
      if (!on) return;
      if (entries.size() < limit) {
        entries.push_back(d);
      } else {
        ++dropped;
      }
    }
  };

  uint32_t read_register(uint8_t addr) const;
  void write_register(uint8_t addr, uint32_t data);
  void write_global_register(int idx, uint32_t data);
  void write_motor_register(int m, int idx, uint32_t data);
  void advance_to_tick(uint64_t t);
  // Motors are integrated lazily (exactly: the integration of (t0, t2] equals that of
  // (t0, t1] then (t1, t2]): up to now when something reads or changes one, not after
  // every datagram. The const inspection functions bring a motor up to date too.
  void sync_motor(int m) const { sync_motor_to(m, now_); }
  void sync_motor_to(int m, uint64_t t) const;
  void sync_motors() const;
  // The first ticks at which motor m, as integrated up to motor_tick_, may have turned a
  // switch on or off (switch_before) or reached x_target or a switch (status_before): until
  // then its switch or status bits are those it had, without integrating it. Worked out
  // after each change to the motor, so a datagram's status byte is a compare per motor.
  struct QuietHorizon {
    uint64_t switch_before;
    uint64_t status_before;
  };
  const QuietHorizon& quiet_horizon(int m) const;
  void forget_quiet_horizon(int m) const {
    horizon_known_[m] = false;
    motor_status_before_ = 0;
  }
  uint8_t motor_status_bits() const;
  // No switch of motor m can turn on or off before this tick (the reach at at most one
  // microstep per pulse clock, from when it was worked out): integration needs no switch
  // checks. Unlike the horizons it holds across integration and velocity writes; 0 unknown.
  uint64_t switch_free_before(int m) const;
  void forget_switch_free(int m) const { switch_free_before_[m] = 0; }
  int64_t switch_reach(int m) const;
  void advance_motor(int m, uint64_t t0, uint64_t t1) const;
  void advance_out_of_reach(int m, uint64_t t, uint64_t t1, unsigned pulse_shift,
                            unsigned ramp_shift) const;
  void stop_at_switch(int m, int32_t* vi) const;
  int64_t steps_to_stop_switch(int m, int dir) const;
  static void ramp_clock(Motor& mo, int32_t tgt);
  static uint64_t segment_end(Motor& mo, bool ramping, uint64_t t, uint64_t t1, unsigned ramp_shift,
                              uint64_t* ramp_edge);
  int32_t effective_target_q8(int m) const;
  bool left_active(int m) const;
  bool right_active(int m) const;
  bool left_exists(int m) const;
  bool right_exists(int m) const;
  bool stop_allowed(int m, int32_t switch_pos) const;
  void note_switches(int m) const;
  void arm_chain_capture();
  void schedule_chain(uint64_t after);
  void complete_chain_datagram();
  int chain_length_bits() const;  // total bits per chain datagram, -1 if endless
  uint64_t chain_datagram_ticks() const;
  uint64_t ticks_for_ns(uint64_t ns) const;

  uint32_t f_clk_hz_;
  uint64_t ns_per_tick_ = 0;      // 0: the clock period is no whole number of ns
  uint64_t tick_reciprocal_ = 0;  // ceil(2^64 / ns_per_tick_), 0 for a 1 ns period
  uint64_t now_ = 0;              // ticks
  uint64_t now_ns_ = 0;           // exact ns clock the ticks derive from
  mutable Motor motor_[kMotors];  // integrated up to motor_tick_ (lazily, see sync)
  mutable uint64_t motor_tick_[kMotors] = {};
  mutable uint64_t motor_integrations_ = 0;
  mutable QuietHorizon horizon_[kMotors] = {};
  mutable bool horizon_known_[kMotors] = {};
  // The status byte's motor bits (all but cdgw), the same for every answer before
  // motor_status_before_ (the motors' nearest horizon; 0 after any change).
  mutable uint8_t motor_status_bits_ = 0;
  mutable uint64_t motor_status_before_ = 0;
  mutable uint64_t switch_free_before_[kMotors] = {};
  mutable uint64_t reach_checks_ = 0;
  uint8_t ram_[128];
  uint32_t smgp_ = 0x000F00;  // clk2_div = 15 at power-on ([428DS] §6.1)
  DriverChain chain_;
  DatagramLog log_;
};

}  // namespace fake

#endif  // HAL_FAKE_MOTION_TMC428_MODEL_H
