// Batched times of impact and shape casts: validate everything, then one query per item of
// the executor's range, each writing its own slot (deterministic for any thread count).

#include <proxima/ccd/ccd_batch.hpp>
#include <proxima/core/validate.hpp>

#include <algorithm>
#include <string>
#include <string_view>

namespace proxima {

namespace {

// Errors of the single-query functions carry their own field names; prefix the query.
Error in_query(Error e, std::size_t i) {
  e.field = "queries[" + std::to_string(i) + "]." + e.field;
  return e;
}

std::optional<Error> check_pose(const Transform& pose, std::string_view name) {
  if (validate::is_acceptable(pose.position) && validate::is_unit(pose.rotation)) return std::nullopt;
  const std::string n(name);
  if (auto e = validate::finite(pose.position, n + ".position")) return e;
  return validate::unit_quaternion(pose.rotation, n + ".rotation");
}

// Items per executor call: a handful of grains per thread, whole queries each.
template <class Query, class Answer, class Solve>
std::size_t run_all(std::span<const Query> queries, std::span<Answer> results, Executor& executor, Solve&& solve) {
  executor.run(queries.size(), [&](std::size_t begin, std::size_t end) {
    for (std::size_t i = begin; i < end; ++i) results[i] = solve(queries[i]);
  });
  std::size_t hits = 0;
  for (const Answer& r : results) {
    hits += (r.status == CcdStatus::Hit || r.status == CcdStatus::InitiallyOverlapping) ? 1 : 0;
  }
  return hits;
}

}  // namespace

Result<std::size_t> time_of_impact_batch(std::span<const ToiQuery> queries, std::span<ToiResult> results,
                                         const ToiOptions& options, Executor& executor) {
  if (results.size() != queries.size()) {
    return make_error(ErrorCode::InvalidArgument, "results", "must have one entry per query");
  }
  for (std::size_t i = 0; i < queries.size(); ++i) {
    if (auto e = validate_motion(queries[i].motion_a, "motion_a")) return in_query(*e, i);
    if (auto e = validate_motion(queries[i].motion_b, "motion_b")) return in_query(*e, i);
  }
  if (auto e = validate_toi_options(options)) return *e;
  return run_all(queries, results, executor, [&](const ToiQuery& q) {
    const auto r = time_of_impact(q.a, q.motion_a, q.b, q.motion_b, options);
    return r ? *r : ToiResult{};
  });
}

Result<std::size_t> shape_cast_batch(std::span<const CastQuery> queries, std::span<CastResult> results,
                                     const CastOptions& options, Executor& executor) {
  if (results.size() != queries.size()) {
    return make_error(ErrorCode::InvalidArgument, "results", "must have one entry per query");
  }
  for (std::size_t i = 0; i < queries.size(); ++i) {
    if (auto e = check_pose(queries[i].pose_a, "pose_a")) return in_query(*e, i);
    if (auto e = validate::finite(queries[i].translation, "translation")) return in_query(*e, i);
    if (auto e = check_pose(queries[i].pose_b, "pose_b")) return in_query(*e, i);
  }
  if (auto e = validate_cast_options(options)) return *e;
  return run_all(queries, results, executor, [&](const CastQuery& q) {
    const auto r = shape_cast(q.a, q.pose_a, q.translation, q.b, q.pose_b, options);
    return r ? *r : CastResult{};
  });
}

}  // namespace proxima
