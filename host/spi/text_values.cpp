// Text parsers of the capture readers (see text_values.h).
#include "host/spi/text_values.h"

#include <cstdlib>  // std::strtod

namespace host::spi {

std::string trim(const std::string& s, const char* chars) {
  const size_t a = s.find_first_not_of(chars);
  if (a == std::string::npos) return "";
  const size_t b = s.find_last_not_of(chars);
  return s.substr(a, b - a + 1);
}

bool split_number_unit(const std::string& text, double* number, std::string* unit) {
  const char* s = text.c_str();
  char* end = nullptr;
  *number = std::strtod(s, &end);
  if (end == s) return false;
  unit->assign(end);
  unit->erase(0, unit->find_first_not_of(' '));
  return true;
}

}  // namespace host::spi
