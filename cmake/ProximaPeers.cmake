# Optional peer libraries (FCL, libccd, Bullet, ODE, Embree 3, Box2D 2.4), used by the
# benchmarks and the cross-validation tests only, never by the library.
include_guard(GLOBAL)
# Optional peer libraries: each found one becomes an INTERFACE target
# proxima_peer_<name> carrying its include paths, libraries and PROXIMA_HAVE_<NAME>=1.
# All of them are gathered in proxima_peer_libraries, which the benchmarks and the
# cross-validation tests link. Included once, by whichever of bench/ or tests/ comes first.
find_package(PkgConfig QUIET)
add_library(proxima_peer_libraries INTERFACE)
set(proxima_peer_report "")

function(proxima_add_peer name define)
  # ARGN: pkg-config module names to try in order.
  set(result "no")
  if(PKG_CONFIG_FOUND)
    foreach(module IN LISTS ARGN)
      pkg_check_modules(PROXIMA_PEER_${name} QUIET IMPORTED_TARGET GLOBAL ${module})
      if(PROXIMA_PEER_${name}_FOUND)
        # Drop a language standard from the .pc file (FCL's says -std=c++11): the
        # benchmarks are C++20.
        get_target_property(peer_options PkgConfig::PROXIMA_PEER_${name} INTERFACE_COMPILE_OPTIONS)
        if(peer_options)
          list(FILTER peer_options EXCLUDE REGEX "^-std=")
          set_property(TARGET PkgConfig::PROXIMA_PEER_${name} PROPERTY INTERFACE_COMPILE_OPTIONS "${peer_options}")
        endif()
        add_library(proxima_peer_${name} INTERFACE)
        target_link_libraries(proxima_peer_${name} INTERFACE PkgConfig::PROXIMA_PEER_${name})
        target_compile_definitions(proxima_peer_${name} INTERFACE ${define}=1)
        target_link_libraries(proxima_peer_libraries INTERFACE proxima_peer_${name})
        set(result "${PROXIMA_PEER_${name}_VERSION}")
        if(result STREQUAL "")
          set(result "yes")
        endif()
        break()
      endif()
    endforeach()
  endif()
  set(proxima_peer_report "${proxima_peer_report} ${name}=${result}" PARENT_SCOPE)
endfunction()

proxima_add_peer(fcl PROXIMA_HAVE_FCL fcl)
proxima_add_peer(ccd PROXIMA_HAVE_CCD ccd)
proxima_add_peer(bullet PROXIMA_HAVE_BULLET bullet)
proxima_add_peer(ode PROXIMA_HAVE_ODE ode)
# Box2D 2.4 (Debian's libbox2d-dev ships box2d.pc): the 2D module's peer. Its .pc also adds
# /usr/include/box2d, so its headers are included as <box2d/b2_*.h>.
proxima_add_peer(box2d PROXIMA_HAVE_BOX2D box2d)

# Embree 3: its CMake package first, then pkg-config.
find_package(embree 3 CONFIG QUIET)
if(embree_FOUND AND TARGET embree)
  add_library(proxima_peer_embree INTERFACE)
  target_link_libraries(proxima_peer_embree INTERFACE embree)
  target_compile_definitions(proxima_peer_embree INTERFACE PROXIMA_HAVE_EMBREE=1)
  target_link_libraries(proxima_peer_libraries INTERFACE proxima_peer_embree)
  set(proxima_peer_report "${proxima_peer_report} embree=${embree_VERSION}")
else()
  proxima_add_peer(embree PROXIMA_HAVE_EMBREE embree3)
endif()
message(STATUS "proxima peers:${proxima_peer_report}")
