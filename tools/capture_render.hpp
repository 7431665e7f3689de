#pragma once
// `proxima render`: pictures of one step of a capture (docs/capture-format.md), drawn with
// cairo into PNG or SVG: the objects' meshes at their poses and the step's draw stream,
// seen by the capture's camera or a default one fitted to the scene.
#include <proxima/core/debug_draw.hpp>
#include <proxima/core/result.hpp>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "capture_reader.hpp"

namespace proxima::tool {

/// The default camera's direction when the capture has none (or it is not used).
enum class RenderView {
  Auto,   ///< Iso for a 3D capture, Top for a 2D one
  Iso,    ///< from (+x, -y, +z) towards the scene, z up
  Top,    ///< looking down -z, y up
  Front,  ///< looking along +y, z up
};

/// Options of a picture.
struct RenderOptions {
  int width = 800;                     ///< pixels (16..8192)
  int height = 600;                    ///< pixels (16..8192)
  std::vector<std::string> layers;     ///< layers drawn (capture-format names); empty: all
  bool capture_camera = true;          ///< use the header's camera when it has one
  RenderView view = RenderView::Auto;  ///< the default camera's direction
  Rgba background{32, 34, 40, 255};    ///< background colour
};

/// A rendered picture: width * height pixels, rows from the top, not premultiplied.
struct Image {
  int width = 0;             ///< pixels
  int height = 0;            ///< pixels
  std::vector<Rgba> pixels;  ///< row-major, top row first

  /// The pixel at column x, row y (from the top-left corner).
  Rgba at(int x, int y) const { return pixels[static_cast<std::size_t>(y) * static_cast<std::size_t>(width) + x]; }
};

/// Where a world point lands in the picture: pixel coordinates (x right, y down) and the
/// distance along the view direction (larger: farther).
struct Projected {
  double x = 0;      ///< pixels from the left edge
  double y = 0;      ///< pixels from the top edge
  double depth = 0;  ///< along the view direction
};

/// The camera of a picture of `frame`: `project` maps world points to pixels.
class RenderCamera {
 public:
  /// The capture's camera (when it has one and options allow), else the default view fitted
  /// to the objects of the frame (half-spaces left out) and the frame's draw stream.
  static RenderCamera for_frame(const Capture& capture, const std::vector<CaptureObject>& objects,
                                const CaptureStep& step, const RenderOptions& options);
  /// The pixel of world point `p`.
  Projected project(const Vec3& p) const;
  /// Unit direction the camera looks along (world frame).
  Vec3 forward() const { return forward_; }
  /// True when a face at `point` with normal `normal` (any length) is seen from behind.
  bool faces_away(const Vec3& point, const Vec3& normal) const {
    return glm::dot(normal, perspective_ ? point - eye_ : forward_) >= Real(0);
  }

 private:
  Vec3 eye_{0}, forward_{0, 0, -1}, right_{1, 0, 0}, up_{0, 1, 0};
  double scale_ = 1;        ///< orthographic: pixels per length unit; perspective: focal length in pixels
  double cx_ = 0, cy_ = 0;  ///< pixel of the view's centre
  bool perspective_ = false;
};

/// The picture of step `frame` (after it ran). Error "frame" when there is no such step.
Result<Image> render_image(const Capture& capture, std::size_t frame, const RenderOptions& options);

/// Writes the picture of step `frame` to `path`: PNG when it ends in ".png", SVG when in
/// ".svg". Errors: "frame", "output" (another extension, or the file cannot be written).
std::optional<Error> render_file(const Capture& capture, std::size_t frame, const RenderOptions& options,
                                 const std::string& path);

}  // namespace proxima::tool
