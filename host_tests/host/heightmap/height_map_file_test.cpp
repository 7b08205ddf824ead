// The height map file: what it holds, what it refuses, and the interpolation of its grid.
#include <gtest/gtest.h>

#include <cstdio>      // std::remove
#include <filesystem>  // temp_directory_path
#include <string>      // std::string

#include "host/lib/heightmap/height_map.h"

namespace host::heightmap {
namespace {

HeightMap three_by_two() {
  HeightMap m;
  m.origin_x_mm = 4;
  m.origin_y_mm = 5;
  m.pitch_x_mm = 10;
  m.pitch_y_mm = 20;
  m.rows = 2;
  m.cols = 3;
  m.heights_um = {0, 10, 20, 30, 40, 50.5};
  m.repeatability_um = 1.5;
  m.probed_at = "2026-11-27T19:50:00Z";
  m.blank = "blank 1";
  return m;
}

const char* const kThreeByTwo = R"({
  "format": "engraver height map",
  "version": 1,
  "units": {"height":"um","xy":"mm"},
  "grid": {"cols":3,"origin_mm":[4.0,5.0],"pitch_mm":[10.0,20.0],"rows":2},
  "heights_um": [
    [0.0,10.0,20.0],
    [30.0,40.0,50.5]
  ],
  "repeatability_um": 1.5,
  "probed_at": "2026-11-27T19:50:00Z",
  "blank": "blank 1"
}
)";

TEST(HeightMapFile, WritesOneRowOfHeightsALine) {
  EXPECT_EQ(height_map_text(three_by_two()), kThreeByTwo);
}

TEST(HeightMapFile, ReadsBackWhatItWrote) {
  const HeightMap m = read_height_map_text(kThreeByTwo, "map.json");
  EXPECT_EQ(m.rows, 2);
  EXPECT_EQ(m.cols, 3);
  EXPECT_DOUBLE_EQ(m.origin_x_mm, 4);
  EXPECT_DOUBLE_EQ(m.pitch_y_mm, 20);
  EXPECT_DOUBLE_EQ(m.height_um(1, 2), 50.5);
  EXPECT_DOUBLE_EQ(*m.repeatability_um, 1.5);
  EXPECT_EQ(m.blank, "blank 1");
  EXPECT_EQ(height_map_text(m), kThreeByTwo);
}

TEST(HeightMapFile, ThroughADisk) {
  const std::string path =
      (std::filesystem::temp_directory_path() / "height_map_file_test.json").string();
  write_height_map_file(three_by_two(), path);
  EXPECT_EQ(height_map_text(read_height_map_file(path)), kThreeByTwo);
  std::remove(path.c_str());
  try {
    read_height_map_file(path);
    FAIL() << "a missing file was read";
  } catch (const HeightMapError& e) {
    EXPECT_EQ(std::string(e.what()), path + ": cannot open the height map");
  }
}

// What a broken file is told, field by field (text replaced in the good file).
struct BadCase {
  std::string from, to, message;
};

TEST(HeightMapFile, RefusesEachBrokenFieldByName) {
  const BadCase cases[] = {
      {"\"version\": 1", "\"version\": 2",
       "m.json: version 2 is not known here (this engraver reads version 1)"},
      {"\"format\": \"engraver height map\"", "\"format\": \"csv\"",
       "m.json: 'format' must be \"engraver height map\""},
      {"\"height\":\"um\"", "\"height\":\"mm\"",
       "m.json: 'units' must be {\"xy\": \"mm\", \"height\": \"um\"}"},
      {"\"rows\":2", "\"rows\":3", "m.json: 'heights_um' must be 3 rows (grid.rows)"},
      {"[30.0,40.0,50.5]", "[30.0,40.0]",
       "m.json: 'heights_um' row 1 must have 3 heights (grid.cols)"},
      {"[30.0,40.0,50.5]", "[30.0,\"x\",50.5]", "m.json: 'heights_um[1][1]' must be a number"},
      {"\"pitch_mm\":[10.0,20.0]", "\"pitch_mm\":[10.0,0]",
       "m.json: the grid's pitch (10, 0) mm must be above 0"},
      {"\"pitch_mm\":[10.0,20.0]", "\"pitch_mm\":[10.0]", "m.json: 'grid.pitch_mm' must be [x, y]"},
      {"\"blank\": \"blank 1\"", "\"blank\": \"blank 1\", \"colour\": 1",
       "m.json: unknown key 'colour'"},
      {"\"cols\":3,", "", "m.json: 'grid.cols' is missing"},
      {"\"rows\":2", "\"rows\":2.5", "m.json: 'grid.rows' must be a whole number"},
      {"[0.0,10.0,20.0]", "[0.0,10.0,1020.0]",
       "m.json: the heights span 1020.0 um with Z 0, more than the 1000 um a blank may be out "
       "of flat (clamp it flat, check the probe clip)"},
      {"[0.0,10.0,20.0]", "[-990.0,10.0,20.0]",  // 50.5 above Z 0, 990 below
       "m.json: the heights span 1040.5 um with Z 0, more than the 1000 um a blank may be out "
       "of flat (clamp it flat, check the probe clip)"},
      {"\"pitch_mm\":[10.0,20.0]", "\"pitch_mm\":[70.0,20.0]",
       "m.json: the grid's pitch (70, 20) mm is outside the controller's 1 .. 65.535 mm"},
      {"\"repeatability_um\": 1.5", "\"repeatability_um\": -1",
       "m.json: repeatability_um must be 0 or above"},
      {"{", "[", ""},  // not JSON: the parser's words follow
  };
  for (const BadCase& c : cases) {
    std::string text = kThreeByTwo;
    const size_t at = text.find(c.from);
    ASSERT_NE(at, std::string::npos) << c.from;
    text.replace(at, c.from.size(), c.to);
    try {
      read_height_map_text(text, "m.json");
      ADD_FAILURE() << "read with " << c.to;
    } catch (const HeightMapError& e) {
      if (c.message.empty())
        EXPECT_EQ(std::string(e.what()).rfind("m.json: not JSON", 0), 0u) << e.what();
      else
        EXPECT_EQ(e.what(), c.message);
    }
  }
}

