// A fresh folder under the temp directory for what a test writes, removed with the object
// (files named by pid alone outlived the tests that wrote them).
#ifndef HOST_TESTS_HOST_TEMP_DIR_H
#define HOST_TESTS_HOST_TEMP_DIR_H

#include <stdlib.h>  // mkdtemp

#include <filesystem>  // std::filesystem
#include <stdexcept>   // std::runtime_error
#include <string>      // std::string

namespace host::test {

class TempDir {
 public:
  // The folder is named `prefix` and six random characters.
  explicit TempDir(const std::string& prefix = "engraver-test-") {
    std::string tmpl = (std::filesystem::temp_directory_path() / (prefix + "XXXXXX")).string();
    if (mkdtemp(&tmpl[0]) == nullptr) throw std::runtime_error("mkdtemp failed: " + tmpl);
    path_ = tmpl;
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  // A file in the folder.
  std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

}  // namespace host::test

#endif  // HOST_TESTS_HOST_TEMP_DIR_H
