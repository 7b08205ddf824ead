// A whole input file read into one string, for the importers and readers that then parse
// it from memory.
#ifndef HOST_LIB_DRAWING_FILE_TEXT_H
#define HOST_LIB_DRAWING_FILE_TEXT_H

#include <string>  // std::string

namespace host {

enum class FileRead { kOk, kCannotOpen, kReadError };

// Reads the file at path into *text, sized once from the file's length (a stringstream and
// its str() held a large file twice). Each caller words its own error.
// A directory, a pipe, device or socket (never opened) or a file that cannot be opened is
// kCannotOpen.
FileRead read_file_text(const std::string& path, std::string* text);

// The first 4 kB of the file at path (less when shorter, empty when it cannot be opened or
// is not a regular file): where formats are recognised by their content.
std::string read_file_head(const std::string& path);

// s with A-Z in lower case (file names, host names).
std::string lower_ascii(std::string s);

// Why the file at path is not read, asked before it is opened (opening a FIFO waits for a
// writer): "is a directory, not a file", "not a regular file (a pipe, device or socket)";
// "" for a regular file (or a link to one) and for a path that does not exist.
std::string not_a_file_text(const std::string& path);

// Why the file at path cannot be opened: not_a_file_text, else "cannot open the file"
// (missing), "cannot open the file: Permission denied".
std::string cannot_open_text(const std::string& path);

// The file's text, or Error "<path>: cannot open the file" / "<path>: cannot read the file"
// (the drawing importers' ImportError, the PCB readers' PcbReadError).
template <class Error>
std::string read_text_or_throw(const std::string& path) {
  std::string text;
  const FileRead r = read_file_text(path, &text);
  if (r == FileRead::kCannotOpen) throw Error(path + ": " + cannot_open_text(path));
  if (r == FileRead::kReadError) throw Error(path + ": cannot read the file");
  return text;
}

// The drawing importers' read: read_text_or_throw<ImportError>.
std::string read_drawing_text(const std::string& path);

}  // namespace host

#endif  // HOST_LIB_DRAWING_FILE_TEXT_H
