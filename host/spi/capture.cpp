// Chooses a capture reader by file content and runs it.
#include "host/spi/capture.h"

#include <fcntl.h>     // O_WRONLY
#include <spawn.h>     // posix_spawnp
#include <sys/wait.h>  // waitpid
#include <unistd.h>    // close, environ

#include <cctype>      // std::tolower
#include <cstdio>      // std::remove
#include <cstdlib>     // mkstemp
#include <filesystem>  // std::filesystem::is_directory
#include <fstream>     // std::ifstream
#include <iterator>    // std::istreambuf_iterator

namespace host::spi {
namespace {

// First non-empty line, lower-cased.
std::string first_line(const std::string& bytes) {
  size_t a = bytes.find_first_not_of(" \t\r\n");
  if (a == std::string::npos) return "";
  size_t b = bytes.find_first_of("\r\n", a);
  std::string line = bytes.substr(a, b == std::string::npos ? std::string::npos : b - a);
  for (char& c : line) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  return line;
}

// Runs `sigrok-cli -i PATH -O vcd -o TMP` (no shell) and reads TMP. False if that fails.
bool sigrok_to_vcd(const std::string& path, std::string* vcd) {
  char tmp[] = "/tmp/engraver-spi-XXXXXX";
  int fd = mkstemp(tmp);
  if (fd < 0) return false;
  close(fd);
  const std::string out = tmp;
  const char* argv[] = {"sigrok-cli", "-i", path.c_str(), "-O", "vcd", "-o", out.c_str(), nullptr};
  posix_spawn_file_actions_t quiet;  // its messages would confuse ours
  posix_spawn_file_actions_init(&quiet);
  posix_spawn_file_actions_addopen(&quiet, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&quiet, 2, "/dev/null", O_WRONLY, 0);
  pid_t pid = 0;
  bool ok = posix_spawnp(&pid, "sigrok-cli", &quiet, nullptr, const_cast<char* const*>(argv),
                         environ) == 0;
  posix_spawn_file_actions_destroy(&quiet);
  int status = 0;
  ok = ok && waitpid(pid, &status, 0) == pid && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  if (ok) {
    std::ifstream f(out, std::ios::binary);
    vcd->assign((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
    ok = !vcd->empty();
  }
  std::remove(out.c_str());
  return ok;
}

}  // namespace

Error load_capture_bytes(const std::string& bytes, const std::string& name, Capture* out) {
  *out = Capture();
  Error e;
  if (bytes.size() >= 4 && bytes.compare(0, 4, "PK\x03\x04", 4) == 0) {
    e = parse_sigrok_sr(bytes, &out->trace);
  } else {
    std::string head = first_line(bytes);
    if (head.empty()) return {"E_FORMAT", name + ": empty file"};
    if (head[0] == '$') {
      e = parse_vcd(bytes, &out->trace);
    } else if (head.find("packet id") != std::string::npos ||
               head.find("start_time") != std::string::npos) {
      // Saleae SPI-analyser export: already decoded words.
      out->predecoded = true;
      e = parse_saleae_spi_csv(bytes, &out->frames);
    } else if (head.rfind("time", 0) == 0 || head.rfind("\"time", 0) == 0) {
      e = parse_saleae_digital_csv(bytes, &out->trace);
    } else {
      return {"E_FORMAT", name +
                              ": unknown capture format (expected VCD, sigrok .sr, or "
                              "Saleae CSV)"};
    }
  }
  if (!e.ok()) e.message = name + ": " + e.message;
  return e;
}

Error load_capture(const std::string& path, Capture* out) {
  std::error_code ec;
  if (std::filesystem::is_directory(path, ec)) return {"E_OPEN", path + ": is a directory"};
  // Asked before opening: a FIFO's open waits for a writer.
  if (std::filesystem::exists(path, ec) && !std::filesystem::is_regular_file(path, ec))
    return {"E_OPEN", path + ": not a regular file (a pipe, device or socket)"};
  std::ifstream in(path, std::ios::binary);
  if (!in) return {"E_OPEN", path + ": cannot open"};
  std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) return {"E_OPEN", path + ": read error"};
  Error e = load_capture_bytes(bytes, path, out);
  if (e.ok() || e.code != "E_FORMAT" || bytes.compare(0, 4, "PK\x03\x04", 4) != 0) return e;
  // A sigrok session this reader does not understand: let sigrok-cli convert it, if present.
  std::string vcd;
  if (!sigrok_to_vcd(path, &vcd)) return e;
  Error e2 = load_capture_bytes(vcd, path + " (via sigrok-cli)", out);
  return e2.ok() ? e2 : e;
}

}  // namespace host::spi
