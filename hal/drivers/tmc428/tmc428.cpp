// TMC428 + TMC246-chain driver: init sequence ([428DS] §13) and the MotionAxes calls.
#include "hal/drivers/tmc428/tmc428.h"  // declarations

#include <string.h>  // memset

#include "hal/drivers/tmc428/tmc428_regs.h"    // addresses, datagrams
#include "hal/drivers/tmc428/tmc428_tables.h"  // RAM tables

namespace drivers {

using namespace tmc428;  // NOLINT: the register names are the datasheet's, kept short

namespace {

// Patterns for the presence check: complementary, so a stuck data line shows either way.
const uint32_t kProbeA = 0xA5A;
const uint32_t kProbeB = 0x5A5;
// Each datagram is at least 32 SCK periods of >= 8 f_clk (SPI <= f_clk / 8): 256 f_clk.
const uint32_t kMinClocksPerDatagram = 256;

// The registers configure_motors() writes per motor, in order, each read back through
// the mask of its fields: all of them but the interrupt flags (cleared by writing 1) and
// lp (read-only).
struct MotorRegister {
  uint8_t reg;
  uint32_t readback_mask;
};
const MotorRegister kMotorRegisters[] = {
    {kDivisors, kAllFields_kDivisors},
    {kVMin, kAllFields_kVMin},
    {kVMax, kAllFields_kVMax},
    {kAMax, kAllFields_kAMax},
    {kPmulPdiv, kAllFields_kPmulPdiv},
    {kCurrentScale, kAllFields_kCurrentScale},
    {kInterrupt, TMC428_FIELD_MASK(kField_kInterrupt_int_mask)},
    {kRefConfRampMode, kAllFields_kRefConfRampMode & ~(uint32_t)kLatchPending}};
enum { kMotorRegisterCount = sizeof kMotorRegisters / sizeof kMotorRegisters[0] };

// The two RAM tables: where each starts and its entries.
struct RamTable {
  uint8_t address;
  const uint8_t* entries;
};
const RamTable kRamTables[2] = {{kRamDriverChain, kDriverChainTable}, {kRamSineTable, kSineTable}};

}  // namespace

Tmc428::Tmc428(hal::SpiMaster& spi, const config::MachineConfig& machine)
    : spi_(spi), machine_(machine) {
  // driver_status_ up to settings_error_axis_ (declared in that order) start at zero
  // (SettingsError::kOk): one memset of the block, less code than a store per member.
  uint8_t* const first = reinterpret_cast<uint8_t*>(driver_status_);
  memset(first, 0, (size_t)(reinterpret_cast<uint8_t*>(&settings_error_axis_ + 1) - first));
  answer_stuck_ = true;
}

// One datagram; remembers the status byte and whether MISO looks stuck.
uint32_t Tmc428::transfer(uint32_t mosi) {
  const uint32_t miso = spi_.transfer32(mosi);
  last_status_ = answer_status(miso);
  if (miso != 0 && miso != 0xFFFFFFFFUL) answer_stuck_ = false;
  return miso;
}

uint32_t Tmc428::write_reg(uint8_t address, uint32_t data) {
  return transfer(write_datagram(address, data));
}

// Reads a register; false if the answer is all ones (no chip: SDO_C is never tri-stated
// on a TMC428, [428DS] §6.2, so a floating/pulled-up line means it is not there).
bool Tmc428::read_reg(uint8_t address, uint32_t* data) {
  const uint32_t miso = transfer(read_datagram(address));
  *data = datagram_data(miso);
  return miso != 0xFFFFFFFFUL;
}

bool Tmc428::write_and_verify(uint8_t address, uint32_t data, uint32_t readback_mask) {
  write_reg(address, data);
  uint32_t got = 0;
  if (!read_reg(address, &got)) return false;
  return (got & readback_mask) == (data & readback_mask);
}

Tmc428InitResult Tmc428::init() {
  ready_ = false;
  answer_stuck_ = true;
  if (machine_.spi_clock_hz == 0 || machine_.spi_clock_hz > machine_.tmc428_clock_hz / 8) {
    settings_error_ = SettingsError::kSpiTooFast;
    return Tmc428InitResult::kBadConfig;
  }
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    settings_error_ =
        compute_axis_settings(machine_.axis[a], machine_.tmc428_clock_hz, &settings_[a]);
    if (settings_error_ != SettingsError::kOk) {
      settings_error_axis_ = a;
      return Tmc428InitResult::kBadConfig;
    }
  }
  Tmc428InitResult r = check_presence();
  if (r != Tmc428InitResult::kOk) return r;
  stop_all();
  r = load_ram();
  if (r != Tmc428InitResult::kOk) return r;
  // SMGP: 3 drivers (LSMD 2), TMC24x polarities (all 0), clk2_div 7 (f_SCK_S = f_clk/16,
  // [429DS] §8.2.5.3), continuous update + refmux for the six multiplexed switches
  // ([428DS] §9.7). Written after the RAM tables so the chain never sends garbage.
  const uint32_t smgp = field_value(kField_kSmgp_lsmd, 2) | field_value(kField_kSmgp_clk2_div, 7) |
                        kSmgpContinuousUpdate | kSmgpRefMux;
  if (!write_and_verify(kSmgp, smgp, kAllFields_kSmgp)) return Tmc428InitResult::kRegisterReadback;
  r = check_chain();
  if (r != Tmc428InitResult::kOk) return r;
  r = configure_motors();
  if (r != Tmc428InitResult::kOk) return r;
  ready_ = true;
  return Tmc428InitResult::kOk;
}

