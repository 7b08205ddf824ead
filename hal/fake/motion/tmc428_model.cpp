// Behavioural TMC428 + TMC246-chain model: register/RAM maps, ramps, pulses, switches,
// driver-chain read-back, in closed form per clock segment (fast enough for the simulator).
#include "hal/fake/motion/tmc428_model.h"  // declarations

#include <cstdlib>  // std::abs

namespace fake {

namespace {

const uint64_t kMask48 = (uint64_t{1} << 48) - 1;

// Sign-extends the low bits of a register value.
int32_t sext(uint32_t value, int bits) {
  const uint32_t sign = uint32_t{1} << (bits - 1);
  const uint32_t mask = (sign << 1) - 1;
  value &= mask;
  return (value & sign) ? (int32_t)(value | ~mask) : (int32_t)value;
}

// x_actual wraps at 24 bits like the chip's counter.
int32_t wrap24(int64_t x) {
  return sext((uint32_t)(x & 0xFFFFFF), 24);
}

enum : uint32_t {
  kModeMask = 3,
  kVelocity = 2,
  kHold = 3,
  kDisableStopL = 0x100,
  kDisableStopR = 0x200,
  kSoftStop = 0x400,
  kRefRnL = 0x800,
  kIntStop = 0x08,
  kIntLeftLow = 0x10,
  kIntRightLow = 0x20,
  kIntLeftHigh = 0x40,
  kIntRightHigh = 0x80,
  kContinuousUpdate = 0x10000,
  kRefMux = 0x100000,
  kMot1r = 0x200000
};

}  // namespace

Tmc428Model::Tmc428Model(uint32_t f_clk_hz) : f_clk_hz_(f_clk_hz) {
  // Whole-nanosecond clock periods (10 MHz: 100 ns): ticks by a multiply, not a division.
  if (f_clk_hz != 0 && 1000000000u % f_clk_hz == 0) {
    ns_per_tick_ = 1000000000u / f_clk_hz;
    tick_reciprocal_ = ns_per_tick_ > 1 ? UINT64_MAX / ns_per_tick_ + 1 : 0;
  }
  // TMC428 RAM is not initialised at power-on ([428DS] §7.3): a fixed pseudo-random fill.
  uint32_t seed = 0x428u;
  for (uint8_t& e : ram_) {
    seed = seed * 1103515245u + 12345u;
    e = (uint8_t)((seed >> 16) & 0x3F);
  }
}

// ---- time ---------------------------------------------------------------------------------

uint64_t Tmc428Model::ticks_for_ns(uint64_t ns) const {
  if (ns_per_tick_ != 0) {
    // From the current tick (ns is never before it): ceil(2^64 / period) times fewer than
    // 2^32 ns is the exact quotient. This runs after every SPI datagram of a simulation.
    const uint64_t since_ns = ns - now_ * ns_per_tick_;
    if (tick_reciprocal_ != 0 && since_ns < (uint64_t{1} << 32))
      return now_ + (uint64_t)(((unsigned __int128)since_ns * tick_reciprocal_) >> 64);
    return ns / ns_per_tick_;
  }
  return (uint64_t)((unsigned __int128)ns * f_clk_hz_ / 1000000000u);
}

uint64_t Tmc428Model::now_ns() const {
  return now_ns_;
}

void Tmc428Model::advance_ns(uint64_t ns) {
  advance_to_ns(now_ns_ + ns);
}

void Tmc428Model::advance_to_ns(uint64_t t_ns) {
  if (t_ns <= now_ns_) return;
  now_ns_ = t_ns;
  advance_to_tick(ticks_for_ns(t_ns));
}

void Tmc428Model::advance_to_tick(uint64_t t) {
  if (t <= now_) return;
  // A capture armed while nothing was due (no motion, no continuous update) may become due
  // once a motor moves.
  if ((chain_.cdgw || chain_.cover_waiting) && !chain_.scheduled) {
    for (int m = 0; m < kMotors; ++m) sync_motor_to(m, t);
    schedule_chain(now_);
  }
  if (chain_.scheduled && chain_.done_tick <= t) complete_chain_datagram();
  now_ = t;
}

void Tmc428Model::sync_motor_to(int m, uint64_t t) const {
  if (t <= motor_tick_[m]) return;
  advance_motor(m, motor_tick_[m], t);
  motor_tick_[m] = t;
  // A horizon bounds the motion from when it was worked out, so it holds for the same motion
  // integrated part of the way (an idle motor's, never, too); past it, work it out again.
  if (horizon_known_[m] && t >= horizon_[m].status_before) forget_quiet_horizon(m);
}

void Tmc428Model::sync_motors() const {
  for (int m = 0; m < kMotors; ++m) sync_motor(m);
}

// A motor not integrated since motor_tick_ makes at most one microstep per pulse clock (and
// one for the accumulator): by now at most S = (now >> ps) - (motor_tick >> ps) + 1. While
// S < D, D the microsteps to the nearest of x_target and the switches, its status bits are
// those it had: now < ((motor_tick >> ps) + D - 1) << ps, or now <= motor_tick. A motor at
// rest with no velocity to ramp to changes nothing until a write (advance_motor's idle
// case): never.
const Tmc428Model::QuietHorizon& Tmc428Model::quiet_horizon(int m) const {
  QuietHorizon& h = horizon_[m];
  if (horizon_known_[m]) return h;
  horizon_known_[m] = true;
  ++reach_checks_;
  const Motor& mo = motor_[m];
  const uint32_t mode = mo.ref_ramp & kModeMask;
  if (mo.v_q8 == 0 && (mode != kVelocity || sext(mo.v_target, 12) == 0)) {
    h.switch_before = UINT64_MAX;
    h.status_before = UINT64_MAX;
    return h;
  }
  const int64_t d_switch = switch_reach(m);
  const uint32_t d24 = (mo.x_target - (uint32_t)mo.x) & 0xFFFFFF;  // 24-bit wrap both ways
  const int64_t d_target = d24 < 0x800000 ? d24 : 0x1000000 - d24;
  const int64_t d_status = d_target < d_switch ? d_target : d_switch;
  const unsigned pulse_shift = 5 + ((mo.divisors >> 12) & 0xF);
  const uint64_t tick = motor_tick_[m];
  const uint64_t synced = tick + 1;  // now <= motor_tick_: nothing to integrate
  const uint64_t pulse = tick >> pulse_shift;
  h.status_before = synced;
  if (d_status >= 1) {
    const uint64_t b = (pulse + (uint64_t)d_status - 1) << pulse_shift;
    if (b > synced) h.status_before = b;
  }
  h.switch_before = synced;
  if (d_switch == INT64_MAX) {
    h.switch_before = UINT64_MAX;
  } else if (d_switch >= 1) {
    const uint64_t b = (pulse + (uint64_t)d_switch - 1) << pulse_shift;
    if (b > synced) h.switch_before = b;
  }
  return h;
}

// Microsteps until a switch of motor m may turn on: 0 for a forced-on or reached switch,
// INT64_MAX (never) for none, or none nearer than 2^30 microsteps.
int64_t Tmc428Model::switch_reach(int m) const {
  const Motor& mo = motor_[m];
  int64_t d_switch = INT64_MAX;
  if (left_exists(m)) {
    if (mo.left.forced_level > 0) d_switch = 0;
    if (mo.left.forced_level < 0 && mo.left.placed) {
      const int64_t d = (int64_t)mo.x - mo.left.position_usteps;
      if (d <= (int64_t{1} << 30) && d < d_switch) d_switch = d < 0 ? 0 : d;
    }
  }
  if (right_exists(m)) {
    if (mo.right.forced_level > 0) d_switch = 0;
    if (mo.right.forced_level < 0 && mo.right.placed) {
      const int64_t d = (int64_t)mo.right.position_usteps - mo.x;
      if (d <= (int64_t{1} << 30) && d < d_switch) d_switch = d < 0 ? 0 : d;
    }
  }
  return d_switch;
}

uint64_t Tmc428Model::switch_free_before(int m) const {
  if (switch_free_before_[m] != 0) return switch_free_before_[m];
  const int64_t d = switch_reach(m);
  const unsigned pulse_shift = 5 + ((motor_[m].divisors >> 12) & 0xF);
  uint64_t before = 1;  // nothing free: t1 > 0 always fails
  if (d == INT64_MAX) {
    before = UINT64_MAX;
  } else if (d >= 2) {
    before = ((motor_tick_[m] >> pulse_shift) + (uint64_t)d - 1) << pulse_shift;
    if (before == 0) before = 1;
  }
  switch_free_before_[m] = before;
  return before;
}

// ---- motors -------------------------------------------------------------------------------

bool Tmc428Model::left_exists(int m) const {
  if (smgp_ & kRefMux) return true;
  if (smgp_ & kMot1r) return m != 2;  // REF3 becomes motor 1's right switch ([428DS] Tab. 9-3)
  return true;
}

bool Tmc428Model::right_exists(int m) const {
  if (smgp_ & kRefMux) return true;
  return (smgp_ & kMot1r) && m == 0;
}

bool Tmc428Model::left_active(int m) const {
  const Motor& mo = motor_[m];
  if (!left_exists(m)) return false;
  if (mo.left.forced_level >= 0) return mo.left.forced_level != 0;
  return mo.left.placed && mo.x <= mo.left.position_usteps;
}

bool Tmc428Model::right_active(int m) const {
  const Motor& mo = motor_[m];
  if (!right_exists(m)) return false;
  if (mo.right.forced_level >= 0) return mo.right.forced_level != 0;
  return mo.right.placed && mo.x >= mo.right.position_usteps;
}

// dx_ref_tolerance excludes a window around 0 from the stop checks ([428DS] §8.15).
bool Tmc428Model::stop_allowed(int m, int32_t switch_pos) const {
  const uint32_t tol = motor_[m].dx_ref_tol;
  return tol == 0 || (uint32_t)std::abs((int64_t)switch_pos) >= tol;
}

// The velocity the ramp heads for, 8 fraction bits.
int32_t Tmc428Model::effective_target_q8(int m) const {
  const Motor& mo = motor_[m];
  const uint32_t mode = mo.ref_ramp & kModeMask;
  if (mode == kHold) return mo.v_q8;
  if (mode != kVelocity) return 0;  // RAMP/SOFT positioning not modelled: ramp to rest
  int32_t tgt = sext(mo.v_target, 12);
  const int32_t top = (int32_t)mo.v_max;
  if (tgt > top) tgt = top;
  if (tgt < -top) tgt = -top;
  if (tgt < 0 && !(mo.ref_ramp & kDisableStopL) && left_active(m) &&
      (mo.left.forced_level >= 0 || stop_allowed(m, mo.left.position_usteps))) {
    return 0;
  }
  if (tgt > 0 && !(mo.ref_ramp & kDisableStopR) && right_active(m) &&
      (mo.right.forced_level >= 0 || stop_allowed(m, mo.right.position_usteps))) {
    return 0;
  }
  return tgt * 256;
}

// Switch edge flags and the position latch after any change of position or switch input.
void Tmc428Model::note_switches(int m) const {
  Motor& mo = motor_[m];
  const bool l = left_active(m);
  const bool r = right_active(m);
  uint8_t f = 0;
  if (l && !mo.left.was_active) f |= kIntLeftHigh;
  if (!l && mo.left.was_active) f |= kIntLeftLow;
  if (r && !mo.right.was_active) f |= kIntRightHigh;
  if (!r && mo.right.was_active) f |= kIntRightLow;
  mo.int_flags = (uint8_t)((mo.int_flags | f) & mo.int_mask);
  if (mo.latch_pending) {
    const bool ref_right = (mo.ref_ramp & kRefRnL) != 0;
    const bool rising = ref_right ? (r && !mo.right.was_active) : (l && !mo.left.was_active);
    if (rising) {
      mo.x_latched = (uint32_t)mo.x & 0xFFFFFF;
      mo.latch_pending = false;
    }
  }
  mo.left.was_active = l;
  mo.right.was_active = r;
}

// Where a segment from t ends: at the next ramp clock (*ramp_edge) while ramping, else at t1
// (and the last ramp step is 0).
uint64_t Tmc428Model::segment_end(Motor& mo, bool ramping, uint64_t t, uint64_t t1,
                                  unsigned ramp_shift, uint64_t* ramp_edge) {
  if (!ramping) {
    mo.last_ramp = 0;
    return t1;
  }
  *ramp_edge = ((t >> ramp_shift) + 1) << ramp_shift;
  return *ramp_edge < t1 ? *ramp_edge : t1;
}

// One ramp clock: the velocity a_max nearer the target.
void Tmc428Model::ramp_clock(Motor& mo, int32_t tgt) {
  const int32_t diff = tgt - mo.v_q8;
  const int32_t a = (int32_t)mo.a_max;
  mo.last_ramp = diff > a ? a : (diff < -a ? -a : diff);
  mo.v_q8 += mo.last_ramp;
}

// No switch can change in (t, t1] (at most one microstep per pulse clock), so the ramp
// target is constant and no stop or flag can happen: closed-form segments between ramp
// clocks.
void Tmc428Model::advance_out_of_reach(int m, uint64_t t, uint64_t t1, unsigned pulse_shift,
                                       unsigned ramp_shift) const {
  Motor& mo = motor_[m];
  const uint32_t mode = mo.ref_ramp & kModeMask;
  // effective_target_q8() with no switch active (none is, out of reach), without its checks:
  // this runs for every moving motor after every datagram.
  int32_t tgt = 0;
  if (mode == kHold) {
    tgt = mo.v_q8;
  } else if (mode == kVelocity) {
    const int32_t top = (int32_t)mo.v_max;
    const int32_t v = sext(mo.v_target, 12);
    tgt = (v > top ? top : (v < -top ? -top : v)) * 256;
  }
  while (t < t1) {
    const bool ramping = mode != kHold && mo.v_q8 != tgt && mo.a_max > 0;
    uint64_t ramp_edge = 0;
    const uint64_t seg_end = segment_end(mo, ramping, t, t1, ramp_shift, &ramp_edge);
    const int32_t vi = mo.v_q8 / 256;
    if (vi != 0) {
      const uint64_t n = (seg_end >> pulse_shift) - (t >> pulse_shift);
      const uint64_t total = mo.pulse_acc + n * (uint64_t)std::abs(vi);
      mo.pulse_acc = (uint32_t)(total % 2048);
      const int64_t steps = (int64_t)(total / 2048);
      mo.x = wrap24((int64_t)mo.x + (vi > 0 ? steps : -steps));
    }
    if (ramping && seg_end == ramp_edge) ramp_clock(mo, tgt);
    t = seg_end;
  }
}

// Moving into an active stop switch: the stop flag, and a hard stop at once (*vi = 0); a
// soft stop ramps via the target.
void Tmc428Model::stop_at_switch(int m, int32_t* vi) const {
  Motor& mo = motor_[m];
  const uint32_t mode = mo.ref_ramp & kModeMask;
  const bool soft = (mo.ref_ramp & kSoftStop) != 0;
  if (mode != kHold && *vi != 0) {
    const bool into_left = *vi < 0 && !(mo.ref_ramp & kDisableStopL) && left_active(m) &&
                           (mo.left.forced_level >= 0 || stop_allowed(m, mo.left.position_usteps));
    const bool into_right =
        *vi > 0 && !(mo.ref_ramp & kDisableStopR) && right_active(m) &&
        (mo.right.forced_level >= 0 || stop_allowed(m, mo.right.position_usteps));
    if (into_left || into_right) {
      mo.int_flags = (uint8_t)((mo.int_flags | kIntStop) & mo.int_mask);
      if (!soft) {
        mo.v_q8 = 0;
        *vi = 0;
      }
    }
  }
}

// Microsteps until a stop switch turns on moving in dir; -1: none ahead.
int64_t Tmc428Model::steps_to_stop_switch(int m, int dir) const {
  const Motor& mo = motor_[m];
  int64_t dist = -1;
  if (dir < 0 && !(mo.ref_ramp & kDisableStopL) && left_exists(m) && mo.left.placed &&
      mo.left.forced_level < 0 && stop_allowed(m, mo.left.position_usteps) &&
      mo.x > mo.left.position_usteps) {
    dist = (int64_t)mo.x - mo.left.position_usteps;
  }
  if (dir > 0 && !(mo.ref_ramp & kDisableStopR) && right_exists(m) && mo.right.placed &&
      mo.right.forced_level < 0 && stop_allowed(m, mo.right.position_usteps) &&
      mo.x < mo.right.position_usteps) {
    dist = (int64_t)mo.right.position_usteps - mo.x;
  }
  return dist;
}

// Integrates one motor over (t0, t1]: ramp clock by ramp clock while the velocity changes,
// one closed-form segment when it does not; a switch hit splits a segment at its pulse.
void Tmc428Model::advance_motor(int m, uint64_t t0, uint64_t t1) const {
  Motor& mo = motor_[m];
  const uint32_t pd = (mo.divisors >> 12) & 0xF;
  const uint32_t rd = (mo.divisors >> 8) & 0xF;
  // Both clocks are powers of two: shifts, not 64-bit divisions, in this hot loop.
  const unsigned pulse_shift = 5 + pd, ramp_shift = 5 + rd;
  const uint32_t mode = mo.ref_ramp & kModeMask;
  uint64_t t = t0;
  // Idle: at rest with no velocity to ramp to. Nothing can change (no pulse, so no switch
  // edge either); most datagrams find most motors so (Z while cutting, all three at rest).
  if (mo.v_q8 == 0 && (mode != kVelocity || sext(mo.v_target, 12) == 0)) {
    mo.last_ramp = 0;
    return;
  }
  ++motor_integrations_;
  if (t1 >= switch_free_before(m)) forget_switch_free(m);  // worked out again from t0
  if (t1 < switch_free_before(m)) {
    advance_out_of_reach(m, t, t1, pulse_shift, ramp_shift);
    return;
  }
  while (t < t1) {
    int32_t vi = mo.v_q8 / 256;  // integer part, toward zero
    stop_at_switch(m, &vi);
    const int32_t tgt = effective_target_q8(m);
    const bool ramping = mode != kHold && mo.v_q8 != tgt && mo.a_max > 0;
    uint64_t ramp_edge = 0;
    const uint64_t seg_end = segment_end(mo, ramping, t, t1, ramp_shift, &ramp_edge);
    if (vi != 0) {
      const uint64_t n = (seg_end >> pulse_shift) - (t >> pulse_shift);  // pulse edges in (t, end]
      if (n != 0) {
        const uint64_t av = (uint64_t)std::abs(vi);
        const int dir = vi > 0 ? 1 : -1;
        const int64_t dist = steps_to_stop_switch(m, dir);
        uint64_t total = mo.pulse_acc + n * av;
        const uint64_t steps = total / 2048;
        if (dist > 0 && (uint64_t)dist <= steps) {
          // The pulse edge of the dist-th step: first j with acc + j v >= dist 2048.
          const uint64_t need = (uint64_t)dist * 2048 - mo.pulse_acc;
          const uint64_t j = (need + av - 1) / av;
          const uint64_t edge = ((t >> pulse_shift) + j) << pulse_shift;
          total = mo.pulse_acc + j * av;
          mo.pulse_acc = (uint32_t)(total - (uint64_t)dist * 2048);
          mo.x = wrap24((int64_t)mo.x + dir * dist);
          note_switches(m);
          // The ramp clock of this same tick still happens (before the stop check).
          if (ramping && edge == ramp_edge) ramp_clock(mo, tgt);
          t = edge;
          continue;  // the stop check at the top of the loop acts on the switch
        }
        mo.pulse_acc = (uint32_t)(total % 2048);
        if (steps != 0) {
          mo.x = wrap24((int64_t)mo.x + dir * (int64_t)steps);
          note_switches(m);
        }
      }
    }
    if (ramping && seg_end == ramp_edge) ramp_clock(mo, tgt);
    t = seg_end;
  }
}

// ---- driver chain -------------------------------------------------------------------------

// Bits per chain datagram from the RAM table: motor n's signals run to its NxM entry; the
// motor counter stops at LSMD ([428DS] §10). -1 if no NxM ends it (sends endlessly).
int Tmc428Model::chain_length_bits() const {
  const uint32_t lsmd = smgp_ & 3;
  if (lsmd == 3) return -1;  // not allowed ([429DS] §8.2.5)
  int i = 0;
  for (uint32_t m = 0; m <= lsmd; ++m) {
    for (;;) {
      if (i >= 64) return -1;
      const bool last = (ram_[i] & 0x20) != 0;
      ++i;
      if (last) break;
    }
  }
  return i;
}

uint64_t Tmc428Model::chain_datagram_ticks() const {
  const int bits = chain_length_bits();
  const uint64_t motors = (smgp_ & 3) + 1;
  const uint64_t clk2_div = (smgp_ >> 8) & 0xFF;
  return ((uint64_t)bits + motors + 2) * 2 * (clk2_div + 1);
}

// When the next chain datagram after `after` completes: at once while a motor steps,
// else at the next continuous-update request (every 32768 2^ramp_div ticks per motor).
void Tmc428Model::schedule_chain(uint64_t after) {
  sync_motors();  // whether one moves
  chain_.scheduled = false;
  if (chain_length_bits() < 0) return;
  bool moving = false;
  for (const Motor& mo : motor_) moving = moving || mo.v_q8 / 256 != 0;
  uint64_t start = 0;
  if (moving) {
    start = after;
  } else if (smgp_ & kContinuousUpdate) {
    start = UINT64_MAX;
    const uint32_t lsmd = smgp_ & 3;
    for (uint32_t m = 0; m <= lsmd && m < (uint32_t)kMotors; ++m) {
      // Motor m's requests are spread by m/(LSMD+1) of a period, so the combined rate is
      // the data sheet's f_clk sum(2^-ramp_div) / 32768 ([428DS] §9.7).
      const uint64_t period = uint64_t{32768} << ((motor_[m].divisors >> 8) & 0xF);
      const uint64_t phase = period * m / (lsmd + 1);
      const uint64_t shifted = after + period - phase;  // >= 0
      const uint64_t next = (shifted / period + 1) * period - period + phase;
      if (next < start) start = next;
    }
  } else {
    return;
  }
  chain_.done_tick = start + chain_datagram_ticks();
  chain_.scheduled = true;
}

// The chain (three 12-bit TMC246 shift registers) returns its statuses first - motor 1's
// driver is the last in the chain, so its bits arrive first - then the bits just sent.
void Tmc428Model::complete_chain_datagram() {
  const int n = chain_length_bits();
  chain_.scheduled = false;
  if (n < 0) return;
  unsigned __int128 received;
  if (chain_.sdi_stuck >= 0) {
    received = chain_.sdi_stuck ? ((unsigned __int128)1 << n) - 1 : 0;
  } else {
    const uint64_t s36 = ((uint64_t)(motor_[0].tmc246_status & 0xFFF) << 24) |
                         ((uint64_t)(motor_[1].tmc246_status & 0xFFF) << 12) |
                         (motor_[2].tmc246_status & 0xFFF);
    received = n <= 36 ? (s36 >> (36 - n)) : ((unsigned __int128)s36 << (n - 36));
  }
  chain_.words = (uint64_t)((((unsigned __int128)chain_.words << n) | received) & kMask48);
  chain_.cdgw = false;
  chain_.cover_waiting = false;
  ++chain_.datagrams;
}

void Tmc428Model::arm_chain_capture() {
  chain_.cdgw = true;
  schedule_chain(now_);
}

// ---- registers ----------------------------------------------------------------------------

uint32_t Tmc428Model::read_register(uint8_t addr) const {
  if (addr & 0x80) {  // RAM: two entries per address ([428DS] §10)
    const int pair = (addr >> 1) & 0x3F;
    return ((uint32_t)ram_[2 * pair + 1] << 8) | ram_[2 * pair];
  }
  const int smda = (addr >> 5) & 3;
  const int idx = (addr >> 1) & 0xF;
  if (smda == 3) return common_reg(idx);
  return reg(smda, idx);
}

uint32_t Tmc428Model::reg(int m, int idx) const {
  // Position, velocity, a_actual, the latch and the flags follow the motion.
  if (idx == 1 || idx == 5 || idx == 7 || idx == 10 || idx == 11 || idx == 14) sync_motor(m);
  const Motor& mo = motor_[m];
  switch (idx) {
    case 0:
      return mo.x_target;
    case 1:
      return (uint32_t)mo.x & 0xFFFFFF;
    case 2:
      return mo.v_min;
    case 3:
      return mo.v_max;
    case 4:
      return mo.v_target;
    case 5:
      return (uint32_t)(mo.v_q8 / 256) & 0xFFF;
    case 6:
      return mo.a_max;
    case 7:
      return (uint32_t)mo.last_ramp & 0xFFF;
    case 8:
      return mo.current;
    case 9:
      return mo.pmul_pdiv | 0x8000;  // pmul bit 7 forced to 1 ([428DS] §8.11)
    case 10:
      return mo.ref_ramp | (mo.latch_pending ? 0x10000u : 0u);
    case 11:
      return ((uint32_t)mo.int_mask << 8) | mo.int_flags;
    case 12:
      return mo.divisors;
    case 13:
      return mo.dx_ref_tol;
    case 14:
      return mo.x_latched;
    default:
      return 0;  // IDX 15 unused on the TMC428: reads 0
  }
}

uint32_t Tmc428Model::common_reg(int jdx) const {
  switch (jdx) {
    case 0:
      return (uint32_t)(chain_.words & 0xFFFFFF);
    case 1:
      return (uint32_t)(chain_.words >> 24);
    case 2: {  // cover_position reads back + 1, bit 23 = cover waiting ([428DS] §9.2)
      const uint32_t pos = ((chain_.cover_pos_len >> 8) + 1) & 0x3F;
      return (chain_.cover_waiting ? 0x800000u : 0u) | (pos << 8) | (chain_.cover_pos_len & 0x1F);
    }
    case 3:
      return chain_.cover_datagram;
    case 14:
      return switch_bits();
    case 15:
      return smgp_;
    default:
      return 0;
  }
}

// A write to the common registers (SMDA 3): the chain capture, cover datagram, global
// parameters.
void Tmc428Model::write_global_register(int idx, uint32_t data) {
  switch (idx) {
    case 0:
    case 1:
      arm_chain_capture();
      break;
    case 2:
      chain_.cover_pos_len = data & 0x3F1F;
      break;
    case 3:
      chain_.cover_datagram = data;
      chain_.cover_waiting = true;
      if (!chain_.scheduled) schedule_chain(now_);
      break;
    case 15:
      sync_motors();
      smgp_ = data & 0x31FFFF;
      for (int m = 0; m < kMotors; ++m) {
        note_switches(m);
        forget_quiet_horizon(m);
        forget_switch_free(m);
      }
      break;
    default:
      break;  // power_down (JDX 8), RO and unused addresses: no effect here
  }
}

// A write to motor m's registers (SMDA 0..2).
void Tmc428Model::write_motor_register(int m, int idx, uint32_t data) {
  // The driver writes every v_target every tick, mostly the value it holds (cruising, or 0
  // for a motor at rest): that changes nothing, so the motor need not be integrated now.
  if (idx == 4 && (data & 0xFFF) == motor_[m].v_target) return;
  sync_motor(m);
  // A horizon assumes no more than a microstep a pulse clock, whatever the velocity: a new
  // v_target keeps it unless it was an idle motor's (never).
  if (idx != 4 || horizon_[m].status_before == UINT64_MAX) forget_quiet_horizon(m);
  if (idx != 0 && idx != 4) forget_switch_free(m);  // x_target, v_target: no switch nearer
  Motor& mo = motor_[m];
  switch (idx) {
    case 0:
      mo.x_target = data;
      break;
    case 1:
      mo.x = sext(data, 24);
      note_switches(m);
      break;
    case 2:
      mo.v_min = data & 0x7FF;
      break;
    case 3:
      mo.v_max = data & 0x7FF;
      break;
    case 4:
      mo.v_target = data & 0xFFF;
      break;
    case 5:  // writable only in HOLD_MODE ([428DS] §8.6)
      if ((mo.ref_ramp & kModeMask) == kHold) mo.v_q8 = sext(data, 12) * 256;
      break;
    case 6:
      mo.a_max = data & 0x7FF;
      break;
    case 8:
      mo.current = data & 0x7777FF;
      break;
    case 9:
      mo.pmul_pdiv = data & 0xFF0F;
      break;
    case 10:
      mo.ref_ramp = data & 0xF03;
      break;
    case 11:  // mask written, flags cleared by 1s, masked flags forced to 0 (Tab. 8-6)
      mo.int_mask = (uint8_t)(data >> 8);
      mo.int_flags = (uint8_t)(mo.int_flags & ~data & mo.int_mask);
      break;
    case 12:
      mo.divisors = data & 0xFF07;
      break;
    case 13:
      mo.dx_ref_tol = data & 0xFFF;
      break;
    case 14:
      mo.latch_pending = true;
      break;
    default:
      break;  // a_actual RO, IDX 15 unused
  }
}

void Tmc428Model::write_register(uint8_t addr, uint32_t data) {
  data &= 0xFFFFFF;
  if (addr & 0x80) {
    const int pair = (addr >> 1) & 0x3F;
    ram_[2 * pair] = (uint8_t)(data & 0x3F);
    ram_[2 * pair + 1] = (uint8_t)((data >> 8) & 0x3F);
    return;
  }
  const int smda = (addr >> 5) & 3;
  const int idx = (addr >> 1) & 0xF;
  if (smda == 3) {
    write_global_register(idx, data);
    return;
  }
  write_motor_register(smda, idx, data);
}

// ---- SPI ----------------------------------------------------------------------------------

uint8_t Tmc428Model::switch_bits() const {
  uint8_t bits = 0;
  for (int m = 0; m < kMotors; ++m) {
    if (now_ >= quiet_horizon(m).switch_before) sync_motor(m);
    if (right_active(m)) bits |= (uint8_t)(1u << (2 * m));
    if (left_active(m)) bits |= (uint8_t)(2u << (2 * m));
  }
  return bits;
}

uint8_t Tmc428Model::status_byte() const {
  uint8_t s = now_ < motor_status_before_ ? motor_status_bits_ : motor_status_bits();
  if (chain_.cdgw || chain_.cover_waiting) s |= 0x40;
  return s;
}

// xEQt, the left switch and the interrupt of each motor, integrating only a motor that may
// have changed them; kept until the first motor's horizon.
uint8_t Tmc428Model::motor_status_bits() const {
  uint8_t s = 0;
  bool irq = false;
  uint64_t before = UINT64_MAX;
  for (int m = 0; m < kMotors; ++m) {
    if (now_ >= quiet_horizon(m).status_before) sync_motor(m);
    const Motor& mo = motor_[m];
    if (((uint32_t)mo.x & 0xFFFFFF) == mo.x_target) s |= (uint8_t)(0x01 << (2 * m));
    if (left_active(m)) s |= (uint8_t)(0x02 << (2 * m));
    irq = irq || (mo.int_flags & mo.int_mask) != 0;
    const uint64_t b = quiet_horizon(m).status_before;
    if (b < before) before = b;
  }
  if (irq) s |= 0x80;
  motor_status_bits_ = s;
  motor_status_before_ = before;
  return s;
}

uint32_t Tmc428Model::transfer32(uint32_t mosi) {
  const uint8_t addr = (uint8_t)(mosi >> 24);
  const bool read = (addr & 0x01) != 0;
  // The status shifts out first, before the datagram is complete ([428DS] §6.4); a write
  // answers data 0 ([429DS] §7.5 example), a read the register in the same transfer.
  uint32_t miso = (uint32_t)status_byte() << 24;
  if (read) {
    miso |= read_register(addr) & 0xFFFFFF;
  } else {
    write_register(addr, mosi & 0xFFFFFF);
  }
  log_.record(Datagram{now_ns_, mosi, miso});
  return miso;
}

// ---- setup and inspection -------------------------------------------------------------------

void Tmc428Model::set_switch_positions(int motor, int32_t left_usteps, int32_t right_usteps) {
  sync_motor(motor);
  Motor& mo = motor_[motor];
  mo.left.position_usteps = left_usteps;
  mo.right.position_usteps = right_usteps;
  mo.left.placed = true;
  mo.right.placed = true;
  note_switches(motor);
  forget_quiet_horizon(motor);
  forget_switch_free(motor);
}

void Tmc428Model::force_switch(int motor, bool right, int level) {
  sync_motor(motor);
  if (right) {
    motor_[motor].right.forced_level = level;
  } else {
    motor_[motor].left.forced_level = level;
  }
  note_switches(motor);
  forget_quiet_horizon(motor);
  forget_switch_free(motor);
}

void Tmc428Model::set_driver_status(int motor, uint16_t status12) {
  motor_[motor].tmc246_status = status12;
}

int32_t Tmc428Model::x_actual(int motor) const {
  sync_motor(motor);
  return motor_[motor].x;
}

int16_t Tmc428Model::v_actual(int motor) const {
  sync_motor(motor);
  return (int16_t)(motor_[motor].v_q8 / 256);
}

int32_t Tmc428Model::v_actual_q8(int motor) const {
  sync_motor(motor);
  return motor_[motor].v_q8;
}

uint8_t Tmc428Model::ram_entry(int index) const {
  return ram_[index & 0x7F];
}

}  // namespace fake
