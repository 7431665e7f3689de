#pragma once
// BilliardTable: the scene of `proxima demo`, the break of a game of pool, run as a game
// loop on the library's CollisionWorld. Sixteen balls (a triangle rack of 15 and the cue
// ball) are moving Sphere objects with continuous detection (CcdMode::Bullet); the four
// cushions are static HalfSpace objects. The world finds the contacts, the impacts and the
// begin / end events; the collision response (equal masses, restitution, rolling
// resistance) lives here in the tool, never in the library.
#include <proxima/core/math.hpp>
#include <proxima/shapes/halfspace.hpp>
#include <proxima/shapes/sphere.hpp>
#include <proxima/world/collision_world.hpp>

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace proxima::tool {

/// The set-up of a break. Lengths in metres, times in seconds, speeds in m/s.
struct BilliardConfig {
  int frames = 600;                       ///< frames to simulate
  double frame_rate = 60.0;               ///< frames per second
  int substeps = 4;                       ///< world steps per frame
  std::uint64_t seed = 1;                 ///< jitter of the rack and the shot; 0: perfectly symmetric
  Real table_length = Real(2.54);         ///< playing surface along x (a 9-foot table)
  Real table_width = Real(1.27);          ///< playing surface along y
  Real ball_radius = Real(0.028575);      ///< pool ball (57.15 mm diameter)
  Real rack_gap = Real(0.0002);           ///< gap between neighbouring racked balls
  Real cue_speed = Real(10);              ///< speed of the cue ball at the start
  Real ball_restitution = Real(0.95);     ///< ball-ball coefficient of restitution
  Real cushion_restitution = Real(0.9);   ///< ball-cushion coefficient of restitution
  Real rolling_deceleration = Real(0.3);  ///< rolling resistance, m/s^2 (about 0.03 g)
  Real contact_distance = Real(0.0005);   ///< the world's contact distance: balls this close touch
  std::string broadphase = "tree";        ///< the world's broad-phase structure, by registry name
};

/// Ball centres and velocities at the start of a break: the rack on the foot spot, the cue
/// ball on the head spot moving at cue_speed towards the apex ball (jittered by the seed).
struct BilliardStart {
  std::array<Vec3, 16> position{};  ///< centres, world frame (z = ball radius)
  std::array<Vec3, 16> velocity{};  ///< m/s
};

/// The break's starting state for `config` (shared with the tests' exact reference).
BilliardStart rack_break(const BilliardConfig& config);
/// The cushions: solids n . x <= d outside the playing surface, normals pointing in
/// (-x, +x, -y, +y sides).
std::array<HalfSpace, 4> table_cushions(const BilliardConfig& config);

/// A collision the table resolved.
struct BilliardContact {
  Vec3 point{Real(0)};      ///< contact point, world frame
  int frame = 0;            ///< frame in which it happened
  int ball = 0;             ///< first ball
  int other = 0;            ///< second ball, or -1 - cushion index for a cushion
  bool continuous = false;  ///< found as a continuous impact (else as a touching manifold)
};

/// Counters, summed over the frames simulated so far.
struct BilliardStats {
  std::uint64_t frames = 0;              ///< frames simulated
  std::uint64_t steps = 0;               ///< world steps (frames * substeps)
  std::uint64_t ball_collisions = 0;     ///< ball-ball collisions resolved
  std::uint64_t cushion_collisions = 0;  ///< ball-cushion collisions resolved
  std::uint64_t impacts = 0;             ///< continuous impact events (ImpactEvent) the world reported
  std::uint64_t begin_events = 0;        ///< contact begin events
  std::uint64_t persist_events = 0;      ///< contact persist events
  std::uint64_t end_events = 0;          ///< contact end events
  std::uint64_t callbacks = 0;           ///< listener calls (begin + persist + end + impact callbacks)
  std::uint64_t capped_steps = 0;        ///< steps whose overlap passes stopped at their cap (never expected)
  double step_seconds = 0.0;             ///< wall-clock time inside CollisionWorld::step
};

/// The billiard scene on a CollisionWorld.
///
/// A frame is `substeps` world steps of h = dt / substeps. Each step: 1. rolling resistance
/// slows every ball; 2. every ball is moved (one batch) to where its velocity takes it in h
/// (plus the time it owes from an impact in the previous step);
/// 3. CollisionWorld::step: the balls are fast objects (safety factor 0.001), so each
/// moving ball's first impact with a ball or a cushion comes as an ImpactEvent at its
/// certified time of impact, and the pairs touching at the new poses come as manifolds and
/// begin / persist / end events (also delivered to this table's listener); 4. impacts, the
/// earliest first: both objects are put back at the time of impact (teleport: no motion),
/// and the impulse for equal masses (v_rel,n' = -e v_rel,n) separates them (the rest of
/// the step is added to those balls' next step); 5. touching manifolds of the other balls:
/// overlaps are pushed apart and approaching pairs get the same impulse; 6. scene queries
/// (overlap) at every ball push apart what still overlaps, pass after pass.
class BilliardTable {
 public:
  /// Number of balls: the cue ball (index 0) and 15 racked balls (1..15).
  static constexpr int kBallCount = 16;
  /// Number of cushions.
  static constexpr int kCushionCount = 4;

  /// Racks the balls and places the cue ball (rack_break), in a new world. Throws
  /// std::invalid_argument for a bad configuration (frame rate, substeps, broad phase).
  explicit BilliardTable(const BilliardConfig& config);
  ~BilliardTable();
  BilliardTable(const BilliardTable&) = delete;
  BilliardTable& operator=(const BilliardTable&) = delete;

  /// Advances the scene by one frame (1 / frame_rate seconds).
  void step();

  /// Moves ball `ball` to `position` with `velocity` (for set-ups other than the break; z of
  /// the position is set to the ball radius, z of the velocity to 0) and restarts its
  /// trajectory there.
  void place_ball(int ball, const Vec3& position, const Vec3& velocity);

  /// The configuration.
  const BilliardConfig& config() const { return config_; }
  /// Ball centres, world frame (z = ball radius: the balls rest on the plane z = 0).
  const std::array<Vec3, kBallCount>& positions() const { return position_; }
  /// Ball velocities, world frame.
  const std::array<Vec3, kBallCount>& velocities() const { return velocity_; }
  /// Every ball's path: its centre at the start, at each of its collisions and at each frame
  /// end where it had moved.
  const std::array<std::vector<Vec3>, kBallCount>& trajectories() const { return trajectory_; }
  /// Every collision so far, in order.
  const std::vector<BilliardContact>& contacts() const { return contacts_; }
  /// Counters.
  const BilliardStats& stats() const { return stats_; }
  /// The collision world (balls and cushions; user data: ball index, or 100 + cushion).
  const CollisionWorld& world() const { return world_; }
  /// The pairs touching now as the listener's begin and end callbacks left them, sorted (equal
  /// to the pairs of world().contacts()).
  std::vector<ObjectPair> touching_from_callbacks() const;
  /// Total kinetic energy per unit ball mass, 1/2 sum |v|^2 (m^2/s^2).
  double kinetic_energy() const;

 private:
  class Listener;

  void substep(Real h);
  void resolve_impacts(Real h, const std::array<Vec3, kBallCount>& start, std::array<bool, kBallCount>& held);
  void resolve_touching(const std::array<bool, kBallCount>& held);
  void separate_overlaps();
  void sync_world();
  void collide(int ball, int other, const Vec3& normal, const Vec3& point, bool continuous);
  int body(ObjectHandle handle) const;
  void record_point(int ball);

  BilliardConfig config_;
  CollisionWorld world_;
  std::unique_ptr<Listener> listener_;
  Sphere ball_shape_;
  std::array<ObjectHandle, kBallCount> ball_{};
  std::array<ObjectHandle, kCushionCount> cushion_{};
  std::array<Vec3, kBallCount> position_{};
  std::array<Vec3, kBallCount> velocity_{};
  std::array<Real, kBallCount> owed_{};  // seconds of motion owed from an impact in the last step
  std::array<std::vector<Vec3>, kBallCount> trajectory_;
  std::vector<BilliardContact> contacts_;
  std::vector<ObjectMove> moves_;
  BilliardStats stats_;
  int frame_ = 0;
};

}  // namespace proxima::tool
