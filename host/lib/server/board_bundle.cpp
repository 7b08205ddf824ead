// Board bundle packing (see board_bundle.h).
#include "host/lib/server/board_bundle.h"

#include <charconv>   // std::from_chars
#include <stdexcept>  // std::runtime_error

#include "host/lib/server/data_folder.h"

namespace host::server {

namespace {
const char kMagic[] = "engraver-board 1\n";
}

std::string pack_board_bundle(const NamedFiles& files) {
  std::string out = kMagic;
  for (const auto& [name, bytes] : files) {
    out += name + " " + std::to_string(bytes.size()) + "\n";
    out += bytes;
    out += "\n";
  }
  return out;
}

NamedFiles unpack_board_bundle(const std::string& bundle) {
  const std::string magic = kMagic;
  if (bundle.compare(0, magic.size(), magic) != 0)
    throw std::runtime_error("board bundle: not a bundle");
  NamedFiles files;
  size_t at = magic.size();
  while (at < bundle.size()) {
    const size_t eol = bundle.find('\n', at);
    const size_t space = bundle.find(' ', at);
    if (eol == std::string::npos || space == std::string::npos || space > eol)
      throw std::runtime_error("board bundle: damaged header");
    const std::string name = bundle.substr(at, space - at);
    size_t size = 0;
    const char* first = bundle.data() + space + 1;
    const char* last = bundle.data() + eol;
    const auto r = std::from_chars(first, last, size);
    if (r.ec != std::errc() || r.ptr != last) throw std::runtime_error("board bundle: bad size");
    if (!is_archive_file(name)) throw std::runtime_error("board bundle: unexpected file " + name);
    at = eol + 1;
    if (size > bundle.size() - at || bundle.size() - at - size < 1 || bundle[at + size] != '\n')
      throw std::runtime_error("board bundle: " + name + " is cut short");
    files.emplace_back(name, bundle.substr(at, size));
    at += size + 1;
  }
  return files;
}

}  // namespace host::server
