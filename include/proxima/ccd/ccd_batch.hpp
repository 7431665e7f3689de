#pragma once
/// @file ccd_batch.hpp
/// Many times of impact or shape casts per call, spread over an Executor (core/executor.hpp).
/// Every query is validated before any runs: on an error nothing is written and the error
/// names the query ("queries[12].motion_a.start.rotation"). Each query writes only its own
/// result, so the output is identical to the serial loop for every executor and thread
/// count.
#include <proxima/ccd/motion.hpp>
#include <proxima/ccd/shape_cast.hpp>
#include <proxima/ccd/time_of_impact.hpp>
#include <proxima/core/executor.hpp>
#include <proxima/core/result.hpp>
#include <proxima/shapes/shape_ref.hpp>

#include <cstddef>
#include <span>

namespace proxima {

/// One time-of-impact query: two geometries and their motions over the step.
struct ToiQuery {
  ShapeRef a;       ///< first geometry (must outlive the call)
  Motion motion_a;  ///< its motion over t in [0, 1]
  ShapeRef b;       ///< second geometry
  Motion motion_b;  ///< its motion
};

/// One shape cast: A at pose_a translated by `translation` against B at pose_b.
struct CastQuery {
  ShapeRef a;        ///< moving geometry
  Transform pose_a;  ///< its placement at t = 0
  Vec3 translation;  ///< world translation over the cast (length units)
  ShapeRef b;        ///< still geometry
  Transform pose_b;  ///< its placement
};

/// time_of_impact of every query into results[i] (results.size() must equal
/// queries.size(): InvalidArgument "results" otherwise). Returns the number of hits
/// (status Hit or InitiallyOverlapping).
Result<std::size_t> time_of_impact_batch(std::span<const ToiQuery> queries, std::span<ToiResult> results,
                                         const ToiOptions& options = {}, Executor& executor = serial_executor());

/// shape_cast of every query into results[i] (same rules as time_of_impact_batch).
Result<std::size_t> shape_cast_batch(std::span<const CastQuery> queries, std::span<CastResult> results,
                                     const CastOptions& options = {}, Executor& executor = serial_executor());

}  // namespace proxima
