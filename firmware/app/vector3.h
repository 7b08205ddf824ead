// Small integer helpers for 3-axis vectors shared by the planner and the path controller.
#ifndef FIRMWARE_APP_VECTOR3_H
#define FIRMWARE_APP_VECTOR3_H

#include <stdint.h>  // int32_t, int16_t

namespace app {

// Scales d so the largest component lies in [2^14, 2^15) (or all are zero): out = d / 2^shift
// rounded, shift in -14..17 (negative: d was multiplied). Keeps the direction to about 3e-5
// and three squares below 2^32.
void normalise3(const int32_t d[3], int16_t out[3], int8_t* shift);

// Sum of the squares of v's components (< 3 * 2^30: fits 32 bits unsigned).
uint32_t sum_squares3(const int16_t v[3]);

// Magnitude of out (as from normalise3): floor(sqrt(sum of squares)), 0..56755.
uint16_t length3(const int16_t v[3]);

// scale_length_q4(floor(sqrt(sum_sq)), shift) > limit_q4, decided on the squares (no root):
// the smallest length that passes the limit, squared, against sum_sq.
bool length_q4_exceeds(uint32_t sum_sq, int8_t shift, uint32_t limit_q4);

// |v| * 2^shift in units of 1/16, saturated at 2^30 (shift as from normalise3).
uint32_t scale_length_q4(uint16_t len, int8_t shift);

}  // namespace app

#endif  // FIRMWARE_APP_VECTOR3_H
