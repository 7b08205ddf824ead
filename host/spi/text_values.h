// Small text parsers the capture readers and the framer share: trimming a field, a number
// with its unit ("4 MHz", "500 ns").
#ifndef HOST_SPI_TEXT_VALUES_H
#define HOST_SPI_TEXT_VALUES_H

#include <stddef.h>  // size_t

#include <string>  // std::string

namespace host::spi {

// s without the characters of `chars` at either end.
std::string trim(const std::string& s, const char* chars = " \t\r\n");

// "4.5 MHz" -> 4.5 and "MHz" (the spaces before the unit skipped, the rest kept as written);
// false when the text does not start with a number.
bool split_number_unit(const std::string& text, double* number, std::string* unit);

// A unit and what one of it is in the caller's base unit.
struct UnitScale {
  const char* unit;
  double scale;
};

// The scale of `unit` in `table`; 0 when the table does not list it.
template <size_t N>
double unit_scale(const std::string& unit, const UnitScale (&table)[N]) {
  for (const UnitScale& u : table) {
    if (unit == u.unit) return u.scale;
  }
  return 0;
}

}  // namespace host::spi

#endif  // HOST_SPI_TEXT_VALUES_H
