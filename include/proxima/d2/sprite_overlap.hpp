#pragma once
/// @file sprite_overlap.hpp
/// Pixel-perfect overlap of two placed sprite masks: how many screen pixels are set in
/// both, which of them comes first, or only whether there is one.
///
/// Frame: screen pixels, x to the right and y down (image coordinates, as SpriteMask), in
/// integer pixel units. A mask placed at integer `position` (x0, y0) covers screen pixel
/// (X, Y) with its pixel (X - x0, Y - y0); mask A is always placed this way.
///
/// Mask B may instead be turned and scaled (TurnedPlacement), by the rule of W9 in
/// shared/bench/FORMATS.md, which is the definition used here, evaluated in double
/// whatever proxima::Real is:
///
///     th = angle (radians; angle_degrees * pi / 180);  c = cos(th);  s = sin(th)
///     cx = xB + wB / 2;   cy = yB + hB / 2
///     dx = (X + 0.5) - cx;   dy = (Y + 0.5) - cy
///     u = (c * dx + s * dy) / scale;   v = (-s * dx + c * dy) / scale
///     B covers (X, Y) with its pixel (floor(u + wB / 2), floor(v + hB / 2)) if inside B
///
/// i.e. nearest-neighbour inverse mapping of screen pixel centres: B is scaled by `scale`
/// and turned by the angle about its centre (cx, cy), and since y points down a positive
/// angle turns B clockwise on screen. Because A sits at integer offsets, its pixel centres
/// are screen pixel centres, so the count equals the number of set pixels of A whose centre,
/// mapped into B's mask by the inverse of B's placement, falls in a set pixel of B.

#include <proxima/core/result.hpp>
#include <proxima/d2/sprite_mask.hpp>

#include <cstdint>
#include <optional>

namespace proxima::d2 {

/// An integer screen pixel position (x right, y down), in pixels.
struct PixelPoint {
  std::int64_t x = 0;  ///< column
  std::int64_t y = 0;  ///< row
  /// Exact equality.
  bool operator==(const PixelPoint&) const = default;
};

/// Largest |x| and |y| of a mask position (2^40 pixels): every screen pixel a mask covers,
/// and its centre, is then exact in double and in std::int64_t.
inline constexpr std::int64_t kMaxSpritePosition = std::int64_t{1} << 40;

/// The answer of sprite_overlap.
struct SpriteOverlap {
  bool overlap = false;             ///< true when count > 0
  std::uint64_t count = 0;          ///< screen pixels set in both placed masks
  std::optional<PixelPoint> first;  ///< the common screen pixel with the smallest (y, x); none when count == 0
  /// Exact equality of every field.
  bool operator==(const SpriteOverlap&) const = default;
};

/// B's turned and scaled placement (the rule in the file comment).
class TurnedPlacement {
 public:
  /// Validated construction, angle in degrees (positive = clockwise on screen): position
  /// within +-kMaxSpritePosition (field "position"), finite angle ("angle_degrees"), finite
  /// scale > 0 ("scale"). The angle in radians is angle_degrees * pi / 180 in double.
  static Result<TurnedPlacement> create(PixelPoint position, double angle_degrees, double scale);
  /// The same with the angle in radians ("angle_radians" names a bad angle).
  static Result<TurnedPlacement> from_radians(PixelPoint position, double angle_radians, double scale);

  /// Screen position (x0, y0) of the mask's corner before turning: its centre is at
  /// (x0 + w / 2, y0 + h / 2).
  PixelPoint position() const { return position_; }
  /// cos(angle), in double.
  double cos() const { return cos_; }
  /// sin(angle), in double.
  double sin() const { return sin_; }
  /// Scale factor (> 0): B's pixels are `scale` screen pixels wide.
  double scale() const { return scale_; }

 private:
  TurnedPlacement(PixelPoint position, double angle_radians, double scale);
  PixelPoint position_;
  double cos_;
  double sin_;
  double scale_;
};

/// The overlap of A at `position_a` and B at `position_b` (translation only). Steps: the
/// bounding rectangles of the set pixels reject; then, per common row, A's words where both
/// rows hold set pixels are ANDed with B's row shifted to A's bit alignment and the results
/// counted (popcount). Time O(common rows x words per row); no allocation. Positions must
/// lie within +-kMaxSpritePosition.
SpriteOverlap sprite_overlap(const SpriteMask& a, PixelPoint position_a, const SpriteMask& b, PixelPoint position_b);
/// True when A at `position_a` and B at `position_b` share a set screen pixel: as
/// sprite_overlap, stopping at the first common word.
bool sprites_overlap(const SpriteMask& a, PixelPoint position_a, const SpriteMask& b, PixelPoint position_b);

/// The overlap of A at `position_a` and B turned and scaled by `placement_b` (rule in the
/// file comment). Steps: A's set rectangle is intersected with turned_bounds(b); per screen
/// row, the span of columns whose centres can map into B's set rectangle is solved from the
/// rule and widened by two pixels, and only A's set pixels in that span are mapped, each
/// getting exactly the rule's answer (a multiplication by 1 / scale, and the rule's own
/// division within 1e-7 of a pixel edge). Time O(A's set pixels in the spans); no
/// allocation.
SpriteOverlap sprite_overlap(const SpriteMask& a, PixelPoint position_a, const SpriteMask& b,
                             const TurnedPlacement& placement_b);
/// True when A at `position_a` and the turned, scaled B share a set screen pixel: as the
/// turned sprite_overlap, stopping at the first common pixel.
bool sprites_overlap(const SpriteMask& a, PixelPoint position_a, const SpriteMask& b,
                     const TurnedPlacement& placement_b);

/// The screen pixels whose set pixels of the turned, scaled B can cover: those whose centres
/// lie in the axis-aligned box of the turned, scaled rectangle of B's set pixels, widened by
/// one pixel on every side (a superset; empty when B has no set pixel).
PixelRect turned_bounds(const SpriteMask& b, const TurnedPlacement& placement_b);

}  // namespace proxima::d2
