// Whole-file reading (see file_text.h).
#include "host/lib/drawing/file_text.h"

#include <algorithm>     // std::transform
#include <cctype>        // std::tolower
#include <cerrno>        // errno
#include <cstring>       // std::strerror
#include <filesystem>    // std::filesystem::file_size, is_directory
#include <fstream>       // std::ifstream
#include <system_error>  // std::error_code

#include "host/lib/drawing/drawing.h"  // ImportError

namespace host {

std::string not_a_file_text(const std::string& path) {
  std::error_code ec;
  const std::filesystem::file_type t = std::filesystem::status(path, ec).type();
  if (t == std::filesystem::file_type::directory) return "is a directory, not a file";
  if (t == std::filesystem::file_type::regular || t == std::filesystem::file_type::not_found ||
      t == std::filesystem::file_type::none || t == std::filesystem::file_type::unknown)
    return "";
  return "not a regular file (a pipe, device or socket)";
}

std::string cannot_open_text(const std::string& path) {
  const std::string not_a_file = not_a_file_text(path);
  if (!not_a_file.empty()) return not_a_file;
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) return "cannot open the file";
  errno = 0;
  std::ifstream probe(path, std::ios::binary);
  const int why = errno;
  if (!probe && why != 0) return std::string("cannot open the file: ") + std::strerror(why);
  return "cannot open the file";
}

FileRead read_file_text(const std::string& path, std::string* text) {
  text->clear();
  std::error_code ec;
  // A directory opens as a stream on Linux, and its "size" can be 2^63; a FIFO's open waits.
  if (!not_a_file_text(path).empty()) return FileRead::kCannotOpen;
  std::ifstream in(path, std::ios::binary);
  if (!in) return FileRead::kCannotOpen;
  const std::uintmax_t size = std::filesystem::file_size(path, ec);
  if (!ec && size > 0) text->reserve(static_cast<size_t>(size));
  char buffer[1 << 16];
  while (in.read(buffer, sizeof buffer) || in.gcount() > 0)
    text->append(buffer, static_cast<size_t>(in.gcount()));
  return in.bad() ? FileRead::kReadError : FileRead::kOk;
}

std::string read_file_head(const std::string& path) {
  if (!not_a_file_text(path).empty()) return std::string();
  std::ifstream in(path, std::ios::binary);
  std::string head(4096, '\0');
  in.read(&head[0], static_cast<std::streamsize>(head.size()));
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

std::string lower_ascii(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  return s;
}

std::string read_drawing_text(const std::string& path) {
  return read_text_or_throw<ImportError>(path);
}

}  // namespace host