// JSON allows any number; 1e400 is beyond a double (the parser's out_of_range): bad input,
// refused with the file's name like any other broken field, never an internal error.
TEST(HeightMapFile, RefusesANumberBeyondADouble) {
  for (const char* huge : {"1e400", "-1e400"}) {
    std::string text = kThreeByTwo;
    text.replace(text.find("50.5]"), 4, huge);
    try {
      read_height_map_text(text, "m.json");
      ADD_FAILURE() << "read " << huge;
    } catch (const HeightMapError& e) {
      EXPECT_EQ(std::string(e.what()).rfind("m.json: a number beyond the range", 0), 0u)
          << e.what();
    }
  }
}

// A key given twice would take its last value without a word (a second heights_um
// replacing the probed one): refused by name, at the top and inside "grid".
TEST(HeightMapFile, RefusesAKeyGivenTwice) {
  const std::pair<const char*, const char*> cases[] = {
      {"  \"repeatability_um\"", "  \"heights_um\": [[0,0,0],[0,0,0]],\n  \"repeatability_um\""},
      {"\"rows\":2}", "\"rows\":2,\"rows\":2}"},
      {"\"version\": 1,", "\"version\": 1, \"version\": 1,"}};
  const char* const names[] = {"heights_um", "rows", "version"};
  for (size_t k = 0; k < std::size(cases); ++k) {
    std::string text = kThreeByTwo;
    text.replace(text.find(cases[k].first), std::string(cases[k].first).size(), cases[k].second);
    try {
      read_height_map_text(text, "m.json");
      ADD_FAILURE() << "read a map with " << names[k] << " twice";
    } catch (const HeightMapError& e) {
      EXPECT_EQ(std::string(e.what()),
                std::string("m.json: key '") + names[k] + "' given more than once");
    }
  }
}

TEST(HeightMapFile, RefusesAGridLargerThanTheControllerKeeps) {
  HeightMap m = three_by_two();
  m.cols = 17;
  m.heights_um.assign(34, 0.0);
  EXPECT_THROW(validate(m, "m"), HeightMapError);
  m.cols = 16;
  m.heights_um.assign(32, 0.0);
  EXPECT_NO_THROW(validate(m, "m"));
}

TEST(HeightMapInterpolation, BilinearInsideNearestEdgeOutside) {
  const HeightMap m = three_by_two();
  EXPECT_DOUBLE_EQ(m.interpolate_um(4, 5), 0);           // a grid point
  EXPECT_DOUBLE_EQ(m.interpolate_um(24, 25), 50.5);      // the far corner
  EXPECT_DOUBLE_EQ(m.interpolate_um(9, 5), 5);           // between columns
  EXPECT_DOUBLE_EQ(m.interpolate_um(4, 15), 15);         // between rows
  EXPECT_DOUBLE_EQ(m.interpolate_um(9, 15), 20);         // a cell's middle: the 4 points' mean
  EXPECT_DOUBLE_EQ(m.interpolate_um(-100, 5), 0);        // left of the map: its edge
  EXPECT_DOUBLE_EQ(m.interpolate_um(14, 100), 40);       // above: the top edge
  EXPECT_DOUBLE_EQ(m.interpolate_um(1000, 1000), 50.5);  // beyond a corner: the corner
  EXPECT_TRUE(m.covers(24, 25));
  EXPECT_FALSE(m.covers(24.01, 25));
  EXPECT_FALSE(m.covers(3.99, 5));
}

}  // namespace
}  // namespace host::heightmap
