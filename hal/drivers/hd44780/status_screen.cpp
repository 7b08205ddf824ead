// Status screen formatting: fixed columns so values do not jump around while they change.
#include "hal/drivers/hd44780/status_screen.h"

namespace drivers {

// Rounds half away from zero to hundredths of a millimetre, then prints right-aligned.
void format_mm(int32_t position_um, char out[kMmFieldChars]) {
  const bool negative = position_um < 0;
  // Widen the magnitude before rounding so INT32_MIN cannot overflow.
  const uint32_t magnitude_um =
      negative ? (uint32_t)(-(position_um + 1)) + 1u : (uint32_t)position_um;
  const uint32_t hundredths = (magnitude_um + 5u) / 10u;
  const uint32_t limit = negative ? 9999u : 99999u;  // "-99.99" / "999.99"
  uint8_t i;
  if (hundredths > limit) {
    for (i = 0; i < kMmFieldChars; ++i) out[i] = '#';
    return;
  }
  for (i = 0; i < kMmFieldChars; ++i) out[i] = ' ';
  uint32_t rest = hundredths;
  int8_t pos = kMmFieldChars - 1;
  // Two decimals, the point, then at least one integer digit.
  out[pos--] = (char)('0' + rest % 10u);
  rest /= 10u;
  out[pos--] = (char)('0' + rest % 10u);
  rest /= 10u;
  out[pos--] = '.';
  do {
    out[pos--] = (char)('0' + rest % 10u);
    rest /= 10u;
  } while (rest != 0 && pos >= 0);
  if (negative && pos >= 0) out[pos] = '-';
}

// Copies up to width characters of text and pads with spaces.
static void put_padded(char* out, const char* text, uint8_t width) {
  uint8_t i = 0;
  if (text != 0) {
    for (; i < width && text[i] != '\0'; ++i) out[i] = text[i];
  }
  for (; i < width; ++i) out[i] = ' ';
}

// Row 0: "SSSSSSSS Z" + 6; row 1: "X" + 6 + "  Y" + 6.
void format_status(const StatusView& view, char row0[kStatusRowChars + 1],
                   char row1[kStatusRowChars + 1]) {
  put_padded(row0, view.state, 8);
  row0[8] = ' ';
  row0[9] = 'Z';
  format_mm(view.position_um[config::kAxisZ], row0 + 10);
  row0[kStatusRowChars] = '\0';
  row1[0] = 'X';
  format_mm(view.position_um[config::kAxisX], row1 + 1);
  row1[7] = ' ';
  row1[8] = ' ';
  row1[9] = 'Y';
  format_mm(view.position_um[config::kAxisY], row1 + 10);
  row1[kStatusRowChars] = '\0';
}

void show_status(hal::TextDisplay* display, const StatusView& view) {
  char row0[kStatusRowChars + 1];
  char row1[kStatusRowChars + 1];
  format_status(view, row0, row1);
  display->write_line(0, row0);
  display->write_line(1, row1);
}

}  // namespace drivers
