// The syntax check and tokenizer of an ASCII DXF file: it splits the text into group
// code/value pairs and checks every one (group codes are integers, numbers are finite and in
// the range of their type, counts fit the file, the file is complete). dxflib is then driven
// with exactly these pairs, so it never reads a byte that was not checked.
#ifndef HOST_LIB_DRAWING_DXF_SCAN_H
#define HOST_LIB_DRAWING_DXF_SCAN_H

#include <cstddef>  // size_t
#include <memory>   // std::unique_ptr
#include <string>   // std::string

#include "host/lib/drawing/drawing.h"  // WorkProgress

namespace host {

// One group code/value pair, value stripped of surrounding blanks.
struct DxfGroup {
  int code = 0;
  std::string value;
  long line = 0;  // line of the group code, from 1
};

// Splits `text` (the file's bytes) into groups up to and including the closing 0/EOF, one
// group at a time, without holding them (a million-entity file has over ten million).
// Comments (group 999) are dropped. `text` must outlive the scanner. next() returns false
// after the closing 0/EOF has been returned; it throws ImportError naming `path`, the line,
// the entity and the problem; content after 0/EOF other than blanks, NUL and Ctrl-Z is
// refused.
class DxfScanner {
 public:
  DxfScanner(const std::string& text, const std::string& path);
  ~DxfScanner();
  DxfScanner(const DxfScanner&) = delete;
  DxfScanner& operator=(const DxfScanner&) = delete;
  bool next(DxfGroup* group);
  // Bytes of the text scanned so far (for progress).
  size_t pos() const;

 private:
  struct State;
  std::unique_ptr<State> s_;
};

// Scans the whole text, so that nothing of a broken file is read: throws what next() would.
// progress (when given): "bytes checked" every 64k groups.
void check_dxf(const std::string& text, const std::string& path,
               const WorkProgress& progress = nullptr);

// Largest count a group may announce (control points, knots, vertices) whatever the file's
// size: far beyond any sane drawing, small enough that dxflib's allocation of it is modest.
const long kMaxDxfDeclaredCount = 1000000;

// Smallest number of bytes one announced item takes in the file ("10\n0\n"): an announced
// count above (file size / this) cannot be honoured, so it is refused before dxflib
// allocates for it.
const long kMinDxfItemBytes = 4;

// Longest value handed to dxflib (its line buffer holds 1023 characters): longer numbers
// are refused, longer text (names, annotations: never engraved) is cut.
const size_t kMaxDxfValueChars = 1000;

// True when the file starts like a DXF (ASCII or binary).
bool looks_like_dxf(const std::string& path);

}  // namespace host

#endif  // HOST_LIB_DRAWING_DXF_SCAN_H
