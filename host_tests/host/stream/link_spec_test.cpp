// --to link specs: the accepted forms and precise errors for the rest.
#include <gtest/gtest.h>

#include "host/lib/stream/link.h"

namespace host {
namespace {

TEST(LinkSpec, TcpHostAndPort) {
  const LinkSpec s = parse_link_spec("tcp://192.0.2.7:10001");
  EXPECT_EQ(s.kind, LinkSpec::kTcp);
  EXPECT_EQ(s.host, "192.0.2.7");
  EXPECT_EQ(s.port, 10001);
}

TEST(LinkSpec, TcpBracketedIpv6) {
  const LinkSpec s = parse_link_spec("tcp://[::1]:5000");
  EXPECT_EQ(s.host, "::1");
  EXPECT_EQ(s.port, 5000);
}

TEST(LinkSpec, SerialDefaultsTo115200) {
  const LinkSpec s = parse_link_spec("serial:/dev/ttyUSB0");
  EXPECT_EQ(s.kind, LinkSpec::kSerial);
  EXPECT_EQ(s.device, "/dev/ttyUSB0");
  EXPECT_EQ(s.baud, 115200u);
}

TEST(LinkSpec, SerialWithBaud) {
  EXPECT_EQ(parse_link_spec("serial:/dev/ttyS1,57600").baud, 57600u);
}

// A port is decimal, leading zeros too (as in a URL): ten digits were "not a number".
TEST(LinkSpec, APortWithLeadingZerosIsDecimal) {
  EXPECT_EQ(parse_link_spec("tcp://127.0.0.1:0080").port, 80);
  EXPECT_EQ(parse_link_spec("tcp://127.0.0.1:0000000000080").port, 80);
  EXPECT_EQ(parse_link_spec("serial:/dev/ttyS1,00057600").baud, 57600u);
  try {
    parse_link_spec("tcp://127.0.0.1:00000000000070000");
    FAIL() << "no error";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("'tcp://127.0.0.1:00000000000070000': the port must be "
                                         "1 .. 65535"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(parse_link_spec("tcp://127.0.0.1:0000"), LinkError);  // port 0
}

TEST(LinkSpec, RejectsWhatItCannotUse) {
  EXPECT_THROW(parse_link_spec("udp://host:1"), LinkError);
  EXPECT_THROW(parse_link_spec("tcp://host"), LinkError);
  // Extra colons or a blank (issue 24's tester: planned, then "cannot resolve host", exit 6).
  EXPECT_THROW(parse_link_spec("tcp://127.0.0.1:47801:5"), LinkError);
  EXPECT_THROW(parse_link_spec("tcp://127.0.0.1::47801"), LinkError);
  EXPECT_THROW(parse_link_spec("tcp://a b:47801"), LinkError);
  EXPECT_THROW(parse_link_spec("tcp://host:0"), LinkError);
  EXPECT_THROW(parse_link_spec("tcp://host:70000"), LinkError);
  EXPECT_THROW(parse_link_spec("tcp://host:12ab"), LinkError);
  EXPECT_THROW(parse_link_spec("serial:"), LinkError);
  EXPECT_THROW(parse_link_spec("serial:/dev/ttyS0,fast"), LinkError);
}

TEST(LinkSpec, ErrorNamesTheSpecAndTheForms) {
  try {
    parse_link_spec("ftp://x:1");
    FAIL() << "no error";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("ftp://x:1"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("tcp://HOST:PORT"), std::string::npos);
  }
}

TEST(Link, ConnectToAClosedPortFailsWithTheLinkName) {
  // Port 1 on loopback: nothing listens there in a test environment.
  try {
    open_link(parse_link_spec("tcp://127.0.0.1:1"), std::chrono::milliseconds(500));
    FAIL() << "connected";
  } catch (const LinkError& e) {
    EXPECT_NE(std::string(e.what()).find("tcp://127.0.0.1:1"), std::string::npos);
  }
}

}  // namespace
}  // namespace host
