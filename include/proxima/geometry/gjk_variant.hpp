#pragma once
/// @file gjk_variant.hpp
/// The choice of GJK iteration, shared by gjk::Settings (geometry/gjk.hpp) and the narrow
/// phase's PairRequest (narrowphase/contact.hpp) without either header pulling in the other.

#include <cstdint>

namespace proxima::gjk {

/// Which GJK iteration to run.
enum class Variant : std::uint8_t {
  Plain,     ///< classic GJK with the signed-volumes sub-simplex solver
  Nesterov,  ///< Nesterov-accelerated GJK (Montaut et al., RSS 2022), restarts to plain
             ///< steps when momentum stops helping
};

}  // namespace proxima::gjk
