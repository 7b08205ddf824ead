// `engraver` starts without the server's libraries: they are engraver-serve's alone
// (docs/performance.md, "Start-up"), so `board`, `run` and the rest load and relocate
// only what they call.
#include <gtest/gtest.h>

#include <string>  // std::string

#include "host_tests/host/cli/tool_run.h"

namespace {

TEST(Startup, EngraverNeedsNoneOfTheServersLibraries) {
  // The dynamic section's NEEDED entries, as the loader reads them.
  const host_tests::ToolRun r = host_tests::run_tool("readelf", std::string("-d ") + ENGRAVER_EXE);
  if (r.code != 0 || r.out.find("(NEEDED)") == std::string::npos)
    GTEST_SKIP() << "readelf (binutils) is not here: " << r.err;
  for (const char* lib : {"libsqlite3", "libpq", "libcpp-httplib", "libzip", "libssl"})
    EXPECT_EQ(r.out.find(lib), std::string::npos) << lib << " in\n" << r.out;
  // The server itself: engraver-serve beside it, with the libraries it needs.
  const std::string exe = ENGRAVER_EXE;
  const host_tests::ToolRun s =
      host_tests::run_tool("readelf", "-d " + exe.substr(0, exe.rfind('/') + 1) + "engraver-serve");
  ASSERT_EQ(s.code, 0) << s.err;
  EXPECT_NE(s.out.find("libsqlite3"), std::string::npos) << s.out;
}

}  // namespace
