#pragma once
// The scene of `proxima demo-tunnelling`: fast small bullets (library Spheres) fired across a
// field of thin spinning plates (library Boxes turning at constant angular velocity about the
// vertical axis), simulated at a fixed frame rate in two collision worlds that differ only in
// the bullets' continuous-detection mode:
//   - discrete (CcdMode::Off): a contact begins when a bullet overlaps a plate at a frame's
//     poses; a bullet that crosses a plate between two frames is never seen (tunnelling);
//   - continuous (CcdMode::Bullet): the world's impact event, the certified time of impact
//     over each frame's motion, bullet and plate both moving; the bullet stops there.
// Plates and bullets are moving objects; layers keep bullets from pairing with bullets and
// plates with plates. A stopped bullet (or one that left the field) is removed from its
// world. Bullets fly straight at constant velocity until a detector stops them (no response:
// the demo is about detection). Everything is seeded (SplitMix64) and built in.
#include <proxima/core/math.hpp>
#include <proxima/core/transform.hpp>
#include <proxima/shapes/box.hpp>
#include <proxima/shapes/sphere.hpp>
#include <proxima/world/collision_world.hpp>
#include <proxima/world/object_desc.hpp>

#include <array>
#include <cstdint>
#include <functional>
#include <vector>

namespace proxima::tool {

/// The set-up. Lengths in metres, times in seconds, speeds in m/s.
struct TunnellingConfig {
  int frames = 90;                          ///< frames to simulate
  double frame_rate = 60.0;                 ///< frames per second
  std::uint64_t seed = 1;                   ///< bullets' lanes, aims, speeds, sizes; plates' phases
  int bullets = 24;                         ///< bullets fired, spread evenly over the run
  Real min_speed = Real(40);                ///< bullet speeds are uniform in [min_speed, max_speed]
  Real max_speed = Real(90);                ///< (90 m/s: 1.5 m per frame)
  Real min_radius = Real(0.05);             ///< bullet radii are uniform in [min_radius, max_radius]
  Real max_radius = Real(0.1);              ///<
  Real plate_half_thickness = Real(0.015);  ///< half thickness of every plate (3 cm plates)
  Real field_length = Real(4);              ///< the field, along x (bullets fly towards +x)
  Real field_width = Real(2.4);             ///< the field, along y
};

/// A thin plate spinning about the vertical (z) axis through its centre.
struct TunnellingPlate {
  Box box;               ///< half extents: thickness (x), half length (y), half height (z)
  Vec3 centre{Real(0)};  ///< fixed centre, world frame
  double phase = 0.0;    ///< angle about z at time 0, radians
  double spin = 0.0;     ///< angular velocity about z, rad/s (constant)

  /// Placement at `time` seconds: rotation by phase + spin * time about z.
  Transform pose_at(double time) const;
};

/// A bullet: a sphere flying in the plane z = 0 at constant velocity from its firing.
struct TunnellingBullet {
  Sphere sphere;           ///< the bullet
  Vec3 start{Real(0)};     ///< centre when fired (left edge of the field)
  Vec3 velocity{Real(0)};  ///< m/s, in the plane z = 0
  int fire_frame = 0;      ///< fired at the start of this frame

  /// Centre at `time` seconds (on the straight line, whether or not a detector stopped it).
  Vec3 position_at(double time, double frame_rate) const;
};

/// How one detector's run went for one bullet.
struct BulletOutcome {
  bool hit = false;                   ///< a plate stopped it
  int plate = -1;                     ///< hit: the plate
  int frame = -1;                     ///< hit: the frame of the hit; else the last frame it flew in
  double time = 0.0;                  ///< hit: time of the contact (continuous) or of the frame pose (discrete), s
  Vec3 stop{Real(0)};                 ///< centre where it stopped (hit) or was last seen
  Vec3 point{Real(0)};                ///< hit: contact point (continuous: the impact's point; discrete: the centre)
  Real toi = Real(0);                 ///< continuous hit: time of impact within the frame, [0, 1]
  bool left_field = false;            ///< flew out of the field
  std::vector<Vec3> frame_positions;  ///< centre at every frame pose it was seen at (firing included)
};

/// Counters of one detector (one collision world), summed over the run.
struct DetectorStats {
  std::uint64_t steps = 0;         ///< CollisionWorld::step calls (one per frame)
  std::uint64_t hits = 0;          ///< bullets stopped
  std::uint64_t impacts = 0;       ///< impact events (continuous detection)
  std::uint64_t begin_events = 0;  ///< contact begin events
  std::uint64_t late_hits = 0;     ///< continuous world: hits seen as a contact only, no impact (never expected)
  double seconds = 0.0;            ///< wall-clock time inside CollisionWorld::step
};

/// Called after each frame's step of a run: the detector's mode, the frame, its world.
using TunnellingFrameObserver = std::function<void(CcdMode mode, int frame, const CollisionWorld& world)>;

/// The scene and both runs.
class TunnellingScene {
 public:
  /// Builds the scene (plates, bullets) from the configuration; simulates nothing yet.
  explicit TunnellingScene(const TunnellingConfig& config);

  /// Runs both detectors over config.frames frames (once; again: the same answers), calling
  /// `observer` (when set) after every step of each.
  void run(const TunnellingFrameObserver& observer = {});

  const TunnellingConfig& config() const { return config_; }
  const std::vector<TunnellingPlate>& plates() const { return plates_; }
  const std::vector<TunnellingBullet>& bullets() const { return bullets_; }
  /// Per bullet, the discrete detector's run.
  const std::vector<BulletOutcome>& discrete() const { return discrete_; }
  /// Per bullet, the continuous detector's run.
  const std::vector<BulletOutcome>& continuous() const { return continuous_; }
  const DetectorStats& discrete_stats() const { return discrete_stats_; }
  const DetectorStats& continuous_stats() const { return continuous_stats_; }

  /// Bullet `i` tunnelled: the continuous detector stops it, and the discrete detector let
  /// it through that plate (missed it altogether, or stopped it later on another plate).
  bool tunnelled(int i) const;
  /// Number of tunnelled bullets.
  int tunnelled_count() const;
  /// Bullets the discrete detector stopped and the continuous one did not (never expected:
  /// an overlap at a frame pose implies an impact at or before it).
  int discrete_only_count() const;
  /// Seconds per frame.
  double frame_time() const { return 1.0 / config_.frame_rate; }
  /// True when the whole sphere of radius `r` at `centre` is outside the field.
  bool outside_field(const Vec3& centre, Real r) const;

 private:
  void run_detector(CcdMode mode, std::vector<BulletOutcome>& outcomes, DetectorStats& stats,
                    const TunnellingFrameObserver& observer) const;

  TunnellingConfig config_;
  std::vector<TunnellingPlate> plates_;
  std::vector<TunnellingBullet> bullets_;
  std::vector<BulletOutcome> discrete_;
  std::vector<BulletOutcome> continuous_;
  DetectorStats discrete_stats_;
  DetectorStats continuous_stats_;
};

}  // namespace proxima::tool
