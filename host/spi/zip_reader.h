// Minimal zip archive reader (stored and deflated members) for sigrok session files.
#ifndef HOST_SPI_ZIP_READER_H
#define HOST_SPI_ZIP_READER_H

#include <map>     // std::map
#include <string>  // std::string

#include "host/spi/capture.h"  // Error

namespace host::spi {

// Unpacks every member of a zip held in memory into name -> contents. Refuses members
// larger than max_member_bytes (zip bombs) and anything malformed, with a coded error.
Error unzip_all(const std::string& zip, std::map<std::string, std::string>* members,
                size_t max_member_bytes);

}  // namespace host::spi

#endif  // HOST_SPI_ZIP_READER_H
