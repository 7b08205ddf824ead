// The height map example in docs/user-guide.md reads as printed, and --surface examples parse.
#include <gtest/gtest.h>

#include <fstream>  // std::ifstream
#include <sstream>  // std::stringstream

#include "host/lib/heightmap/height_map.h"
#include "host/lib/heightmap/surface_model.h"

namespace host::heightmap {
namespace {

std::string guide() {
  std::ifstream in(std::string(ENGRAVER_SOURCE_DIR) + "/docs/user-guide.md");
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

// The indented block after `heading`, its indent taken off.
std::string block_after(const std::string& text, const std::string& heading) {
  size_t at = text.find(heading);
  if (at == std::string::npos) return "";
  at = text.find("\n    ", at);
  std::string out;
  while (at != std::string::npos && text.compare(at, 5, "\n    ") == 0) {
    const size_t end = text.find('\n', at + 1);
    out += text.substr(at + 5, end - at - 5) + "\n";
    at = end;
  }
  return out;
}

TEST(GuideHeightMap, TheMapFileExampleReadsAsPrinted) {
  const std::string example = block_after(guide(), "### The map file");
  ASSERT_FALSE(example.empty());
  const HeightMap m = read_height_map_text(example, "the guide's example");
  EXPECT_EQ(m.rows, 2);
  EXPECT_EQ(m.cols, 3);
  EXPECT_DOUBLE_EQ(m.height_um(1, 2), 52.3);
  EXPECT_EQ(height_map_text(m), example);  // the writer writes it the same way
}

TEST(GuideHeightMap, TheSurfaceExamplesParse) {
  const std::string text = block_after(guide(), "### The simulated warped blank");
  ASSERT_FALSE(text.empty());
  size_t n = 0;
  for (size_t at = text.find("--surface "); at != std::string::npos;
       at = text.find("--surface ", at + 1)) {
    const size_t start = at + 10, end = text.find(' ', start);
    EXPECT_NO_THROW(parse_surface_spec(text.substr(start, end - start)));
    ++n;
  }
  EXPECT_EQ(n, 2u);
}

}  // namespace
}  // namespace host::heightmap
