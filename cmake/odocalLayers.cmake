# The library is built layer by layer (docs/architecture.md). Each layer compiles against an
# include tree of its own in the build directory that links in only the public headers it may
# use: odocal/error.hpp and odocal/options/ (used by all), its own headers and those of the
# layers it names in SEES. An include in the wrong direction then fails to build.
#
#   odocal_add_layer(NAME SOURCES file... SEES layer... [LINK target...] [PRECOMPILE header...]
#                    [FUZZ_COUNTERS_ONLY])
#
# makes the OBJECT library odocal_<NAME>; the odocal library is assembled from their objects.
# PRECOMPILE names third-party headers to precompile for it (cmake/odocalPrecompiledHeaders.cmake),
# except in the fuzzing build; FUZZ_COUNTERS_ONLY marks numeric code whose integer comparisons the
# fuzzing build need not trace (cmake/odocalSanitizers.cmake).
function(odocal_add_layer name)
  cmake_parse_arguments(arg "FUZZ_COUNTERS_ONLY" "" "SOURCES;SEES;LINK;PRECOMPILE" ${ARGN})
  set(root "${PROJECT_BINARY_DIR}/layer-include/${name}")
  file(REMOVE_RECURSE "${root}")
  file(MAKE_DIRECTORY "${root}/odocal")
  set(headers "${PROJECT_SOURCE_DIR}/include/odocal")
  file(CREATE_LINK "${headers}/error.hpp" "${root}/odocal/error.hpp" SYMBOLIC)
  foreach(layer IN LISTS arg_SEES ITEMS options ${name})
    if(IS_DIRECTORY "${headers}/${layer}" AND NOT EXISTS "${root}/odocal/${layer}")
      file(CREATE_LINK "${headers}/${layer}" "${root}/odocal/${layer}" SYMBOLIC)
    endif()
  endforeach()

  add_library(odocal_${name} OBJECT ${arg_SOURCES})
  target_compile_features(odocal_${name} PRIVATE cxx_std_20)
  target_include_directories(odocal_${name} PRIVATE "${root}" "${CMAKE_CURRENT_SOURCE_DIR}/${name}")
  target_link_libraries(odocal_${name} PRIVATE Eigen3::Eigen fmt::fmt ${arg_LINK})
  set_target_properties(odocal_${name} PROPERTIES POSITION_INDEPENDENT_CODE ON)
  odocal_set_warnings(odocal_${name})
  odocal_set_sanitizers(odocal_${name})
  if(arg_FUZZ_COUNTERS_ONLY)
    odocal_instrument_for_fuzzing(odocal_${name} COUNTERS_ONLY)
  else()
    odocal_instrument_for_fuzzing(odocal_${name})
  endif()
  # The fuzzing build compiles each library file on its own includes, so that a missing #include
  # still fails a build somewhere (cmake/odocalPrecompiledHeaders.cmake).
  if(NOT ODOCAL_FUZZ)
    odocal_precompile_headers(odocal_${name} ${arg_PRECOMPILE})
  endif()
endfunction()
