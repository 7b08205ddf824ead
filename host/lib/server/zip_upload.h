// A board sent as one zip file (what CAM tools and board houses pass around): its entries
// read from memory with libzip (Debian libzip-dev). Entry names keep only their last part
// and are names, never paths; sizes are checked while reading (a zip's own size fields
// may lie), so a zip bomb stops at the upload limit.
#ifndef HOST_LIB_SERVER_ZIP_UPLOAD_H
#define HOST_LIB_SERVER_ZIP_UPLOAD_H

#include <stdexcept>  // std::runtime_error
#include <string>     // std::string
#include <vector>     // std::vector

#include "host/lib/server/board_planning.h"  // UploadFile

namespace host::server {

// Starts like a zip file (a local file header).
bool looks_like_zip(const std::string& bytes);

class ZipError : public std::runtime_error {
 public:
  ZipError(const std::string& msg, bool too_large)
      : std::runtime_error(msg), too_large_(too_large) {}
  bool too_large() const { return too_large_; }

 private:
  bool too_large_;
};

// The zip's files (folders, hidden files and __MACOSX/ left out), in the zip's order.
// Throws ZipError naming `zip_name`: damaged, encrypted, an entry named to land outside
// the zip's folder (absolute, a drive, ".."), more than max_entries entries, or
// (too_large) more than max_bytes once unpacked.
std::vector<UploadFile> unzip_upload(const std::string& bytes, const std::string& zip_name,
                                     size_t max_bytes, size_t max_entries);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_ZIP_UPLOAD_H
