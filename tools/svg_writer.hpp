#pragma once
// SvgWriter: builds a small SVG 1.1 document (rectangles, circles, polylines, polygons, text) in
// memory and writes it to a file. Coordinates are in user units (pixels of the viewBox).
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace proxima::tool {

/// A point of the drawing, in user units (x to the right, y down).
struct SvgPoint {
  double x = 0.0;  ///< horizontal coordinate
  double y = 0.0;  ///< vertical coordinate (down)
};

/// Accumulates SVG elements; the document starts with `<svg` (no XML prolog) so that it can
/// be embedded in HTML as is.
class SvgWriter {
 public:
  /// A drawing of `width` x `height` user units.
  SvgWriter(double width, double height);

  /// Filled (and optionally stroked: stroke_width > 0) axis-aligned rectangle.
  void rect(double x, double y, double width, double height, std::string_view fill, std::string_view stroke = "none",
            double stroke_width = 0.0, double corner_radius = 0.0);
  /// Circle at (cx, cy); stroke only when stroke_width > 0; opacity in [0, 1].
  void circle(double cx, double cy, double r, std::string_view fill, std::string_view stroke = "none",
              double stroke_width = 0.0, double opacity = 1.0);
  /// Open polyline through `points` (no fill); `dash` is an SVG stroke-dasharray or empty.
  void polyline(const std::vector<SvgPoint>& points, std::string_view stroke, double stroke_width, double opacity = 1.0,
                std::string_view dash = {});
  /// Closed polygon through `points`, filled (fill "none": outline only) and stroked when
  /// stroke_width > 0; opacity (of fill and stroke) in [0, 1].
  void polygon(const std::vector<SvgPoint>& points, std::string_view fill, std::string_view stroke = "none",
               double stroke_width = 0.0, double opacity = 1.0);
  /// A line segment.
  void line(SvgPoint a, SvgPoint b, std::string_view stroke, double stroke_width);
  /// Text with its baseline starting at (x, y); `text` is escaped.
  void text(double x, double y, std::string_view text, double font_size, std::string_view fill = "black",
            std::string_view anchor = "start");
  /// Opens a group with an SVG `<title>` (a tooltip in browsers) when `title` is non-empty.
  void begin_group(std::string_view title = {});
  /// Closes the group opened last.
  void end_group();

  /// The complete document.
  std::string str() const;

 private:
  double width_;
  double height_;
  std::string body_;
};

/// Writes `content` to the file `path` (replacing it); false when it cannot be written.
bool write_file(const std::string& path, const std::string& content);

/// `text` with &, <, >, " and ' replaced by their XML entities.
std::string xml_escape(std::string_view text);

}  // namespace proxima::tool
