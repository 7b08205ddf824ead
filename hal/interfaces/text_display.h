// A two-line character display as the application sees it (HD44780 behind it).
#ifndef HAL_INTERFACES_TEXT_DISPLAY_H
#define HAL_INTERFACES_TEXT_DISPLAY_H

#include <stdint.h>  // uint8_t

namespace hal {

class TextDisplay {
 public:
  enum { kColumns = 16, kRows = 2 };
  // Writes up to kColumns characters of a NUL-terminated string on a row, pads with spaces.
  virtual void write_line(uint8_t row, const char* text) = 0;
  virtual void clear() = 0;

 protected:
  ~TextDisplay() {}
};

}  // namespace hal

#endif  // HAL_INTERFACES_TEXT_DISPLAY_H
