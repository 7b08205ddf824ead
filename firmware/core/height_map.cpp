// Height map: grid storage and fixed-point bilinear interpolation (see height_map.h).
#include "firmware/core/height_map.h"

#include "firmware/core/divide.h"       // div_u32_by_u16
#include "firmware/core/fixed_point.h"  // mul_u16_u16, mul_s16_u16

namespace core {

namespace {

const uint16_t kOneQ14 = 16384;

// a + (b - a) * f for a Q14 fraction f, both ends and the result in Q4 micrometres
// (|a|, |b| <= 16 000: the difference times 2^14 stays below 2^30).
int32_t lerp_q4(int32_t a_q4, int32_t b_q4, uint16_t f_q14) {
  const int32_t d = b_q4 - a_q4;
  // |d| <= 32 000 fits int16; one 16x16 product.
  return a_q4 + core::asr32(mul_s16_u16((int16_t)d, f_q14) + 8192L, 14);
}

}  // namespace

HeightMap::HeightMap() {
  clear();
}

void HeightMap::clear() {
  active_ = false;
  cols_ = 0;
  rows_ = 0;
  lowest_um_ = 0;
  highest_um_ = 0;
  init_axis(&x_, 0, kMinPitchUm, 2);
  init_axis(&y_, 0, kMinPitchUm, 2);
}

void HeightMap::init_axis(Axis* a, int32_t origin_um, uint16_t pitch_um, uint8_t points) {
  a->origin_um = origin_um;
  a->cell_start_um = origin_um;
  a->pitch_um = pitch_um;
  a->cells = (uint8_t)(points - 1U);
  a->cell = 0;
  uint16_t rest = 0;
  a->reciprocal = div_u32_by_u16(0xFFFFFFFFUL, pitch_um, &rest);  // once per map
}

bool HeightMap::begin(uint8_t cols, uint8_t rows, int32_t x0_um, int32_t y0_um, uint16_t pitch_x_um,
                      uint16_t pitch_y_um) {
  clear();
  if (cols < 2 || rows < 2 || cols > kMaxSide || rows > kMaxSide || pitch_x_um < kMinPitchUm ||
      pitch_y_um < kMinPitchUm)
    return false;
  cols_ = cols;
  rows_ = rows;
  init_axis(&x_, x0_um, pitch_x_um, cols);
  init_axis(&y_, y0_um, pitch_y_um, rows);
  for (uint16_t i = 0; i < (uint16_t)sizeof packed_; ++i) packed_[i] = 0;
  return true;
}

// Byte 3k/2 holds the low 8 bits of an even index; the next byte's low nibble its high 4
// bits and its high nibble the low 4 of the odd index after it, whose high 8 follow.
int16_t HeightMap::height(uint16_t i) const {
  const uint8_t* p = &packed_[i + (i >> 1)];
  const uint16_t v = (i & 1U) ? (uint16_t)((p[0] >> 4) | ((uint16_t)p[1] << 4))
                              : (uint16_t)(p[0] | ((uint16_t)(p[1] & 0x0FU) << 8));
  return (int16_t)((v & 0x0800U) ? (v | 0xF000U) : v);  // 12-bit two's complement
}

bool HeightMap::set(uint16_t index, int16_t height_um) {
  if (cols_ == 0 || index >= (uint16_t)cols_ * rows_) return false;
  if (height_um > kMaxHeightUm || height_um < -kMaxHeightUm) return false;
  const uint16_t v = (uint16_t)height_um & 0x0FFFU;
  uint8_t* p = &packed_[index + (index >> 1)];
  if (index & 1U) {
    p[0] = (uint8_t)((p[0] & 0x0FU) | ((v & 0x0FU) << 4));
    p[1] = (uint8_t)(v >> 4);
  } else {
    p[0] = (uint8_t)v;
    p[1] = (uint8_t)((p[1] & 0xF0U) | (v >> 8));
  }
  return true;
}

void HeightMap::complete() {
  if (cols_ == 0) return;
  const uint16_t n = (uint16_t)cols_ * rows_;
  lowest_um_ = height(0);
  highest_um_ = lowest_um_;
  for (uint16_t i = 1; i < n; ++i) {
    const int16_t h = height(i);
    if (h < lowest_um_) lowest_um_ = h;
    if (h > highest_um_) highest_um_ = h;
  }
  active_ = true;
}

// Steps the cached cell toward v (at most cells steps after a jump, usually none), then the
// fraction: r / pitch as r * floor((2^32 - 1) / pitch) / 2^18, from two 16x16 products
// (r < 2^16, and the reciprocal < 2^23 for a pitch >= 1 mm): low by at most 1 in Q14.
uint16_t HeightMap::locate(Axis* a, int32_t v_um) {
  if (v_um <= a->origin_um) {
    a->cell = 0;
    a->cell_start_um = a->origin_um;
    return 0;
  }
  while (a->cell < a->cells - 1U && v_um >= a->cell_start_um + (int32_t)a->pitch_um) {
    ++a->cell;
    a->cell_start_um += a->pitch_um;
  }
  while (a->cell > 0 && v_um < a->cell_start_um) {
    --a->cell;
    a->cell_start_um -= a->pitch_um;
  }
  const int32_t r = v_um - a->cell_start_um;
  if (r >= (int32_t)a->pitch_um) return kOneQ14;  // beyond the last grid line: the edge
  const uint16_t r16 = (uint16_t)r;
  const uint32_t q16 = mul_u16_u16(r16, (uint16_t)(a->reciprocal >> 16)) +
                       (mul_u16_u16(r16, (uint16_t)a->reciprocal) >> 16);  // r/pitch * 2^16
  return (uint16_t)((q16 + 2U) >> 2);
}

// Out of line: the two rows share one copy (-0.1 kB on the AVR proxy, a call per row).
__attribute__((noinline)) int32_t HeightMap::row_q4(uint16_t i, uint16_t fx_q14) const {
  return lerp_q4((int32_t)height(i) << 4, (int32_t)height((uint16_t)(i + 1U)) << 4, fx_q14);
}

int16_t HeightMap::offset_um(int32_t x_um, int32_t y_um) {
  if (!active_) return 0;
  const uint16_t fx = locate(&x_, x_um);
  const uint16_t fy = locate(&y_, y_um);
  const uint16_t i0 = (uint16_t)((uint16_t)y_.cell * cols_ + x_.cell);
  const uint16_t i1 = (uint16_t)(i0 + cols_);
  // Along X on the cell's two rows (Q4: heights <= 1 000 um fit easily), then along Y.
  int32_t z = asr32(lerp_q4(row_q4(i0, fx), row_q4(i1, fx), fy) + 8L, 4);
  // A convex combination of the corners: inside [lowest, highest] already; kept so for sure.
  if (z < lowest_um_) z = lowest_um_;
  if (z > highest_um_) z = highest_um_;
  return (int16_t)z;
}

}  // namespace core
