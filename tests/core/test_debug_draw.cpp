// DrawBuffer records every batch in order and replays it unchanged; the layer names are
// distinct (the capture format and the viewers key on them).
#include <gtest/gtest.h>

#include <proxima/core/debug_draw.hpp>

#include <set>
#include <string>

namespace proxima::test_debug_draw {

DrawLine line(Real x) { return {Vec3(x, 0, 0), Vec3(x, 1, 0), Rgba{1, 2, 3, 4}, {DrawLayer::Contacts, 0}}; }

TEST(DebugDraw, BufferRecordsBatchesInOrder) {
  DrawBuffer buffer;
  EXPECT_TRUE(buffer.empty());
  const DrawLine first[] = {line(1), line(2)};
  const DrawLine second[] = {line(3)};
  buffer.draw_lines(first);
  buffer.draw_lines(second);
  buffer.draw_lines({});
  ASSERT_EQ(buffer.lines.size(), 3u);
  EXPECT_EQ(buffer.lines[0].from.x, Real(1));
  EXPECT_EQ(buffer.lines[2].from.x, Real(3));
  EXPECT_EQ(buffer.lines[1].color, (Rgba{1, 2, 3, 4}));
  EXPECT_FALSE(buffer.empty());
  buffer.clear();
  EXPECT_TRUE(buffer.empty());
}

TEST(DebugDraw, ReplayCopiesEveryKind) {
  DrawBuffer source;
  const DrawLine l[] = {line(5)};
  const DrawTriangle t[] = {{Vec3(0), Vec3(1, 0, 0), Vec3(0, 1, 0), Rgba{9, 9, 9, 255}, {DrawLayer::Shapes, 0}}};
  const DrawPoint p[] = {{Vec3(2), Real(6), Rgba{}, {DrawLayer::Contacts, 0}}};
  const DrawBox b[] = {{Vec3(1), Vec3(2), kIdentityQuat, Rgba{}, {DrawLayer::Bvh, 3}}};
  const DrawText x[] = {{Vec3(0), "label", Rgba{}, {DrawLayer::Text, 0}}};
  source.draw_lines(l);
  source.draw_triangles(t);
  source.draw_points(p);
  source.draw_boxes(b);
  source.draw_texts(x);
  DrawBuffer copy;
  source.replay(copy);
  ASSERT_EQ(copy.lines.size(), 1u);
  ASSERT_EQ(copy.triangles.size(), 1u);
  ASSERT_EQ(copy.points.size(), 1u);
  ASSERT_EQ(copy.boxes.size(), 1u);
  ASSERT_EQ(copy.texts.size(), 1u);
  EXPECT_EQ(copy.boxes[0].tag, (DrawTag{DrawLayer::Bvh, 3}));
  EXPECT_EQ(copy.texts[0].text, "label");
  EXPECT_EQ(copy.points[0].size, Real(6));
}

TEST(DebugDraw, LayerNamesAreDistinct) {
  std::set<std::string> names;
  for (int i = 0; i < kDrawLayerCount; ++i) names.emplace(to_string(static_cast<DrawLayer>(i)));
  EXPECT_EQ(names.size(), static_cast<std::size_t>(kDrawLayerCount));
  EXPECT_EQ(to_string(DrawLayer::BroadPhase), "broadphase");
  EXPECT_EQ(to_string(DrawLayer::User), "user");
}

}  // namespace proxima::test_debug_draw
