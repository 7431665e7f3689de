#pragma once
/// @file debug_draw.hpp
/// The debug-draw interface: what any layer of the library may emit to show its state
/// (shapes, bounds, hierarchy nodes, contacts, sweeps, rays), and a buffer that records it.
///
/// Drawing is batched: a sink receives spans of primitives (lines, triangles, points, boxes,
/// text), never one virtual call per line, so an emitter fills a small array and hands it
/// over at once. Every primitive carries its own colour and a tag (a layer, and a level
/// within it: a hierarchy's depth), so that a viewer can toggle what it shows.
///
/// Frames and units: every position is in the world frame (the frame of the poses given to
/// the emitters), in the library's length units; the library draws nothing itself. The
/// emitters live in `proxima/debug/`; this header depends on nothing but the core types, so
/// that every layer can emit into it.
#include <proxima/core/math.hpp>

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace proxima {

/// A colour: red, green, blue and opacity, 0..255 each (sRGB, not premultiplied).
struct Rgba {
  std::uint8_t r = 255;  ///< red
  std::uint8_t g = 255;  ///< green
  std::uint8_t b = 255;  ///< blue
  std::uint8_t a = 255;  ///< opacity (255: opaque)
  friend constexpr bool operator==(const Rgba&, const Rgba&) = default;
};

/// What a primitive shows, for a viewer's layer toggles. The capture format writes the short
/// names of to_string().
enum class DrawLayer : std::uint8_t {
  Shapes,      ///< shapes' surfaces ("shapes")
  Bounds,      ///< bounding volumes of shapes and objects ("bounds")
  Bvh,         ///< nodes of a shape's hierarchy, level = depth ("bvh")
  BroadPhase,  ///< nodes or proxy boxes of a broad-phase structure, level = depth ("broadphase")
  Contacts,    ///< contact points and the segments between their witnesses ("contacts")
  Normals,     ///< contact normals ("normals")
  Sweeps,      ///< continuous detection: shapes along a motion and its path ("sweeps")
  Queries,     ///< scene-query rays, hits and their normals ("queries")
  Text,        ///< labels ("text")
  User,        ///< the application's own drawing ("user")
};

/// Number of DrawLayer values.
inline constexpr int kDrawLayerCount = 10;

/// Short lower-case name of a layer ("shapes", "bvh", ...).
constexpr std::string_view to_string(DrawLayer layer) {
  constexpr std::string_view kNames[kDrawLayerCount] = {"shapes",  "bounds", "bvh",     "broadphase", "contacts",
                                                        "normals", "sweeps", "queries", "text",       "user"};
  const auto index = static_cast<unsigned>(layer);
  return index < static_cast<unsigned>(kDrawLayerCount) ? kNames[index] : std::string_view("user");
}

/// The tag of a primitive: its layer and a level within the layer (a hierarchy node's depth,
/// the root at 0; 0 where a layer has no levels).
struct DrawTag {
  DrawLayer layer = DrawLayer::User;  ///< what the primitive shows
  std::uint16_t level = 0;            ///< depth in a hierarchy (0: root or no hierarchy)
  friend constexpr bool operator==(const DrawTag&, const DrawTag&) = default;
};

/// A line segment from `from` to `to` (world frame, length units).
struct DrawLine {
  Vec3 from{Real(0)};  ///< first end, world frame
  Vec3 to{Real(0)};    ///< second end, world frame
  Rgba color;          ///< colour
  DrawTag tag;         ///< layer and level
};

/// A filled triangle (world frame). Its front side is the one where a, b, c run
/// counter-clockwise (the outward side of a shape's tessellation); viewers may draw both sides.
struct DrawTriangle {
  Vec3 a{Real(0)};  ///< first corner, world frame
  Vec3 b{Real(0)};  ///< second corner
  Vec3 c{Real(0)};  ///< third corner
  Rgba color;       ///< colour (viewers shade it by the normal)
  DrawTag tag;      ///< layer and level
};

/// A point marker at `position` (world frame).
struct DrawPoint {
  Vec3 position{Real(0)};  ///< world frame
  Real size = Real(4);     ///< marker diameter on the screen, in pixels (a viewer's hint)
  Rgba color;              ///< colour
  DrawTag tag;             ///< layer and level
};

/// A box drawn as its twelve edges: an oriented box of half extents `half_extents` about
/// `center`, its axes the columns of `rotation` (the identity: an axis-aligned box).
struct DrawBox {
  Vec3 center{Real(0)};          ///< centre, world frame
  Vec3 half_extents{Real(0)};    ///< half extents along the box's own axes (>= 0, length units)
  Quat rotation{kIdentityQuat};  ///< box frame -> world frame
  Rgba color;                    ///< colour
  DrawTag tag;                   ///< layer and level
};

/// A label anchored at `position` (world frame), drawn facing the screen.
struct DrawText {
  Vec3 position{Real(0)};  ///< anchor, world frame
  std::string text;        ///< UTF-8
  Rgba color;              ///< colour
  DrawTag tag;             ///< layer and level
};

/// A debug-draw sink: receives batches of primitives. Implement it to draw with an engine's
/// renderer; DrawBuffer records them. Each call may be given an empty span. The spans are
/// valid only during the call.
class DebugDraw {
 public:
  virtual ~DebugDraw() = default;
  /// Receives line segments.
  virtual void draw_lines(std::span<const DrawLine> lines) = 0;
  /// Receives filled triangles.
  virtual void draw_triangles(std::span<const DrawTriangle> triangles) = 0;
  /// Receives point markers.
  virtual void draw_points(std::span<const DrawPoint> points) = 0;
  /// Receives boxes (axis-aligned or oriented), drawn as their edges.
  virtual void draw_boxes(std::span<const DrawBox> boxes) = 0;
  /// Receives labels.
  virtual void draw_texts(std::span<const DrawText> texts) = 0;
};

/// A DebugDraw that records everything it receives, in order per kind, into vectors (the
/// capture format writes them; tests read them).
class DrawBuffer final : public DebugDraw {
 public:
  std::vector<DrawLine> lines;          ///< every line received
  std::vector<DrawTriangle> triangles;  ///< every triangle received
  std::vector<DrawPoint> points;        ///< every point received
  std::vector<DrawBox> boxes;           ///< every box received
  std::vector<DrawText> texts;          ///< every label received

  /// Appends `in` to lines.
  void draw_lines(std::span<const DrawLine> in) override { lines.insert(lines.end(), in.begin(), in.end()); }
  /// Appends `in` to triangles.
  void draw_triangles(std::span<const DrawTriangle> in) override {
    triangles.insert(triangles.end(), in.begin(), in.end());
  }
  /// Appends `in` to points.
  void draw_points(std::span<const DrawPoint> in) override { points.insert(points.end(), in.begin(), in.end()); }
  /// Appends `in` to boxes.
  void draw_boxes(std::span<const DrawBox> in) override { boxes.insert(boxes.end(), in.begin(), in.end()); }
  /// Appends `in` to texts.
  void draw_texts(std::span<const DrawText> in) override { texts.insert(texts.end(), in.begin(), in.end()); }

  /// Sends everything recorded to `sink`, one call per kind.
  void replay(DebugDraw& sink) const {
    sink.draw_lines(lines);
    sink.draw_triangles(triangles);
    sink.draw_points(points);
    sink.draw_boxes(boxes);
    sink.draw_texts(texts);
  }
  /// True when nothing is recorded.
  bool empty() const { return lines.empty() && triangles.empty() && points.empty() && boxes.empty() && texts.empty(); }
  /// Forgets everything recorded (keeps the capacity).
  void clear() {
    lines.clear();
    triangles.clear();
    points.clear();
    boxes.clear();
    texts.clear();
  }
};

}  // namespace proxima
