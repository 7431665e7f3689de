// `proxima render` (capture_render.hpp).
//
// Steps:
//   1. the objects as they are after the frame's step (objects_at) and the step's draw
//      stream, filtered by layer (objects' meshes are the "shapes" layer);
//   2. the camera: the capture's, or a default direction (iso, top, front) whose
//      orthographic view is fitted to the frame's points;
//   3. painter's algorithm: the objects' triangles that face the camera (their meshes are
//      closed and wound outward; surfaces come with both windings) and every triangle of
//      the draw stream, projected, sorted far to near by the centroid's depth, filled with
//      flat shading (brighter the more it faces the camera);
//   4. overlays on top, in order: boxes (12 edges), lines, points (discs), labels;
//   5. cairo draws on an image surface (PNG, or pixels for the tests) or an SVG surface.
#include "capture_render.hpp"

#include <algorithm>
#include <array>
#include <cairo-svg.h>
#include <cairo.h>
#include <cmath>
#include <cstring>
#include <memory>

namespace proxima::tool {

namespace {

struct Face {
  std::array<Projected, 3> corners;
  Rgba color;
  double shade = 1;
  double depth = 0;
};

struct Scene {
  std::vector<Face> faces;
  std::vector<std::array<Projected, 2>> segments;
  std::vector<Rgba> segment_colors;
  std::vector<DrawPoint> points;
  std::vector<DrawText> texts;
};

bool layer_on(const RenderOptions& options, DrawLayer layer) {
  return options.layers.empty() ||
         std::find(options.layers.begin(), options.layers.end(), to_string(layer)) != options.layers.end();
}

double facing(const Vec3& a, const Vec3& b, const Vec3& c, const Vec3& forward) {
  const Vec3 n = glm::cross(b - a, c - a);
  const Real length = glm::length(n);
  if (!(length > Real(0))) return 1;
  return 0.4 + 0.6 * std::abs(double(glm::dot(n / length, forward)));
}

void add_face(Scene& scene, const RenderCamera& camera, const Vec3& a, const Vec3& b, const Vec3& c, Rgba color,
              bool cull = false) {
  if (cull && camera.faces_away(a, glm::cross(b - a, c - a))) return;
  Face f{{camera.project(a), camera.project(b), camera.project(c)}, color, facing(a, b, c, camera.forward()), 0};
  for (const Projected& p : f.corners) {
    if (!(p.depth > 0) || !std::isfinite(p.x) || !std::isfinite(p.y)) return;  // behind the camera
  }
  f.depth = (f.corners[0].depth + f.corners[1].depth + f.corners[2].depth) / 3;
  scene.faces.push_back(f);
}

void add_segment(Scene& scene, const RenderCamera& camera, const Vec3& a, const Vec3& b, Rgba color) {
  const Projected pa = camera.project(a), pb = camera.project(b);
  if (!(pa.depth > 0) || !(pb.depth > 0)) return;
  scene.segments.push_back({pa, pb});
  scene.segment_colors.push_back(color);
}

void add_box(Scene& scene, const RenderCamera& camera, const DrawBox& box) {
  std::array<Vec3, 8> corner;
  for (int i = 0; i < 8; ++i) {
    const Vec3 sign((i & 1) ? 1 : -1, (i & 2) ? 1 : -1, (i & 4) ? 1 : -1);
    corner[std::size_t(i)] = box.center + box.rotation * (sign * box.half_extents);
  }
  for (int i = 0; i < 8; ++i) {
    for (int bit : {1, 2, 4}) {
      if (!(i & bit)) add_segment(scene, camera, corner[std::size_t(i)], corner[std::size_t(i | bit)], box.color);
    }
  }
}

Scene build_scene(const std::vector<CaptureObject>& objects, const DrawBuffer& draw, const RenderCamera& camera,
                  const RenderOptions& options) {
  Scene scene;
  if (layer_on(options, DrawLayer::Shapes)) {
    for (const CaptureObject& o : objects) {
      for (std::size_t i = 0; i + 2 < o.indices.size(); i += 3) {
        add_face(scene, camera, o.pose.apply(o.positions[o.indices[i]]), o.pose.apply(o.positions[o.indices[i + 1]]),
                 o.pose.apply(o.positions[o.indices[i + 2]]), o.color, true);
      }
    }
  }
  for (const DrawTriangle& t : draw.triangles) {
    if (layer_on(options, t.tag.layer)) add_face(scene, camera, t.a, t.b, t.c, t.color);
  }
  std::stable_sort(scene.faces.begin(), scene.faces.end(),
                   [](const Face& a, const Face& b) { return a.depth > b.depth; });
  for (const DrawBox& b : draw.boxes) {
    if (layer_on(options, b.tag.layer)) add_box(scene, camera, b);
  }
  for (const DrawLine& l : draw.lines) {
    if (layer_on(options, l.tag.layer)) add_segment(scene, camera, l.from, l.to, l.color);
  }
  for (const DrawPoint& p : draw.points) {
    if (layer_on(options, p.tag.layer)) scene.points.push_back(p);
  }
  for (const DrawText& t : draw.texts) {
    if (layer_on(options, t.tag.layer)) scene.texts.push_back(t);
  }
  return scene;
}

void set_color(cairo_t* cr, Rgba c, double shade = 1) {
  cairo_set_source_rgba(cr, c.r / 255.0 * shade, c.g / 255.0 * shade, c.b / 255.0 * shade, c.a / 255.0);
}

void paint(cairo_t* cr, const Scene& scene, const RenderCamera& camera, const RenderOptions& options) {
  set_color(cr, options.background);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (const Face& f : scene.faces) {
    cairo_move_to(cr, f.corners[0].x, f.corners[0].y);
    cairo_line_to(cr, f.corners[1].x, f.corners[1].y);
    cairo_line_to(cr, f.corners[2].x, f.corners[2].y);
    cairo_close_path(cr);
    set_color(cr, f.color, f.shade);
    if (f.color.a == 255) {  // a thin outline of the same colour hides the seams between faces
      cairo_fill_preserve(cr);
      cairo_set_line_width(cr, 0.75);
      cairo_stroke(cr);
    } else {
      cairo_fill(cr);
    }
  }
  cairo_set_line_width(cr, 1.5);
  for (std::size_t i = 0; i < scene.segments.size(); ++i) {
    cairo_move_to(cr, scene.segments[i][0].x, scene.segments[i][0].y);
    cairo_line_to(cr, scene.segments[i][1].x, scene.segments[i][1].y);
    set_color(cr, scene.segment_colors[i]);
    cairo_stroke(cr);
  }
  for (const DrawPoint& p : scene.points) {
    const Projected at = camera.project(p.position);
    if (!(at.depth > 0)) continue;
    cairo_arc(cr, at.x, at.y, std::clamp(double(p.size), 1.0, 64.0) / 2, 0, 2 * 3.14159265358979);
    set_color(cr, p.color);
    cairo_fill(cr);
  }
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, 11);
  for (const DrawText& t : scene.texts) {
    const Projected at = camera.project(t.position);
    if (!(at.depth > 0)) continue;
    cairo_move_to(cr, at.x + 4, at.y - 4);
    set_color(cr, t.color);
    cairo_show_text(cr, t.text.c_str());
  }
}

std::optional<Error> check_options(const RenderOptions& options) {
  if (options.width < 16 || options.width > 8192) return Error{ErrorCode::OutOfRange, "width", "must be 16..8192"};
  if (options.height < 16 || options.height > 8192) return Error{ErrorCode::OutOfRange, "height", "must be 16..8192"};
  return std::nullopt;
}

/// Draws step `frame` on `cr` (a surface of options.width x options.height).
std::optional<Error> draw_frame(cairo_t* cr, const Capture& capture, std::size_t frame, const RenderOptions& options) {
  Result<std::vector<CaptureObject>> objects = objects_at(capture, frame);
  if (!objects.ok()) return objects.error();
  const CaptureStep& step = capture.steps[frame];
  const RenderCamera camera = RenderCamera::for_frame(capture, objects.value(), step, options);
  paint(cr, build_scene(objects.value(), step.draw, camera, options), camera, options);
  return std::nullopt;
}

bool ends_with(const std::string& text, const std::string& tail) {
  return text.size() >= tail.size() && text.compare(text.size() - tail.size(), tail.size(), tail) == 0;
}

using SurfacePtr = std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)>;
using ContextPtr = std::unique_ptr<cairo_t, decltype(&cairo_destroy)>;

}  // namespace