// Write/read-back of dx_ref_tolerance (motor 1) with two complementary patterns, then 0.
// A register without motion effect, so a chip left running by a warm restart is not moved.
Tmc428InitResult Tmc428::check_presence() {
  const uint8_t reg = motor_reg(0, kDxRefTolerance);
  const bool a_ok = write_and_verify(reg, kProbeA, kAllFields_kDxRefTolerance);
  const bool b_ok = write_and_verify(reg, kProbeB, kAllFields_kDxRefTolerance);
  write_reg(reg, 0);
  if (answer_stuck_) return Tmc428InitResult::kNoResponse;
  if (!a_ok || !b_ok) return Tmc428InitResult::kRegisterReadback;
  return Tmc428InitResult::kOk;
}

// Stops whatever a warm restart left running: RAMP mode with v_max = 0 cannot move
// ([428DS] §8.1), v_target 0 so velocity mode later starts at rest, and pulse_div/ramp_div
// 0 (changing pulse_div is safe only in RAMP mode, §8.14; ramp_div 0 makes the continuous
// driver update fast for the chain check).
void Tmc428::stop_all() {
  // Every value written is 0 (kRampMode is 0).
  enum { kStopCount = 4 };
  static const uint8_t kStopRegisters[kStopCount] = {kVMax, kRefConfRampMode, kVTarget, kDivisors};
  for (uint8_t m = 0; m < config::kAxisCount; ++m) {
    for (uint8_t i = 0; i < kStopCount; ++i) {
      write_reg(motor_reg(m, kStopRegisters[i]), 0);
    }
  }
}

// Both RAM tables ([428DS] §13 steps 2-3; TMC428 RAM is random at power-on, §7.3), then
// read back (RW = 1 on RAM returns the same pair layout).
Tmc428InitResult Tmc428::load_ram() {
  bool same = true;
  for (uint8_t pass = 0; pass < 2; ++pass) {  // every pair written, then every pair read back
    for (uint8_t t = 0; t < 2; ++t) {
      const RamTable& table = kRamTables[t];
      for (uint8_t k = 0; k < kRamPairs; ++k) {
        const uint8_t address = (uint8_t)(table.address + 2 * k);
        const uint32_t data = ram_pair_data(table.entries[2 * k], table.entries[2 * k + 1]);
        if (pass == 0) {
          write_reg(address, data);
          continue;
        }
        uint32_t got = 0;
        if (!read_reg(address, &got) || (got & 0x3F3F) != data) same = false;
      }
    }
  }
  return same ? Tmc428InitResult::kOk : Tmc428InitResult::kRamReadback;
}

// Captures the next 48 bits the chain shifts back: write datagram_low_word (sets CDGW),
// poll until CDGW = 0, read both words ([428DS] §9.1, Trinamic tmc428_misc.c).
bool Tmc428::fetch_chain_words(uint32_t* low, uint32_t* high) {
  write_reg(kDatagramLowWord, 0);
  for (uint16_t i = 0; i < chain_poll_limit_; ++i) {
    const uint32_t miso = transfer(read_datagram(kDatagramLowWord));
    if (miso == 0xFFFFFFFFUL) return false;
    if ((answer_status(miso) & kStatusCdgw) == 0) {
      *low = datagram_data(miso);
      return read_reg(kDatagramHighWord, high);
    }
  }
  return false;
}

// Chain check while ramp_div = 0 on all motors: the continuous update then sends a chain
// datagram every 32768 / 3 f_clk ([428DS] §9.7); allow twice that.
Tmc428InitResult Tmc428::check_chain() {
  chain_poll_limit_ = (uint16_t)((2UL * 32768UL / 3UL) / kMinClocksPerDatagram + 16);
  uint32_t low = 0;
  uint32_t high = 0;
  if (!fetch_chain_words(&low, &high)) return Tmc428InitResult::kChainTimeout;
  return store_driver_status(low, high) ? Tmc428InitResult::kOk : Tmc428InitResult::kChainReadback;
}

