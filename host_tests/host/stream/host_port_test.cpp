// ADDR:PORT, the one reader and writer of the tool's TCP addresses (sim and serve --listen,
// send --to tcp://).
#include "host/lib/stream/host_port.h"

#include <gtest/gtest.h>

#include <stdexcept>  // std::invalid_argument
#include <string>     // std::string

namespace host {
namespace {

// What parse_host_port says about `text`, "" when it takes it.
std::string refusal(const std::string& text, PortUse use) {
  try {
    parse_host_port(text, use);
    return "";
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
}

TEST(HostPort, ABracketedIpv6AddressIsReadWithoutItsBrackets) {
  const HostPort listen = parse_host_port("[::1]:47907", PortUse::kListen);
  EXPECT_EQ(listen.host, "::1");
  EXPECT_EQ(listen.port, 47907);
  EXPECT_EQ(parse_host_port("[::]:0", PortUse::kListen).host, "::");
  EXPECT_EQ(parse_host_port("[fe80::1%lo]:80", PortUse::kConnect).host, "fe80::1%lo");
}

TEST(HostPort, AnIpv4AddressOrAHostName) {
  const HostPort v4 = parse_host_port("127.0.0.1:0080", PortUse::kListen);
  EXPECT_EQ(v4.host, "127.0.0.1");
  EXPECT_EQ(v4.port, 80);  // leading zeros are decimal ones
  EXPECT_EQ(parse_host_port("xport.local:10001", PortUse::kConnect).host, "xport.local");
}

TEST(HostPort, AnIpv6AddressIsWrittenInBrackets) {
  EXPECT_EQ(host_port_text("::1", 47912), "[::1]:47912");
  EXPECT_EQ(host_port_text("127.0.0.1", 8080), "127.0.0.1:8080");
  EXPECT_EQ(host_port_text("xport.local", 10001), "xport.local:10001");
}

TEST(HostPort, ThePortIsDecimalDigitsInItsRange) {
  for (const char* bad : {"127.0.0.1:65536", "127.0.0.1:80x", "127.0.0.1:-80", "127.0.0.1:+80",
                          "127.0.0.1: 80", "127.0.0.1:", "127.0.0.1:99999999999999999999"}) {
    EXPECT_EQ(refusal(bad, PortUse::kListen), "the port must be 0 .. 65535 (0: any free port)")
        << bad;
  }
  EXPECT_EQ(parse_host_port("127.0.0.1:0", PortUse::kListen).port, 0);
  EXPECT_EQ(refusal("127.0.0.1:0", PortUse::kConnect), "the port must be 1 .. 65535");
  EXPECT_EQ(parse_host_port("127.0.0.1:65535", PortUse::kConnect).port, 65535);
}

TEST(HostPort, WhatIsNotAnAddressAndAPortSaysWhy) {
  EXPECT_EQ(refusal("", PortUse::kListen),
            "expected ADDR:PORT (e.g. 127.0.0.1:10001, or [::1]:10001 for IPv6)");
  EXPECT_EQ(refusal("[::1]", PortUse::kListen),
            "expected ADDR:PORT (e.g. 127.0.0.1:10001, or [::1]:10001 for IPv6)");
  EXPECT_EQ(refusal("[::1:80", PortUse::kListen),
            "'[' without its ']' (an IPv6 address in brackets: [::1]:10001)");
  EXPECT_EQ(refusal("::1:47907", PortUse::kListen),
            "an IPv6 address goes in brackets, as in a URL: [::1]:47907");
  EXPECT_EQ(refusal("[127.0.0.1]:80", PortUse::kConnect),
            "'[127.0.0.1]' is not an IPv6 address (only an IPv6 address goes in brackets: "
            "[::1]:80)");
  EXPECT_EQ(refusal("127.0.0.1:47801:5", PortUse::kConnect),
            "'127.0.0.1:47801' is not a host name or address");
  EXPECT_EQ(refusal("a b:80", PortUse::kConnect), "'a b' is not a host name or address");
  EXPECT_EQ(refusal(":80", PortUse::kConnect), "no host before the port");
  EXPECT_EQ(refusal(":80", PortUse::kListen),
            "no address before the port (e.g. 127.0.0.1:80, or 0.0.0.0:80 for every interface)");
}

// A listening socket binds one of this PC's addresses: a name is not looked up.
TEST(HostPort, ListeningTakesANumericAddressOnly) {
  EXPECT_EQ(refusal("localhost:8080", PortUse::kListen),
            "listen address 'localhost' is not a numeric address (e.g. 127.0.0.1, 0.0.0.0 for "
            "every interface, [::1], [::])");
  EXPECT_EQ(refusal("localhost:8080", PortUse::kConnect), "");
}

}  // namespace
}  // namespace host