Result<Image> render_image(const Capture& capture, std::size_t frame, const RenderOptions& options) {
  if (auto e = check_options(options)) return *e;
  SurfacePtr surface(cairo_image_surface_create(CAIRO_FORMAT_ARGB32, options.width, options.height),
                     cairo_surface_destroy);
  ContextPtr cr(cairo_create(surface.get()), cairo_destroy);
  if (auto e = draw_frame(cr.get(), capture, frame, options)) return *e;
  cairo_surface_flush(surface.get());
  const unsigned char* data = cairo_image_surface_get_data(surface.get());
  const int stride = cairo_image_surface_get_stride(surface.get());
  Image image{options.width, options.height, {}};
  image.pixels.reserve(static_cast<std::size_t>(options.width) * static_cast<std::size_t>(options.height));
  for (int y = 0; y < options.height; ++y) {
    for (int x = 0; x < options.width; ++x) {
      std::uint32_t argb = 0;
      std::memcpy(&argb, data + y * stride + 4 * x, 4);  // native-endian ARGB, premultiplied
      const std::uint32_t a = argb >> 24;
      const auto channel = [&](int shift) {
        const std::uint32_t v = (argb >> shift) & 0xffu;
        return static_cast<std::uint8_t>(a == 0 ? 0 : std::min<std::uint32_t>(255, (v * 255 + a / 2) / a));
      };
      image.pixels.push_back(Rgba{channel(16), channel(8), channel(0), static_cast<std::uint8_t>(a)});
    }
  }
  return image;
}

std::optional<Error> render_file(const Capture& capture, std::size_t frame, const RenderOptions& options,
                                 const std::string& path) {
  if (auto e = check_options(options)) return e;
  const bool png = ends_with(path, ".png"), svg = ends_with(path, ".svg");
  if (!png && !svg) return Error{ErrorCode::InvalidArgument, "output", "must end in .png or .svg: " + path};
  SurfacePtr surface(svg ? cairo_svg_surface_create(path.c_str(), options.width, options.height)
                         : cairo_image_surface_create(CAIRO_FORMAT_ARGB32, options.width, options.height),
                     cairo_surface_destroy);
  {
    ContextPtr cr(cairo_create(surface.get()), cairo_destroy);
    if (auto e = draw_frame(cr.get(), capture, frame, options)) return e;
  }
  cairo_status_t status = CAIRO_STATUS_SUCCESS;
  if (png) {
    status = cairo_surface_write_to_png(surface.get(), path.c_str());
  } else {
    cairo_surface_finish(surface.get());
    status = cairo_surface_status(surface.get());
  }
  if (status != CAIRO_STATUS_SUCCESS) {
    return Error{ErrorCode::InvalidArgument, "output", "cannot write " + path + ": " + cairo_status_to_string(status)};
  }
  return std::nullopt;
}

}  // namespace proxima::tool
