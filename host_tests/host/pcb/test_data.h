// Paths and helpers shared by the PCB reader tests.
#ifndef HOST_TESTS_HOST_PCB_TEST_DATA_H
#define HOST_TESTS_HOST_PCB_TEST_DATA_H

#include <clipper.hpp>  // ClipperLib::Paths, Area

#include <string>  // std::string

namespace host::pcb::test {

// A file of host_tests/host/pcb/data/ (the project's own test boards).
inline std::string data_file(const std::string& name) {
  return std::string(ENGRAVER_SOURCE_DIR) + "/host_tests/host/pcb/data/" + name;
}

// Net area in mm² (outers count positive, holes negative).
inline double area_mm2(const ClipperLib::Paths& paths) {
  double a = 0;
  for (const auto& p : paths) a += ClipperLib::Area(p);
  return a * 1e-12;
}

}  // namespace host::pcb::test

#endif  // HOST_TESTS_HOST_PCB_TEST_DATA_H
