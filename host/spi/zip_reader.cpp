// Zip parsing via the central directory; deflate through zlib's raw inflate.
#include "host/spi/zip_reader.h"

#include <zlib.h>  // inflate

#include <cstdint>  // uint32_t

namespace host::spi {
namespace {

uint32_t le16(const std::string& s, size_t at) {
  return static_cast<uint8_t>(s[at]) | (static_cast<uint8_t>(s[at + 1]) << 8);
}
uint32_t le32(const std::string& s, size_t at) {
  return le16(s, at) | (le16(s, at + 2) << 16);
}

// Raw-deflate decompression of exactly `size` bytes.
bool inflate_raw(const char* data, size_t len, size_t size, std::string* out) {
  out->assign(size, '\0');
  z_stream zs{};
  if (inflateInit2(&zs, -MAX_WBITS) != Z_OK) return false;
  zs.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(data));
  zs.avail_in = static_cast<uInt>(len);
  zs.next_out = reinterpret_cast<Bytef*>(size ? &(*out)[0] : nullptr);
  zs.avail_out = static_cast<uInt>(size);
  int rc = inflate(&zs, Z_FINISH);
  size_t produced = size - zs.avail_out;
  inflateEnd(&zs);
  return (rc == Z_STREAM_END || (rc == Z_BUF_ERROR && size == 0)) && produced == size;
}

}  // namespace

Error unzip_all(const std::string& zip, std::map<std::string, std::string>* members,
                size_t max_member_bytes) {
  members->clear();
  const size_t n = zip.size();
  if (n < 22) return {"E_FORMAT", "zip: file too short"};
  // End of central directory: last occurrence of PK\5\6 within the final 64 KiB + 22.
  size_t eocd = std::string::npos;
  size_t lowest = n > 22 + 65535 ? n - 22 - 65535 : 0;
  for (size_t i = n - 22 + 1; i-- > lowest;) {
    if (le32(zip, i) == 0x06054b50u) {
      eocd = i;
      break;
    }
  }
  if (eocd == std::string::npos) return {"E_FORMAT", "zip: no end-of-directory record"};
  uint32_t count = le16(zip, eocd + 10);
  uint32_t dir_size = le32(zip, eocd + 12);
  uint32_t dir_at = le32(zip, eocd + 16);
  if (static_cast<uint64_t>(dir_at) + dir_size > eocd)
    return {"E_FORMAT", "zip: central directory out of bounds (truncated file?)"};
  size_t p = dir_at;
  for (uint32_t k = 0; k < count; ++k) {
    if (p + 46 > eocd || le32(zip, p) != 0x02014b50u)
      return {"E_FORMAT", "zip: bad central directory entry"};
    uint32_t method = le16(zip, p + 10);
    uint32_t csize = le32(zip, p + 20);
    uint32_t usize = le32(zip, p + 24);
    uint32_t name_len = le16(zip, p + 28);
    uint32_t extra_len = le16(zip, p + 30);
    uint32_t comment_len = le16(zip, p + 32);
    uint32_t local_at = le32(zip, p + 42);
    if (p + 46 + name_len > eocd) return {"E_FORMAT", "zip: entry name out of bounds"};
    std::string name = zip.substr(p + 46, name_len);
    p += 46 + name_len + extra_len + comment_len;
    if (static_cast<uint64_t>(local_at) + 30 > n || le32(zip, local_at) != 0x04034b50u)
      return {"E_FORMAT", "zip: bad local header for '" + name + "'"};
    uint64_t data_at =
        static_cast<uint64_t>(local_at) + 30 + le16(zip, local_at + 26) + le16(zip, local_at + 28);
    if (data_at + csize > n) return {"E_FORMAT", "zip: member '" + name + "' truncated"};
    if (usize > max_member_bytes)
      return {"E_TOO_BIG", "zip: member '" + name + "' is " + std::to_string(usize) + " bytes"};
    std::string data;
    if (method == 0) {
      if (csize != usize) return {"E_FORMAT", "zip: stored member size mismatch"};
      data = zip.substr(data_at, csize);
    } else if (method == 8) {
      if (!inflate_raw(zip.data() + data_at, csize, usize, &data))
        return {"E_FORMAT", "zip: member '" + name + "' does not inflate (corrupt)"};
    } else {
      return {"E_FORMAT",
              "zip: member '" + name + "' uses unsupported compression " + std::to_string(method)};
    }
    (*members)[name] = std::move(data);
  }
  return {};
}

}  // namespace host::spi
