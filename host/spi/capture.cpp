// Chooses a capture reader by file content and runs it.
#include "host/spi/capture.h"

#include <cctype>    // std::tolower
#include <fstream>   // std::ifstream
#include <iterator>  // std::istreambuf_iterator

namespace host::spi {
namespace {

// First non-empty line, lower-cased.
std::string first_line(const std::string& bytes) {
  size_t a = bytes.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  size_t b = bytes.find_first_of("\r\n", a);
  std::string line = bytes.substr(a, b == std::string::npos ? std::string::npos : b - a);
  for (char& c : line) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return line;
}

}  // namespace

Error load_capture_bytes(const std::string& bytes, const std::string& name, Capture* out) {
  *out = Capture();
  Error e;
  if (bytes.size() >= 4 && bytes.compare(0, 4, "PK\x03\x04", 4) == 0) {
    e = parse_sigrok_sr(bytes, &out->trace);
  } else {
    std::string head = first_line(bytes);
    if (head.empty()) return {"E_FORMAT", name + ": empty file"};
    if (head[0] == '$') {
      e = parse_vcd(bytes, &out->trace);
    } else if (head.find("packet id") != std::string::npos ||
               head.find("start_time") != std::string::npos) {
      // Saleae SPI-analyser export: already decoded words.
      out->predecoded = true;
      e = parse_saleae_spi_csv(bytes, &out->frames);
    } else if (head.rfind("time", 0) == 0 || head.rfind("\"time", 0) == 0) {
      e = parse_saleae_digital_csv(bytes, &out->trace);
    } else {
      return {"E_FORMAT", name + ": unknown capture format (expected VCD, sigrok .sr, or "
                                 "Saleae CSV)"};
    }
  }
  if (!e.ok()) e.message = name + ": " + e.message;
  return e;
}

Error load_capture(const std::string& path, Capture* out) {
  std::ifstream in(path, std::ios::binary);
  if (!in) return {"E_OPEN", path + ": cannot open"};
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return {"E_OPEN", path + ": read error"};
  return load_capture_bytes(bytes, path, out);
}

}  // namespace host::spi
