#pragma once
// Helpers of the world-protocol tests: a session answering requests written as JSON text,
// with the expectation of acceptance or rejection checked on each.
#include <gtest/gtest.h>

#include <cstdint>
#include <string>

#include "world_session.hpp"

namespace proxima::test {

/// A world-protocol session over an empty world.
struct WorldSessionFixture {
  tool::WorldSession session;

  explicit WorldSessionFixture(const tool::WorldOptions& options = {})
      : session(tool::WorldSession::create(options).value()) {}

  /// Answers the request (JSON text) and checks that it was accepted (or rejected).
  tool::Json ask(const std::string& request, bool expect_ok = true) {
    bool rejected = false;
    tool::Json answer = session.answer_line(request, rejected);
    EXPECT_EQ(rejected, !expect_ok) << request << " -> " << answer.dump();
    return answer;
  }
  /// Adds an object from the members of an add request (without "op") and returns its handle.
  std::uint64_t add(const std::string& members) {
    const tool::Json answer = ask(R"({"op":"add",)" + members + "}");
    return answer.contains("object") ? answer["object"].get<std::uint64_t>() : ~0ull;
  }
  /// The answer of "hash".
  std::string hash() { return ask(R"({"op":"hash"})")["hash"].get<std::string>(); }
};

}  // namespace proxima::test
