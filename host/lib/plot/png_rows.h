// A PNG file written a band of rows at a time from cairo RGB24 rows (opaque plots): the
// picture is never held whole in memory, and zlib runs at its fastest level, which on the
// board plots costs a third of the time of cairo's own writer for files about 1.3x larger.
#ifndef HOST_LIB_PLOT_PNG_ROWS_H
#define HOST_LIB_PLOT_PNG_ROWS_H

#include <cstdint>  // uint8_t
#include <string>   // std::string

namespace host {

struct PngRowsState;  // libpng's structures and the file

class PngRows {
 public:
  // Creates the file for an RGB picture of width x height pixels; throws std::runtime_error
  // naming it when it cannot.
  PngRows(const std::string& path, int width_px, int height_px);
  ~PngRows();
  PngRows(const PngRows&) = delete;
  PngRows& operator=(const PngRows&) = delete;

  // Appends `rows` rows of cairo RGB24 pixels (one uint32 per pixel, native order),
  // `stride` bytes apart.
  void add_rows(const uint8_t* data, int stride, int rows);
  // Ends the picture and closes the file; throws when a write failed.
  void finish();

 private:
  std::string path_;
  PngRowsState* s_;
};

}  // namespace host

#endif  // HOST_LIB_PLOT_PNG_ROWS_H
