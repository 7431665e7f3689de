#pragma once
/// @file world_settings.hpp
/// WorldSettings: a CollisionWorld's configuration, fixed at creation. The defaults need no
/// tuning for worlds in metres.
#include <proxima/core/math.hpp>

#include <optional>
#include <string>

namespace proxima {

struct Error;

/// Configuration of a CollisionWorld (see CollisionWorld::create).
struct WorldSettings {
  /// The broad-phase structure, by registry name (broadphase/any_broadphase.hpp:
  /// "tree", "sap", "grid", "hash", "hgrid", "mbp", "octree", ...). The dynamic AABB tree
  /// is the default: it handles any mix of sizes, static level geometry and unbounded worlds.
  std::string broadphase = "tree";
  /// Speculative contact distance (length units, >= 0): pairs whose gap is at most this
  /// touch (their manifold points have depth -gap). 0: touching or overlapping only.
  Real contact_distance = Real(0);
  /// Largest number of points per contact manifold (1..4).
  int max_contacts = 4;
  /// Whether two sensors sense each other.
  bool sensors_sense_sensors = false;
  /// Master switch of continuous detection (objects' CcdMode applies when on).
  bool continuous = true;
  /// An object is fast in a step when a point of it may move farther than this times its
  /// smallest extent (the thickness of its bounding box's thinnest side; the radius bound of
  /// its rotation counts too). In (0, 1]; smaller is safer and costs more time-of-impact queries.
  Real ccd_safety_factor = Real(0.25);
  /// Length tolerance of the time of impact (ToiOptions::tolerance; 0: the default).
  Real ccd_tolerance = Real(0);
};

/// An Error naming the first invalid field ("settings.contact_distance", ...), or nothing.
std::optional<Error> validate_world_settings(const WorldSettings& settings);

}  // namespace proxima