// Per-motor registers ([428DS] §13 step 5), each read back. pulse_div is written while
// still in RAMP mode with v_max = 0 (§8.14); velocity mode and the switch stops last.
Tmc428InitResult Tmc428::configure_motors() {
  // After ramp_div grows the continuous update is slower: re-derive the poll bound for
  // read_driver_status(): period = 32768 / sum(2^-ramp_div) f_clk.
  uint32_t rate_sum = 0;  // sum of 2^(13 - ramp_div)
  for (uint8_t m = 0; m < config::kAxisCount; ++m)
    rate_sum += 1UL << (kMaxDiv - settings_[m].ramp_div);
  const uint32_t period = (32768UL << kMaxDiv) / rate_sum;
  const uint32_t polls = 2 * period / kMinClocksPerDatagram + 16;
  for (uint8_t m = 0; m < config::kAxisCount; ++m) {
    const AxisSettings& s = settings_[m];
    // In the order of kMotorRegisters.
    const uint32_t data[kMotorRegisterCount] = {
        divisors_data(s.pulse_div, s.ramp_div, s.usrs), s.v_min, s.v_max, s.a_max,
        pmul_pdiv_data(s.pmul, s.pdiv),
        current_scale_data(s.is_agtat, s.is_aleat, s.is_v0, s.a_threshold),
        // INT_STOP unmasked so a switch stop shows as INT in every status byte; write 1s
        // to clear stale flags (Tab. 8-6).
        field_value(kField_kInterrupt_int_mask, kIntStop) |
            TMC428_FIELD_MASK(kField_kInterrupt_int_flags),
        // ref_conf 0: stop on both switches, hard stop, left = reference ([428DS] Tab. 8-4).
        field_value(kField_kRefConfRampMode_ramp_mode, kVelocityMode)};
    for (uint8_t i = 0; i < kMotorRegisterCount; ++i) {
      if (!write_and_verify(motor_reg(m, kMotorRegisters[i].reg), data[i],
                            kMotorRegisters[i].readback_mask)) {
        return Tmc428InitResult::kRegisterReadback;
      }
    }
  }
  chain_poll_limit_ = (uint16_t)(polls > 0xFFFF ? 0xFFFF : polls);
  return Tmc428InitResult::kOk;
}

bool Tmc428::read_driver_status() {
  uint32_t low = 0;
  uint32_t high = 0;
  return fetch_chain_words(&low, &high) && store_driver_status(low, high);
}

// Motor 1's bits go out first and end in the last driver, whose status arrives first:
// motor 1 = high[11:0], motor 2 = low[23:12], motor 3 = low[11:0] ([429DS] Fig. 8.5).
// False when a status lacks TMC246 bit 8, which is always 1 ([246DS] §4).
bool Tmc428::store_driver_status(uint32_t low, uint32_t high) {
  driver_status_[0] = (uint16_t)(high & 0xFFF);
  driver_status_[1] = (uint16_t)((low >> 12) & 0xFFF);
  driver_status_[2] = (uint16_t)(low & 0xFFF);
  bool all_one = true;
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    if ((driver_status_[a] & 0x100) == 0) all_one = false;
  }
  return all_one;
}

// TMC246 status bits (TMC246B data sheet sec. 4, status word).
enum {
  kTmc246AlwaysOne = 0x100,
  kTmc246Overtemperature = 0x80,  // switched off
  kTmc246Undervoltage = 0x20,     // VS too low
  kTmc246OvercurrentHigh = 0x10,
  kTmc246OvercurrentB = 0x02,
  kTmc246OvercurrentA = 0x01,
  kTmc246FaultBits =
      kTmc246Overtemperature | kTmc246OvercurrentHigh | kTmc246OvercurrentB | kTmc246OvercurrentA
};

// The steps of poll_driver_check().
enum CheckStep { kCheckArm = 0, kCheckLowWord = 1, kCheckHighWord = 2 };

uint8_t Tmc428::classify_driver_status(uint16_t status12) {
  // A missing always-1 bit: the chain is broken or that driver has no logic supply.
  if ((status12 & kTmc246AlwaysOne) == 0) return hal::kDriverCheckFault;
  if (status12 & kTmc246FaultBits) return hal::kDriverCheckFault;
  if (status12 & kTmc246Undervoltage) return hal::kDriverCheckUndervoltage;
  return hal::kDriverCheckOk;
}

