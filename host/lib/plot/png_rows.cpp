// PNG rows written band by band with libpng (see png_rows.h).
#include "host/lib/plot/png_rows.h"

#include <png.h>  // png_*

#include <csetjmp>    // setjmp
#include <cstdio>     // std::FILE
#include <stdexcept>  // std::runtime_error

namespace host {

struct PngRowsState {
  std::FILE* file = nullptr;
  png_structp png = nullptr;
  png_infop info = nullptr;
  int height_px = 0;
  int rows_written = 0;
};

namespace {

// libpng reports errors by longjmp to the setjmp of the call that failed: these wrappers
// hold only plain data across it and return false instead.
bool begin(PngRowsState* s, int width_px, int height_px) {
  if (setjmp(png_jmpbuf(s->png))) return false;
  png_init_io(s->png, s->file);
  png_set_IHDR(s->png, s->info, static_cast<png_uint_32>(width_px),
               static_cast<png_uint_32>(height_px), 8, PNG_COLOR_TYPE_RGB, PNG_INTERLACE_NONE,
               PNG_COMPRESSION_TYPE_DEFAULT, PNG_FILTER_TYPE_DEFAULT);
  // Plots are flat colour: one cheap filter and zlib's fastest level keep the file small
  // enough at a fraction of the default's time.
  png_set_filter(s->png, PNG_FILTER_TYPE_BASE, PNG_FILTER_SUB);
  png_set_compression_level(s->png, 1);
  png_write_info(s->png, s->info);
  // cairo RGB24 in memory on a little-endian host: B, G, R, unused.
  png_set_bgr(s->png);
  png_set_filler(s->png, 0, PNG_FILLER_AFTER);
  return true;
}

bool rows(PngRowsState* s, const uint8_t* data, int stride, int n) {
  if (setjmp(png_jmpbuf(s->png))) return false;
  for (int i = 0; i < n; ++i) png_write_row(s->png, data + static_cast<long>(i) * stride);
  return true;
}

bool end(PngRowsState* s) {
  if (setjmp(png_jmpbuf(s->png))) return false;
  png_write_end(s->png, nullptr);
  return true;
}

void release(PngRowsState* s) {
  if (s->png) png_destroy_write_struct(&s->png, s->info ? &s->info : nullptr);
  if (s->file) std::fclose(s->file);
  delete s;
}

}  // namespace

PngRows::PngRows(const std::string& path, int width_px, int height_px)
    : path_(path), s_(new PngRowsState) {
  s_->height_px = height_px;
  s_->file = std::fopen(path.c_str(), "wb");
  s_->png = png_create_write_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  if (s_->png) s_->info = png_create_info_struct(s_->png);
  if (!s_->file || !s_->png || !s_->info || !begin(s_, width_px, height_px)) {
    release(s_);
    throw std::runtime_error(path + ": cannot write the plot");
  }
}

PngRows::~PngRows() {
  release(s_);
}

void PngRows::add_rows(const uint8_t* data, int stride, int n) {
  if (s_->rows_written + n > s_->height_px || !rows(s_, data, stride, n))
    throw std::runtime_error(path_ + ": cannot write the plot");
  s_->rows_written += n;
}

void PngRows::finish() {
  bool ok = s_->rows_written == s_->height_px && end(s_);
  ok = std::fflush(s_->file) == 0 && ok;
  ok = std::fclose(s_->file) == 0 && ok;
  s_->file = nullptr;
  if (!ok) throw std::runtime_error(path_ + ": cannot write the plot (write failed)");
}

}  // namespace host
