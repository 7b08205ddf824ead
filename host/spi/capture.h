// Loads a logic-analyser capture (VCD, sigrok .sr, Saleae CSV) into a Trace, or a Saleae
// SPI-analyser export straight into frames.
#ifndef HOST_SPI_CAPTURE_H
#define HOST_SPI_CAPTURE_H

#include <string>  // std::string
#include <vector>  // std::vector

#include "host/spi/frame.h"  // Frame
#include "host/spi/trace.h"  // Trace

namespace host::spi {

// A coded error: code is stable ("E_OPEN", "E_FORMAT", ...), message says what and where.
struct Error {
  std::string code;
  std::string message;
  bool ok() const { return code.empty(); }
};

struct Capture {
  bool predecoded = false;    // true: frames came decoded (Saleae SPI-analyser CSV)
  Trace trace;                // when !predecoded
  std::vector<Frame> frames;  // when predecoded
};

// Reads one format from text/bytes already in memory.
Error parse_vcd(const std::string& text, Trace* out);
Error parse_sigrok_sr(const std::string& bytes, Trace* out);
Error parse_saleae_digital_csv(const std::string& text, Trace* out);
Error parse_saleae_spi_csv(const std::string& text, std::vector<Frame>* out);

// Reads a file, choosing the reader by content (zip magic, "$" VCD keywords, CSV header).
Error load_capture(const std::string& path, Capture* out);

// Same, from bytes already read (the name only helps the error messages).
Error load_capture_bytes(const std::string& bytes, const std::string& name, Capture* out);

}  // namespace host::spi

#endif  // HOST_SPI_CAPTURE_H
