// The Host header check: requests naming another site's host are refused before any handler
// (DNS rebinding), the server's own names and addresses are served.
#include "host/lib/server/allowed_hosts.h"

#include <gtest/gtest.h>
#include <unistd.h>  // gethostname

#include "host_tests/host/server/server_test_rig.h"

namespace host::server {
namespace {

TEST(AllowedHosts, LoopbackServerAnswersItsLoopbackNamesOnly) {
  const AllowedHosts hosts("127.0.0.1", {});
  for (const char* ok : {"127.0.0.1", "127.0.0.1:8080", "localhost:8080", "LOCALHOST",
                         "localhost.:8080", "[::1]:8080"}) {
    EXPECT_TRUE(hosts.allows(ok)) << ok;
  }
  for (const char* bad :
       {"", "evil.example", "evil.example:8080", "127.0.0.1.evil.example", "localhost.evil.example",
        "192.168.1.7:8080", "[::1", "::1", "127.0.0.1 evil.example"}) {
    EXPECT_FALSE(hosts.allows(bad)) << bad;
  }
}

TEST(AllowedHosts, AllAddressesAddTheHostNameAndAllowedHostAddsNames) {
  char name[256] = {};
  ASSERT_EQ(gethostname(name, sizeof name - 1), 0);
  EXPECT_TRUE(AllowedHosts("0.0.0.0", {}).allows(std::string(name) + ":8080"));
  EXPECT_TRUE(AllowedHosts("0.0.0.0", {}).allows("127.0.0.1:8080"));
  EXPECT_FALSE(AllowedHosts("0.0.0.0", {}).allows("evil.example"));
  EXPECT_TRUE(AllowedHosts("192.168.1.7", {}).allows("192.168.1.7:8080"));
  const AllowedHosts named("127.0.0.1", {"workshop.example", "[fd00::7]"});
  EXPECT_TRUE(named.allows("Workshop.Example:8080"));
  EXPECT_TRUE(named.allows("[fd00::7]:8080"));
  EXPECT_FALSE(named.allows("shop.example"));
}

// A Host naming another port than the server's is another origin (a page on that port,
// forwarded here): refused, unless that NAME:PORT was allowed (a proxy in front). No port
// is the scheme's default (a proxy, or the server on 80). A port that is no port is refused.
TEST(AllowedHosts, APortInTheHostMustBeTheServersOwn) {
  AllowedHosts hosts("127.0.0.1", {"workshop.example:443"});
  hosts.set_port(8080);
  for (const char* ok : {"127.0.0.1:8080", "localhost:8080", "[::1]:8080", "localhost",
                         "workshop.example", "workshop.example:8080", "workshop.example:443"}) {
    EXPECT_TRUE(hosts.allows(ok)) << ok;
  }
  for (const char* bad : {"127.0.0.1:9999", "localhost:80", "[::1]:8081", "localhost:443",
                          "localhost:", "localhost:80a", "localhost:0", "localhost:65536",
                          "localhost:+8080", "[::1]:", "[::1]x"}) {
    EXPECT_FALSE(hosts.allows(bad)) << bad;
  }
  EXPECT_NE(hosts.describe().find("localhost:8080"), std::string::npos) << hosts.describe();
  EXPECT_NE(hosts.describe().find("workshop.example:443"), std::string::npos);
}

TEST(AllowedHosts, TheServerRefusesAHostWithAnotherPort) {
  test::TempDir dir;
  test::ServerRig server(dir.path(), {});
  auto client = server.client();
  const int other = server.port() == 65535 ? 65534 : server.port() + 1;
  auto r = client.Get("/api/jobs", {{"Host", fmt::format("127.0.0.1:{}", other)}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 403) << r->body;
  EXPECT_NE(r->body.find(fmt::format("127.0.0.1:{}", server.port())), std::string::npos)
      << r->body;  // the message names the server's own
  r = client.Get("/api/jobs", {{"Host", fmt::format("127.0.0.1:{}", server.port())}});
  ASSERT_TRUE(r);
  EXPECT_EQ(r->status, 200) << r->body;
}

TEST(AllowedHosts, TheServerRefusesAnotherHostBeforeAnyHandler) {
  test::TempDir dir;
  test::ServerRig server(dir.path(), {});
  const int64_t id = server.upload_ok("a.ngc", test::square_gcode(10, 10, 10));
  auto client = server.client();
  const std::string port = std::to_string(server.port());
  for (const std::string& host : {"evil.example:" + port, "127.0.0.1.evil.example:" + port}) {
    const httplib::Headers h = {{"Host", host}};
    // (No /api/events here: served, it would never end; the check is the same for all.)
    for (const char* path :
         {"/", "/api/status", "/api/jobs", "/api/jobs/1", "/api/jobs/1/files/input.ngc"}) {
      auto r = client.Get(path, h);
      ASSERT_TRUE(r) << path;
      EXPECT_EQ(r->status, 403) << host << path;
      EXPECT_NE(r->body.find("not a name of this server"), std::string::npos) << r->body;
      EXPECT_EQ(r->body.find("G1"), std::string::npos) << r->body;  // not the drawing
    }
    // With the token too: the check comes first.
    httplib::Headers with_token = server.auth();
    with_token.emplace("Host", host);
    auto r = client.Post(fmt::format("/api/jobs/{}/control", id).c_str(), with_token,
                         R"({"action": "cancel"})", "application/json");
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 403);
  }
  EXPECT_EQ(server.job(id)["state"], "queued");
  for (const std::string& host : {"localhost:" + port, "127.0.0.1:" + port, "[::1]:" + port}) {
    auto r = client.Get("/api/jobs", {{"Host", host}});
    ASSERT_TRUE(r);
    EXPECT_EQ(r->status, 200) << host;
  }
}

}  // namespace
}  // namespace host::server
