// Whole-file reading: every byte, across the read buffer; a directory or a missing file is
// "cannot open", not a huge allocation or an empty text.
#include "host/lib/drawing/file_text.h"

#include <gtest/gtest.h>
#include <unistd.h>  // getpid

#include <filesystem>  // std::filesystem::create_directories
#include <fstream>     // std::ofstream
#include <string>      // std::string

namespace host {
namespace {

std::string temp_path(const std::string& name) {
  return testing::TempDir() + "/" + std::to_string(getpid()) + "-" + name;
}

TEST(FileText, ReadsEveryByteOfAFileLargerThanItsBuffer) {
  std::string content;
  for (int i = 0; i < 200000; ++i) content.push_back(static_cast<char>((i * 7919) % 256));
  const std::string path = temp_path("file_text.bin");
  std::ofstream(path, std::ios::binary) << content;
  std::string text = "left over";
  ASSERT_EQ(read_file_text(path, &text), FileRead::kOk);
  EXPECT_EQ(text, content);
}

TEST(FileText, AnEmptyFileIsAnEmptyText) {
  const std::string path = temp_path("file_text_empty.txt");
  std::ofstream(path, std::ios::binary).close();
  std::string text = "left over";
  ASSERT_EQ(read_file_text(path, &text), FileRead::kOk);
  EXPECT_EQ(text, "");
}

TEST(FileText, ADirectoryOrAMissingFileCannotBeOpened) {
  const std::string dir = temp_path("file_text_dir.gbr");
  std::filesystem::create_directories(dir);
  std::string text;
  EXPECT_EQ(read_file_text(dir, &text), FileRead::kCannotOpen);
  EXPECT_EQ(read_file_text(temp_path("no_such_file.dxf"), &text), FileRead::kCannotOpen);
}

}  // namespace
}  // namespace host
