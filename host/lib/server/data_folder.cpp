// Data folder layout, the access token and small file helpers.
#include "host/lib/server/data_folder.h"

#include <fcntl.h>     // open
#include <sys/stat.h>  // S_IRUSR
#include <unistd.h>    // write, close

#include <cstring>    // std::strcmp
#include <fstream>    // std::ifstream
#include <random>     // std::random_device
#include <stdexcept>  // std::runtime_error

#include "host/lib/drawing/file_text.h"  // read_file_text

namespace host::server {

namespace fs = std::filesystem;

const char* const kArchiveFiles[] = {
    "plan.json", "plot.svg", "plot.png", "report.json", "machine.log", "input.dxf", "input.ngc",
    "input.nc", "input.gcode", "input.tap", "input.g", "input.gbr", "input.drl", "input",
    // A board job: its manifest and layers (board_planning.h).
    "board.json", "copper.top.gbr", "copper.bot.gbr", "outline.gbr", "drill.drl", "drill.b.drl",
    "drill.c.drl", "drill.d.drl", "input.zip",
    // Its height map and the machine it was probed on (board_height_map.h).
    "heightmap.json", "heightmap.svg", "heightmap.machine", nullptr};

bool is_archive_file(const std::string& name) {
  for (const char* const* f = kArchiveFiles; *f != nullptr; ++f) {
    if (name == *f) return true;
  }
  return false;
}

std::string random_hex(size_t bytes) {
  std::random_device rd;  // /dev/urandom on Linux
  static const char kHex[] = "0123456789abcdef";
  std::string s;
  for (size_t i = 0; i < bytes; ++i) {
    const unsigned v = rd() & 0xFFu;
    s += kHex[v >> 4];
    s += kHex[v & 0xF];
  }
  return s;
}

DataFolder::DataFolder(const fs::path& root, const fs::path& archive)
    : root_(root),
      jobs_(archive.empty() ? root / "jobs" : archive),
      staging_(archive.empty() ? root / "tmp" : archive / ".staging") {
  std::error_code ec;
  fs::create_directories(root_ / "jobs", ec);
  if (!ec) fs::remove_all(root_ / "tmp", ec);
  if (!ec) fs::create_directories(root_ / "tmp", ec);
  if (ec) throw std::runtime_error(root_.string() + ": cannot use as data folder: " + ec.message());
  // A shared archive's staging folder is not cleared: other servers' uploads are in it.
  fs::create_directories(staging_, ec);
  if (ec) throw std::runtime_error(jobs_.string() + ": cannot use as archive: " + ec.message());
}

fs::path DataFolder::new_staging_dir() const {
  const fs::path dir = staging_ / random_hex(12);
  fs::create_directories(dir);
  return dir;
}

std::string DataFolder::token(bool* created) const {
  const fs::path path = token_path();
  *created = false;
  std::ifstream in(path);
  std::string token;
  if (in >> token && token.size() >= 32) return token;
  token = random_hex(24);
  // O_EXCL on a fresh name, then rename: never a half-written or world-readable token.
  const fs::path fresh = root_ / ("token." + random_hex(4));
  const int fd = ::open(fresh.c_str(), O_WRONLY | O_CREAT | O_EXCL, S_IRUSR | S_IWUSR);
  if (fd < 0) throw std::runtime_error(fresh.string() + ": cannot create the token file");
  const std::string line = token + "\n";
  const bool ok = ::write(fd, line.data(), line.size()) == static_cast<ssize_t>(line.size());
  ::close(fd);
  if (!ok) throw std::runtime_error(fresh.string() + ": cannot write the token file");
  fs::rename(fresh, path);
  *created = true;
  return token;
}

void write_file(const fs::path& path, const std::string& content) {
  std::ofstream out(path, std::ios::binary);
  out.write(content.data(), static_cast<std::streamsize>(content.size()));
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
}

std::string read_file(const fs::path& path) {
  std::string text;
  if (read_file_text(path.string(), &text) != FileRead::kOk)
    throw std::runtime_error(path.string() + ": cannot read");
  return text;
}

std::string read_file_head(const fs::path& path, size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  std::string head(bytes, '\0');
  in.read(head.data(), static_cast<std::streamsize>(bytes));
  if (in.bad() || (!in && !in.eof())) throw std::runtime_error(path.string() + ": cannot read");
  head.resize(static_cast<size_t>(in.gcount()));
  return head;
}

}  // namespace host::server
