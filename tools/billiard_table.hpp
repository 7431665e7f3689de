#pragma once
// BilliardTable: the scene of `proxima demo`, the break of a game of pool. Sixteen balls
// (a triangle rack of 15 and the cue ball) roll on a table bounded by four cushions. The
// balls are library Spheres, the cushions library HalfSpaces; the collision response
// (equal masses, restitution, rolling resistance) lives here in the tool, never in the
// library.
#include <proxima/broadphase/sweep_and_prune.hpp>
#include <proxima/core/math.hpp>
#include <proxima/geometry/aabb.hpp>
#include <proxima/shapes/halfspace.hpp>
#include <proxima/shapes/sphere.hpp>

#include <array>
#include <cstdint>
#include <utility>
#include <vector>

namespace proxima::tool {

/// A pair of indices (ball, ball) with first < second, or (ball, cushion).
using IndexPair = std::pair<std::uint32_t, std::uint32_t>;

/// The set-up of a break. Lengths in metres, times in seconds, speeds in m/s.
struct BilliardConfig {
  int frames = 600;                       ///< frames to simulate
  double frame_rate = 60.0;               ///< frames per second
  std::uint64_t seed = 1;                 ///< jitter of the rack and the shot; 0: perfectly symmetric
  Real table_length = Real(2.54);         ///< playing surface along x (a 9-foot table)
  Real table_width = Real(1.27);          ///< playing surface along y
  Real ball_radius = Real(0.028575);      ///< pool ball (57.15 mm diameter)
  Real rack_gap = Real(0.0002);           ///< gap between neighbouring racked balls
  Real cue_speed = Real(10);              ///< speed of the cue ball at the start
  Real ball_restitution = Real(0.95);     ///< ball-ball coefficient of restitution
  Real cushion_restitution = Real(0.9);   ///< ball-cushion coefficient of restitution
  Real rolling_deceleration = Real(0.3);  ///< rolling resistance, m/s^2 (about 0.03 g)
  int max_events_per_frame = 1000;        ///< safety cap on collisions resolved in one frame
  bool brute_force_pairs = false;         ///< pass every pair on instead of sweeping (a reference for tests)
};

/// A collision that happened.
struct BilliardContact {
  Vec3 point{Real(0)};  ///< contact point, world frame
  int frame = 0;        ///< frame in which it happened
  int ball = 0;         ///< first ball
  int other = 0;        ///< second ball, or -1 - cushion index for a cushion
};

/// Counters of the detection work, summed over the frames simulated so far.
struct BilliardStats {
  std::uint64_t frames = 0;                   ///< frames simulated
  std::uint64_t brute_ball_pairs = 0;         ///< n(n-1)/2 per frame
  std::uint64_t brute_cushion_pairs = 0;      ///< n * cushions per frame
  std::uint64_t candidate_ball_pairs = 0;     ///< distinct ball pairs the broad phase passed on, per frame
  std::uint64_t candidate_cushion_pairs = 0;  ///< distinct ball-cushion pairs passed on, per frame
  std::uint64_t broad_phase_passes = 0;       ///< sweeps run (one per frame plus one per collision)
  std::uint64_t ball_collisions = 0;          ///< ball-ball impacts resolved
  std::uint64_t cushion_collisions = 0;       ///< ball-cushion impacts resolved
  std::uint64_t capped_frames = 0;            ///< frames that reached max_events_per_frame
};

/// The billiard scene and its event-driven simulation.
///
/// Each frame: 1. rolling resistance slows every ball; 2. each ball's world AABB is swept
/// over the rest of the frame (the Sphere's world_aabb at both ends, merged); 3. the library's
/// incremental sweep-and-prune (SweepAndPrune) pairs the boxes, and each box is tested against the cushions' world
/// AABBs;
/// 4. the candidates' times of impact are found by ray casts of the relative motion against
/// the Minkowski sums (a Sphere of radius 2r for a ball pair, the cushion's HalfSpace pushed
/// out by r for a cushion; Ericson, Real-Time Collision Detection, 5.5.7); 5. the earliest
/// impact is advanced to and resolved, the boxes are swept again from there, and 4-5 repeat
/// until no impact remains in the frame. Balls therefore never tunnel, however fast.
class BilliardTable {
 public:
  /// Number of balls: the cue ball (index 0) and 15 racked balls (1..15).
  static constexpr int kBallCount = 16;
  /// Number of cushions.
  static constexpr int kCushionCount = 4;

  /// Racks the balls and places the cue ball, moving at cue_speed towards the rack.
  explicit BilliardTable(const BilliardConfig& config);

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
  /// The cushions: solids n . x <= d outside the playing surface, normals pointing in.
  const std::array<HalfSpace, kCushionCount>& cushions() const { return cushion_; }
  /// Every ball's path: its centre at the start, at each of its impacts and at each frame
  /// end where it had moved.
  const std::array<std::vector<Vec3>, kBallCount>& trajectories() const { return trajectory_; }
  /// Every impact so far, in order.
  const std::vector<BilliardContact>& contacts() const { return contacts_; }
  /// Detection counters.
  const BilliardStats& stats() const { return stats_; }
  /// Total kinetic energy per unit ball mass, 1/2 sum |v|^2 (m^2/s^2).
  double kinetic_energy() const;

 private:
  struct Impact {
    Real fraction = Real(2);  // of the remaining frame time; > 1: none
    int a = -1;
    int b = -1;  // ball, or -1 - cushion
  };

  void sweep_boxes(Real duration);
  void find_candidates(std::vector<char>& ball_seen, std::vector<char>& cushion_seen);
  Impact earliest_impact(Real duration) const;
  void resolve(const Impact& impact);
  void record_point(int ball);

  BilliardConfig config_;
  Sphere ball_;          // every ball's shape
  Sphere contact_ball_;  // Minkowski sum of two balls: radius 2r around one centre
  std::array<HalfSpace, kCushionCount> cushion_;
  std::array<HalfSpace, kCushionCount> contact_cushion_;  // each cushion pushed out by r
  std::array<Aabb, kCushionCount> cushion_box_;
  std::array<Vec3, kBallCount> position_{};
  std::array<Vec3, kBallCount> velocity_{};
  std::array<Aabb, kBallCount> swept_box_{};
  std::array<std::vector<Vec3>, kBallCount> trajectory_;
  std::vector<BilliardContact> contacts_;
  std::vector<IndexPair> ball_pairs_;
  std::vector<IndexPair> cushion_pairs_;  // (ball, cushion)
  SweepAndPrune sweep_;                   // the library's incremental sweep-and-prune over the swept boxes
  bool sweep_filled_ = false;             // balls inserted into sweep_
  std::vector<ProxyPair> proxy_pairs_;
  BilliardStats stats_;
  int frame_ = 0;
};

}  // namespace proxima::tool
