// The height map as the controller takes it: #A then #E frames of 8 heights, decoded back.
#include "host/lib/heightmap/controller_map.h"

#include <gtest/gtest.h>

#include "firmware/protocol/codec.h"
#include "firmware/protocol/messages.h"

namespace host::heightmap {
namespace {

template <typename Msg>
Msg decoded(const QueuedCommand& c) {
  EXPECT_EQ(c.letter, static_cast<uint8_t>(Msg::kLetter));
  proto::Frame f{};
  f.start = proto::kCommandStart;
  f.letter = c.letter;
  f.length = static_cast<uint8_t>(c.payload.size());
  f.payload = c.payload.data();
  Msg m{};
  EXPECT_EQ(proto::decode_frame(f, &m), proto::ErrorCode::kOk);
  return m;
}

TEST(ControllerMap, HeaderThenEightHeightsAFrameRowByRow) {
  HeightMap m;
  m.origin_x_mm = 4.0;
  m.origin_y_mm = 3.5;
  m.pitch_x_mm = 9.1111;
  m.pitch_y_mm = 8.8571;
  m.rows = 3;
  m.cols = 7;
  for (int i = 0; i < 21; ++i) m.heights_um.push_back(i * 10.4 - 50);
  const std::vector<QueuedCommand> c = height_map_commands(m);
  ASSERT_EQ(c.size(), 4u);  // the header and 21 heights in 8 + 8 + 5
  const proto::HeightMapHeaderCmd h = decoded<proto::HeightMapHeaderCmd>(c[0]);
  EXPECT_EQ(h.cols, 7);
  EXPECT_EQ(h.rows, 3);
  EXPECT_EQ(h.x0_um, 4000);
  EXPECT_EQ(h.y0_um, 3500);
  EXPECT_EQ(h.pitch_x_um, 9111);
  EXPECT_EQ(h.pitch_y_um, 8857);
  size_t next = 0;
  for (size_t k = 1; k < c.size(); ++k) {
    const proto::HeightMapDataCmd d = decoded<proto::HeightMapDataCmd>(c[k]);
    EXPECT_EQ(d.index, next);
    EXPECT_EQ(d.height_n, k < 3 ? 8 : 5);
    for (int i = 0; i < d.height_n; ++i)
      EXPECT_EQ(d.height_um[i], std::lround(m.heights_um[next + i])) << next + i;
    next += d.height_n;
  }
  EXPECT_EQ(next, 21u);
}

TEST(ControllerMap, AnInvalidMapIsNotSent) {
  HeightMap m;
  m.rows = m.cols = 2;
  m.pitch_x_mm = m.pitch_y_mm = 10;
  m.heights_um = {0, 0, 0, 1500};
  EXPECT_THROW(height_map_commands(m), HeightMapError);
}

TEST(ControllerMap, ClearingIsAnEmptyHeader) {
  const proto::HeightMapHeaderCmd h =
      decoded<proto::HeightMapHeaderCmd>(clear_height_map_command());
  EXPECT_EQ(h.cols, 0);
  EXPECT_EQ(h.rows, 0);
}

}  // namespace
}  // namespace host::heightmap
