// Small helpers for the host_spi tests: temp files and framing a VCD held in a string.
#ifndef HOST_TESTS_SPI_TEST_UTIL_H
#define HOST_TESTS_SPI_TEST_UTIL_H

#include <gtest/gtest.h>  // ::testing::TempDir

#include <unistd.h>  // getpid

#include <fstream>  // std::ofstream
#include <string>   // std::string
#include <vector>   // std::vector

#include "host/spi/capture.h"  // parse_vcd
#include "host/spi/framer.h"   // frame_capture

namespace spi_test {

// Writes text to a fresh file in the test temp dir and returns its path. The name carries
// the process id: ctest runs the tests of this binary in parallel processes.
inline std::string temp_file(const std::string& name, const std::string& text) {
  std::string path = ::testing::TempDir() + "/spi_test_" + std::to_string(::getpid()) + "_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// Frames a VCD text with the given options; fails the test on a reader error.
inline host::spi::FramerResult frame_vcd(const std::string& vcd, host::spi::FramerOptions o = {}) {
  host::spi::Trace t;
  host::spi::Error e = host::spi::parse_vcd(vcd, &t);
  EXPECT_TRUE(e.ok()) << e.code << " " << e.message;
  host::spi::FramerResult r;
  e = host::spi::frame_capture(t, o, &r);
  EXPECT_TRUE(e.ok()) << e.code << " " << e.message;
  return r;
}

inline std::string data_path(const std::string& name) {
  return std::string(SPI_TEST_DATA_DIR) + "/" + name;
}

}  // namespace spi_test

#endif  // HOST_TESTS_SPI_TEST_UTIL_H
