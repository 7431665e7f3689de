#pragma once
// ExactBilliards: the test reference of `proxima demo`'s billiard break. The same table,
// rack and shot as tool::BilliardTable, simulated event by event with exact times of impact
// over every pair (no broad phase, no collision world): the earliest impact of the frame is
// advanced to and resolved, and again until the frame holds none. The demo's game loop on
// the collision world is checked against it.
#include <proxima/core/math.hpp>
#include <proxima/shapes/halfspace.hpp>
#include <proxima/shapes/sphere.hpp>

#include <array>
#include <vector>

#include "billiard_table.hpp"

namespace proxima::test_billiards {

using tool::BilliardConfig;
using tool::BilliardContact;

/// The billiard scene simulated event by event (see the file comment).
class ExactBilliards {
 public:
  static constexpr int kBallCount = tool::BilliardTable::kBallCount;
  static constexpr int kCushionCount = tool::BilliardTable::kCushionCount;

  /// The rack and the shot of tool::BilliardTable(config).
  explicit ExactBilliards(const BilliardConfig& config);

  /// Advances the scene by one frame.
  void step();
  /// As tool::BilliardTable::place_ball.
  void place_ball(int ball, const Vec3& position, const Vec3& velocity);

  const std::array<Vec3, kBallCount>& positions() const { return position_; }
  const std::array<Vec3, kBallCount>& velocities() const { return velocity_; }
  /// Every impact so far, in order (`continuous` is true for all).
  const std::vector<BilliardContact>& contacts() const { return contacts_; }
  /// 1/2 sum |v|^2.
  double kinetic_energy() const;

 private:
  struct Impact {
    Real fraction = Real(2);  // of the remaining frame time; > 1: none
    int a = -1;
    int b = -1;  // ball, or -1 - cushion
  };
  Impact earliest_impact(Real duration) const;
  void resolve(const Impact& impact);

  BilliardConfig config_;
  Sphere contact_ball_;  // Minkowski sum of two balls: radius 2r around one centre
  std::array<HalfSpace, kCushionCount> cushion_;
  std::array<HalfSpace, kCushionCount> contact_cushion_;  // each cushion pushed out by r
  std::array<Vec3, kBallCount> position_{};
  std::array<Vec3, kBallCount> velocity_{};
  std::vector<BilliardContact> contacts_;
  int frame_ = 0;
};

}  // namespace proxima::test_billiards
