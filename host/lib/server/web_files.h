// Where `engraver serve` finds its page: --web, or the folder installed with the executable
// (share/engraver/web beside bin/; the build tree holds a copy at the same place), never the
// source checkout the binary was built from.
#ifndef HOST_LIB_SERVER_WEB_FILES_H
#define HOST_LIB_SERVER_WEB_FILES_H

#include <filesystem>  // std::filesystem::path
#include <string>      // std::string

namespace host::server {

// The page's files, each served at / (index.html) or /NAME. Ends with nullptr.
extern const char* const kWebFiles[];

// The folder `from_bin` (e.g. "../share/engraver/web") relative to the running
// executable's folder (/proc/self/exe). Throws std::runtime_error when that is unknown.
std::filesystem::path web_dir_beside_executable(const std::string& from_bin);

// Why `dir` cannot serve the page ("" when it holds every file of kWebFiles).
std::string missing_web_files(const std::filesystem::path& dir);

}  // namespace host::server

#endif  // HOST_LIB_SERVER_WEB_FILES_H
