// Zip uploads (see zip_upload.h).
#include "host/lib/server/zip_upload.h"

#include <fmt/format.h>  // fmt::format

#include <zip.h>  // libzip

namespace host::server {

bool looks_like_zip(const std::string& bytes) {
  return bytes.compare(0, 4, std::string("PK\x03\x04", 4)) == 0;
}

namespace {

// The last part of an entry's name ("gerber/a-F.Cu.gbr" -> "a-F.Cu.gbr"); "" for a folder
// or something to leave out (hidden files, macOS resource forks).
std::string entry_file_name(const std::string& entry) {
  if (entry.empty() || entry.back() == '/' || entry.back() == '\\') return "";
  if (entry.rfind("__MACOSX/", 0) == 0) return "";
  const size_t slash = entry.find_last_of("/\\");
  const std::string name = slash == std::string::npos ? entry : entry.substr(slash + 1);
  return name.empty() || name[0] == '.' ? "" : name;
}

// An absolute name, a drive, or a ".." part: an entry made to be unpacked elsewhere.
bool points_outside(const std::string& entry) {
  if (entry.empty()) return false;
  if (entry[0] == '/' || entry[0] == '\\' || entry.find(':') != std::string::npos) return true;
  size_t start = 0;
  while (start <= entry.size()) {
    const size_t end = entry.find_first_of("/\\", start);
    if (entry.substr(start, end == std::string::npos ? end : end - start) == "..") return true;
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return false;
}

struct Archive {
  zip_t* zip = nullptr;
  ~Archive() {
    if (zip != nullptr) zip_discard(zip);
  }
};

}  // namespace

std::vector<UploadFile> unzip_upload(const std::string& bytes, const std::string& zip_name,
                                     size_t max_bytes, size_t max_entries) {
  zip_error_t error;
  zip_error_init(&error);
  zip_source_t* source = zip_source_buffer_create(bytes.data(), bytes.size(), 0, &error);
  Archive a;
  if (source != nullptr) {
    a.zip = zip_open_from_source(source, ZIP_RDONLY | ZIP_CHECKCONS, &error);
    if (a.zip == nullptr) zip_source_free(source);
  }
  if (a.zip == nullptr) {
    const std::string why = zip_error_strerror(&error);
    zip_error_fini(&error);
    throw ZipError(fmt::format("{}: not a readable zip file: {}", zip_name, why), false);
  }
  zip_error_fini(&error);
  const zip_int64_t entries = zip_get_num_entries(a.zip, 0);
  if (entries < 0 || static_cast<size_t>(entries) > max_entries) {
    throw ZipError(fmt::format("{}: {} entries, more than {}", zip_name, entries, max_entries),
                   false);
  }
  std::vector<UploadFile> files;
  size_t total = 0;
  for (zip_int64_t i = 0; i < entries; ++i) {
    const char* entry = zip_get_name(a.zip, static_cast<zip_uint64_t>(i), ZIP_FL_ENC_GUESS);
    if (entry != nullptr && points_outside(entry)) {
      throw ZipError(fmt::format("{}: entry '{}' points outside the zip", zip_name, entry), false);
    }
    const std::string name = entry_file_name(entry != nullptr ? entry : "");
    if (name.empty()) continue;
    zip_file_t* f = zip_fopen_index(a.zip, static_cast<zip_uint64_t>(i), 0);
    if (f == nullptr) {
      throw ZipError(
          fmt::format("{}: {}: cannot be unpacked: {}", zip_name, entry, zip_strerror(a.zip)),
          false);
    }
    UploadFile file{name, ""};
    char buffer[16384];
    zip_int64_t got = 0;
    while ((got = zip_fread(f, buffer, sizeof(buffer))) > 0) {
      total += static_cast<size_t>(got);
      if (total > max_bytes) {
        zip_fclose(f);
        throw ZipError(
            fmt::format("{}: more than the limit of {} bytes once unpacked", zip_name, max_bytes),
            true);
      }
      file.content.append(buffer, static_cast<size_t>(got));
    }
    const std::string why = got < 0 ? zip_file_strerror(f) : "";
    zip_fclose(f);
    if (got < 0) throw ZipError(fmt::format("{}: {}: damaged: {}", zip_name, entry, why), false);
    files.push_back(std::move(file));
  }
  return files;
}

}  // namespace host::server
