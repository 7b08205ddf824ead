// The blank's surface as a grid of heights (the probed height map, docs/protocol.md #A/#E):
// the offset to add to a planned Z at any X/Y, by bilinear interpolation in fixed point
// (16x16 products, no division and no 64-bit arithmetic per point), the nearest edge value
// outside the grid. 16 x 16 heights of 12 bits (-2048..2047 um; the map holds -1000..1000):
// 384 bytes, 419 with the grid and the cache (AVR/dsPIC sizes).
#ifndef FIRMWARE_CORE_HEIGHT_MAP_H
#define FIRMWARE_CORE_HEIGHT_MAP_H

#include <stdint.h>  // int32_t, int16_t, uint16_t, uint8_t

namespace core {

class HeightMap {
 public:
  enum { kMaxSide = 16, kMaxPoints = kMaxSide * kMaxSide, kMinPitchUm = 1000, kMaxHeightUm = 1000 };

  HeightMap();
  // No map: every offset 0, inactive.
  void clear();
  // A new grid (cols, rows 2..16; pitches >= kMinPitchUm): inactive, every height 0, until
  // complete(). False (and cleared) for a grid outside those limits.
  bool begin(uint8_t cols, uint8_t rows, int32_t x0_um, int32_t y0_um, uint16_t pitch_x_um,
             uint16_t pitch_y_um);
  // Height of grid point index = row * cols + col (row 0 at y0, col 0 at x0). False past
  // the grid or beyond +-kMaxHeightUm (the interpolation's fixed point needs that bound).
  bool set(uint16_t index, int16_t height_um);
  // Every height is in: compensation on (lowest/highest taken here).
  void complete();
  bool active() const { return active_; }

  // The interpolated height at (x, y): bilinear inside the grid, the nearest edge value
  // outside (no extrapolation); 0 while inactive. Within 1 um of the exact bilinear value.
  int16_t offset_um(int32_t x_um, int32_t y_um);
  int16_t highest_um() const { return active_ ? highest_um_ : 0; }
  int16_t lowest_um() const { return active_ ? lowest_um_ : 0; }
  uint8_t cols() const { return cols_; }
  uint8_t rows() const { return rows_; }

 private:
  // One axis of the grid: the cell [start, start + pitch) the last point fell in (points
  // come in order, so finding the next one's cell is a step or two) and 1/pitch.
  struct Axis {
    int32_t origin_um;
    int32_t cell_start_um;
    uint32_t reciprocal;  // floor((2^32 - 1) / pitch)
    uint16_t pitch_um;
    uint8_t cells;  // points - 1
    uint8_t cell;
  };
  static void init_axis(Axis* a, int32_t origin_um, uint16_t pitch_um, uint8_t points);
  // Cell index and the position in it as a fraction, Q14 (0..16384), clamped to the grid.
  static uint16_t locate(Axis* a, int32_t v_um);
  // Height index i, packed two in three bytes (low 8 bits, then the high 4 of each).
  int16_t height(uint16_t i) const;
  // Heights i and i + 1 interpolated at the Q14 fraction fx, in Q4 micrometres.
  int32_t row_q4(uint16_t i, uint16_t fx_q14) const;

  uint8_t packed_[kMaxPoints * 3 / 2];
  Axis x_;
  Axis y_;
  int16_t lowest_um_;
  int16_t highest_um_;
  uint8_t cols_;
  uint8_t rows_;
  bool active_;
};

}  // namespace core

#endif  // FIRMWARE_CORE_HEIGHT_MAP_H
