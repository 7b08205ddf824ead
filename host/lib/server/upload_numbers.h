// The number and yes/no fields of an upload (a form part or a query parameter), read by the
// rules of the command line's options: a plain decimal (host/lib/plan/plain_decimal.h; no
// hex, no blanks, no nan or inf), a count a whole number (2.0 and 1e0 are 2 and 1), a
// yes/no one of a fixed set of words. Each returns "" or why not, naming the field.
#ifndef HOST_LIB_SERVER_UPLOAD_NUMBERS_H
#define HOST_LIB_SERVER_UPLOAD_NUMBERS_H

#include <cstdint>  // int64_t
#include <string>   // std::string

namespace host::server {

// "tool_width_mm '0x10' is not a decimal number ..." / "... is not a finite number".
std::string read_decimal_field(const std::string& key, const std::string& text, double* out);

// A decimal that is whole and within +-1e15 ("passes '1.5' is not a whole number").
std::string read_whole_field(const std::string& key, const std::string& text, int64_t* out);

// 1, true, yes, on / 0, false, no, off (a page's checkbox sends "on"); anything else is
// refused, listing them.
std::string read_flag_field(const std::string& key, const std::string& text, bool* out);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_UPLOAD_NUMBERS_H
