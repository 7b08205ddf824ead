// The page's files and where they are installed (see web_files.h).
#include "host/lib/server/web_files.h"

#include <stdexcept>     // std::runtime_error
#include <system_error>  // std::error_code

namespace host::server {

namespace fs = std::filesystem;

const char* const kWebFiles[] = {"index.html", "app.js", "style.css", nullptr};

fs::path web_dir_beside_executable(const std::string& from_bin) {
  std::error_code ec;
  const fs::path exe = fs::read_symlink("/proc/self/exe", ec);
  if (ec) throw std::runtime_error("cannot tell where this engraver is: " + ec.message());
  return (exe.parent_path() / from_bin).lexically_normal();
}

std::string missing_web_files(const fs::path& dir) {
  std::string missing;
  for (const char* const* f = kWebFiles; *f != nullptr; ++f) {
    std::error_code ec;
    if (!fs::is_regular_file(dir / *f, ec))
      missing += std::string(missing.empty() ? "" : ", ") + *f;
  }
  if (missing.empty()) return "";
  return dir.string() + " lacks the page's " + missing;
}

}  // namespace host::server
