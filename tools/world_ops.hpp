#pragma once
// The handlers of the world protocol's operations (docs/world-protocol.md), listed in the
// table of world_session.cpp: objects (world_object_ops.cpp), the step and the state
// (world_step_ops.cpp), scene queries (world_query_ops.cpp).
#include "json_values.hpp"

namespace proxima::tool {

class WorldSession;

/// {"op":"add","geometry":G,...} -> {"object":H}.
Json op_world_add(WorldSession& session, const Json& request);
/// {"op":"remove","object":H} -> {"removed":[H,...]} (the object and its attached subtree).
Json op_world_remove(WorldSession& session, const Json& request);
/// {"op":"move","object":H,"pose":P} or {"op":"move","objects":[{"object":H,"pose":P},...]}.
Json op_world_move(WorldSession& session, const Json& request);
/// {"op":"set_geometry","object":H,"geometry":G}.
Json op_world_set_geometry(WorldSession& session, const Json& request);
/// {"op":"set_filter","object":H,"filter":F}.
Json op_world_set_filter(WorldSession& session, const Json& request);
/// {"op":"set_kind","object":H,"kind":K}.
Json op_world_set_kind(WorldSession& session, const Json& request);
/// {"op":"set_ccd","object":H,"ccd":C}.
Json op_world_set_ccd(WorldSession& session, const Json& request);
/// {"op":"set_user_data","object":H,"user_data":U}.
Json op_world_set_user_data(WorldSession& session, const Json& request);
/// {"op":"attach","object":H,"parent":H|null,"local_pose":P}.
Json op_world_attach(WorldSession& session, const Json& request);
/// {"op":"exclude","a":H,"b":H,"excluded":bool}.
Json op_world_exclude(WorldSession& session, const Json& request);

/// {"op":"step","dt":s,"contacts":bool} -> the step's events (and manifolds).
Json op_world_step(WorldSession& session, const Json& request);
/// {"op":"hash"} -> {"hash":"<16 hex digits>"}.
Json op_world_hash(WorldSession& session, const Json& request);
/// {"op":"save","file":F} -> {"ok":true}.
Json op_world_save(WorldSession& session, const Json& request);
/// {"op":"load","file":F} -> {"objects":n}: the session's world becomes the snapshot's.
Json op_world_load(WorldSession& session, const Json& request);

/// {"op":"raycast","origin","direction","max_t"?,"filter"?,"mode"?} -> {"hits":[...]}.
Json op_world_raycast(WorldSession& session, const Json& request);
/// {"op":"line_of_sight","from","to","filter"?} -> {"clear":bool}.
Json op_world_line_of_sight(WorldSession& session, const Json& request);
/// {"op":"overlap", "geometry"+"pose"? | "box" | "point", "filter"?, "mode"?} -> {"objects":[H,...]}.
Json op_world_overlap(WorldSession& session, const Json& request);
/// {"op":"sweep","geometry","pose"?,"translation","filter"?,"mode"?} -> {"hits":[...]}.
Json op_world_sweep(WorldSession& session, const Json& request);
/// {"op":"closest", "point" | "geometry"+"pose"?, "max_distance", "filter"?} -> {"object":H,...}.
Json op_world_closest(WorldSession& session, const Json& request);

}  // namespace proxima::tool
