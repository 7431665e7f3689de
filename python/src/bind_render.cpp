// proxima.render: a picture of one step of a capture file, drawn by the same renderer as
// `proxima render` (cairo; tools/capture_render.hpp): to a PNG or SVG file, or returned as an
// (height, width, 4) uint8 RGBA array. Built when the tool is (PROXIMA_BUILD_TOOLS).
#include "conversions.hpp"
#include "module_parts.hpp"

#if PROXIMA_PYTHON_RENDER
#include <fstream>
#include <pybind11/stl.h>

#include "capture_render.hpp"
#endif

namespace proxima::python {

#if PROXIMA_PYTHON_RENDER
namespace {

tool::RenderView view_of(const std::string& name) {
  if (name == "auto") return tool::RenderView::Auto;
  if (name == "iso") return tool::RenderView::Iso;
  if (name == "top") return tool::RenderView::Top;
  if (name == "front") return tool::RenderView::Front;
  raise_argument_error("view", "expected 'auto', 'iso', 'top' or 'front'");
}

py::object render(const std::string& capture_path, std::size_t frame, py::handle out, int width, int height,
                  py::handle layers, const std::string& view, bool capture_camera) {
  std::ifstream in(capture_path, std::ios::binary);
  if (!in) raise_argument_error("capture", "cannot be opened: " + capture_path);
  const tool::Capture capture = take(tool::read_capture(in));
  tool::RenderOptions options;
  options.width = width;
  options.height = height;
  options.view = view_of(view);
  options.capture_camera = capture_camera;
  if (!layers.is_none()) options.layers = layers.cast<std::vector<std::string>>();
  if (!out.is_none()) {
    check(tool::render_file(capture, frame, options, py::str(out)));
    return py::none();
  }
  const tool::Image image = take(tool::render_image(capture, frame, options));
  py::array_t<std::uint8_t> pixels({py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(4)});
  std::uint8_t* d = pixels.mutable_data();
  for (const Rgba& p : image.pixels) *d++ = p.r, *d++ = p.g, *d++ = p.b, *d++ = p.a;
  return pixels;
}

}  // namespace
#endif

void bind_render(py::module_& m) {
#if PROXIMA_PYTHON_RENDER
  m.def("render", &render, py::arg("capture"), py::arg("frame"), py::arg("out") = py::none(), py::kw_only(),
        py::arg("width") = 800, py::arg("height") = 600, py::arg("layers") = py::none(), py::arg("view") = "auto",
        py::arg("capture_camera") = true,
        "Draws step `frame` of the capture file: to `out` (.png or .svg) and returns None, or returns the picture "
        "as an (height, width, 4) uint8 RGBA array. layers: names to draw (shapes, bounds, bvh, broadphase, "
        "contacts, normals, sweeps, queries, text, user; default all); view: the default camera's direction "
        "('auto', 'iso', 'top', 'front') when the capture's own camera is not used.");
#else
  (void)m;
#endif
}

}  // namespace proxima::python
