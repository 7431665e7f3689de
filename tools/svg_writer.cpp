#include "svg_writer.hpp"

#include <cstdio>
#include <fstream>

namespace proxima::tool {

namespace {

// A coordinate with two decimals (a hundredth of a pixel is finer than any display).
std::string num(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof(buffer), "%.2f", x);
  std::string s(buffer);
  // Trim trailing zeros for a smaller file: "12.50" -> "12.5", "3.00" -> "3".
  while (!s.empty() && s.back() == '0') s.pop_back();
  if (!s.empty() && s.back() == '.') s.pop_back();
  if (s == "-0") s = "0";
  return s;
}

std::string attr(std::string_view name, std::string_view value) {
  std::string out;
  out.reserve(name.size() + value.size() + 4);
  out.append(1, ' ').append(name).append("=\"").append(xml_escape(value)).append(1, '"');
  return out;
}

}  // namespace

std::string xml_escape(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&apos;"; break;
      default: out += c;
    }
  }
  return out;
}

SvgWriter::SvgWriter(double width, double height) : width_(width), height_(height) {}

void SvgWriter::rect(double x, double y, double width, double height, std::string_view fill, std::string_view stroke,
                     double stroke_width, double corner_radius) {
  body_ += "<rect" + attr("x", num(x)) + attr("y", num(y)) + attr("width", num(width)) + attr("height", num(height));
  if (corner_radius > 0.0) body_ += attr("rx", num(corner_radius));
  body_ += attr("fill", fill);
  if (stroke_width > 0.0) body_ += attr("stroke", stroke) + attr("stroke-width", num(stroke_width));
  body_ += "/>\n";
}

void SvgWriter::circle(double cx, double cy, double r, std::string_view fill, std::string_view stroke,
                       double stroke_width, double opacity) {
  body_ += "<circle" + attr("cx", num(cx)) + attr("cy", num(cy)) + attr("r", num(r)) + attr("fill", fill);
  if (stroke_width > 0.0) body_ += attr("stroke", stroke) + attr("stroke-width", num(stroke_width));
  if (opacity < 1.0) body_ += attr("opacity", num(opacity));
  body_ += "/>\n";
}

void SvgWriter::polyline(const std::vector<SvgPoint>& points, std::string_view stroke, double stroke_width,
                         double opacity, std::string_view dash) {
  std::string coords;
  coords.reserve(points.size() * 14);
  for (const SvgPoint& p : points) {
    if (!coords.empty()) coords += ' ';
    coords += num(p.x) + "," + num(p.y);
  }
  body_ += "<polyline" + attr("points", coords) + attr("fill", "none") + attr("stroke", stroke) +
           attr("stroke-width", num(stroke_width)) + attr("stroke-linejoin", "round") + attr("stroke-linecap", "round");
  if (opacity < 1.0) body_ += attr("stroke-opacity", num(opacity));
  if (!dash.empty()) body_ += attr("stroke-dasharray", dash);
  body_ += "/>\n";
}

void SvgWriter::polygon(const std::vector<SvgPoint>& points, std::string_view fill, std::string_view stroke,
                        double stroke_width, double opacity) {
  std::string coords;
  coords.reserve(points.size() * 14);
  for (const SvgPoint& p : points) {
    if (!coords.empty()) coords += ' ';
    coords += num(p.x) + "," + num(p.y);
  }
  body_ += "<polygon" + attr("points", coords) + attr("fill", fill);
  if (stroke_width > 0.0) {
    body_ += attr("stroke", stroke) + attr("stroke-width", num(stroke_width)) + attr("stroke-linejoin", "round");
  }
  if (opacity < 1.0) body_ += attr("opacity", num(opacity));
  body_ += "/>\n";
}

void SvgWriter::line(SvgPoint a, SvgPoint b, std::string_view stroke, double stroke_width) {
  body_ += "<line" + attr("x1", num(a.x)) + attr("y1", num(a.y)) + attr("x2", num(b.x)) + attr("y2", num(b.y)) +
           attr("stroke", stroke) + attr("stroke-width", num(stroke_width)) + "/>\n";
}

void SvgWriter::text(double x, double y, std::string_view text, double font_size, std::string_view fill,
                     std::string_view anchor) {
  body_ += "<text" + attr("x", num(x)) + attr("y", num(y)) + attr("font-size", num(font_size)) +
           attr("font-family", "sans-serif") + attr("fill", fill) + attr("text-anchor", anchor) + ">" +
           xml_escape(text) + "</text>\n";
}

void SvgWriter::begin_group(std::string_view title) {
  body_ += "<g>";
  if (!title.empty()) body_ += "<title>" + xml_escape(title) + "</title>";
  body_ += "\n";
}

void SvgWriter::end_group() { body_ += "</g>\n"; }

std::string SvgWriter::str() const {
  return "<svg xmlns=\"http://www.w3.org/2000/svg\" version=\"1.1\"" + attr("width", num(width_)) +
         attr("height", num(height_)) + attr("viewBox", "0 0 " + num(width_) + " " + num(height_)) + ">\n" + body_ +
         "</svg>\n";
}

bool write_file(const std::string& path, const std::string& content) {
  std::ofstream file(path, std::ios::binary);
  if (!file) return false;
  file << content;
  file.close();
  return static_cast<bool>(file);
}

}  // namespace proxima::tool