uint8_t Tmc428::poll_driver_check() {
  if (!ready_) return hal::kDriverCheckPending;
  if (check_step_ == kCheckArm) {
    write_reg(kDatagramLowWord, 0);  // CDGW = 1 until the next chain datagram is captured
    check_step_ = kCheckLowWord;
    return hal::kDriverCheckPending;
  }
  if (check_step_ == kCheckLowWord) {
    const uint32_t miso = transfer(read_datagram(kDatagramLowWord));
    if (miso != 0xFFFFFFFFUL && (answer_status(miso) & kStatusCdgw) == 0) {
      check_low_word_ = datagram_data(miso);
      check_step_ = kCheckHighWord;
    }
    return hal::kDriverCheckPending;
  }
  check_step_ = kCheckArm;
  uint32_t high = 0;
  if (!read_reg(kDatagramHighWord, &high)) return hal::kDriverCheckPending;
  store_driver_status(check_low_word_, high);  // a missing bit 8 is classified below
  uint8_t worst = hal::kDriverCheckOk;
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    const uint8_t c = classify_driver_status(driver_status_[a]);
    if (c == hal::kDriverCheckFault || worst == hal::kDriverCheckOk) worst = c;
  }
  return worst;
}

bool Tmc428::take_interrupt_flags(uint8_t axis, uint8_t* flags) {
  if (!ready_ || axis >= config::kAxisCount) return false;
  uint32_t data = 0;
  if (!read_reg(motor_reg(axis, kInterrupt), &data)) return false;
  *flags = (uint8_t)(data & 0xFF);
  // Writing 1 clears a flag; the mask (bits 15..8) is written back unchanged.
  write_reg(motor_reg(axis, kInterrupt), (data & 0xFF00) | *flags);
  return true;
}

bool Tmc428::read_axes(uint8_t reg, uint8_t bits, int32_t out[config::kAxisCount]) {
  const uint8_t above = (uint8_t)(32U - bits);  // shifted out, then the sign shifted in
  if (!ready_) return false;
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    uint32_t data = 0;
    if (!read_reg(motor_reg(a, reg), &data)) return false;
    out[a] = (int32_t)(data << above) >> above;
  }
  return true;
}

bool Tmc428::read_actual_usteps(int32_t out[config::kAxisCount]) {
  return read_axes(kXActual, TMC428_FIELD_WIDTH(kField_kXActual_x), out);
}

bool Tmc428::write_velocity_units(const int16_t v[config::kAxisCount]) {
  if (!ready_) return false;
  bool sane = true;
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    const int16_t top = (int16_t)settings_[a].v_max;
    int16_t value = v[a];
    if (value > top) value = top;
    if (value < -top) value = (int16_t)-top;
    const uint32_t data = field_value(kField_kVTarget_v, (uint32_t)(int32_t)value);
    if (write_reg(motor_reg(a, kVTarget), data) == 0xFFFFFFFFUL) sane = false;
  }
  return sane;
}

bool Tmc428::read_velocity_units(int16_t out[config::kAxisCount]) {
  int32_t v[config::kAxisCount];
  if (!read_axes(kVActual, TMC428_FIELD_WIDTH(kField_kVActual_v), v)) return false;
  for (uint8_t a = 0; a < config::kAxisCount; ++a) out[a] = (int16_t)v[a];  // 11 bits
  return true;
}

// Writes x_actual and x_target alike, so xEQt holds and a switch to RAMP mode stays put.
bool Tmc428::set_actual_usteps(const int32_t usteps[config::kAxisCount]) {
  if (!ready_) return false;
  bool sane = true;
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    const uint32_t x = field_value(kField_kXActual_x, (uint32_t)usteps[a]);
    if (write_reg(motor_reg(a, kXActual), x) == 0xFFFFFFFFUL) sane = false;
    if (write_reg(motor_reg(a, kXTarget), x) == 0xFFFFFFFFUL) sane = false;
  }
  return sane;
}

// Reference switch register (JDX 14): r1 bit 0, l1 bit 1, r2 bit 2 ... ([428DS] §9.6).
bool Tmc428::read_limits(uint8_t* bits) {
  if (!ready_) return false;
  uint32_t data = 0;
  if (!read_reg(kRefSwitches, &data)) return false;
  uint8_t out = 0;
  for (uint8_t a = 0; a < config::kAxisCount; ++a) {
    if (data & (2u << (2 * a))) out |= (uint8_t)(hal::kLimitXLeft << (2 * a));
    if (data & (1u << (2 * a))) out |= (uint8_t)(hal::kLimitXRight << (2 * a));
  }
  *bits = out;
  return true;
}

uint32_t Tmc428::usteps_per_s_per_unit_q16(uint8_t axis) const {
  return axis < config::kAxisCount ? settings_[axis].usteps_per_s_per_unit_q16 : 0;
}

int16_t Tmc428::max_velocity_units(uint8_t axis) const {
  return axis < config::kAxisCount ? (int16_t)settings_[axis].v_max : 0;
}

uint16_t Tmc428::accel_units_per_ms(uint8_t axis) const {
  return axis < config::kAxisCount ? settings_[axis].accel_units_per_ms : 0;
}

}  // namespace drivers
