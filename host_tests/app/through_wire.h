// Test helper: a message encoded and decoded through the codec, as the wire carries it.
#ifndef HOST_TESTS_APP_THROUGH_WIRE_H
#define HOST_TESTS_APP_THROUGH_WIRE_H

#include <gtest/gtest.h>

#include "firmware/protocol/codec.h"  // encode, decode

namespace test {

template <typename Msg>
Msg through_wire(const Msg& m) {
  proto::Payload p;
  EXPECT_EQ(proto::encode(m, &p), proto::ErrorCode::kOk);
  Msg back;
  EXPECT_EQ(proto::decode(p.bytes, p.length, &back), proto::ErrorCode::kOk);
  return back;
}

}  // namespace test

#endif  // HOST_TESTS_APP_THROUGH_WIRE_H
