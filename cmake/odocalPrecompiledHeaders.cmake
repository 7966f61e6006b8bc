# Precompiled third-party headers. Parsing Ceres and Eigen takes about 4 s of every file that
# includes them (3.8 s under the sanitized flags); a target's files share one parse instead
# (docs/reliability.md, "Build time"). Only third-party headers go in: odocal's own change too
# often, and the layers' include checks (odocalLayers.cmake) must still see each odocal include.
#
# The library's layers are built without them when ODOCAL_FUZZ is on (the sanitizer build of
# `make sanitize` and `make fuzz`), so that a missing #include in the library still fails a build;
# -DCMAKE_DISABLE_PRECOMPILE_HEADERS=ON does so for every target.
function(odocal_precompile_headers target)
  if(ARGN)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()
