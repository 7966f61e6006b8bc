# Precompiled third-party headers. Parsing Ceres and Eigen takes about 4 s of every file that
# includes them (3.8 s under the sanitized flags); a target's files share one parse instead
# (docs/reliability.md, "Build time"). Only third-party headers go in: odocal's own change too
# often, and the layers' include checks (odocalLayers.cmake) must still see each odocal include.
#
# -DCMAKE_DISABLE_PRECOMPILE_HEADERS=ON builds every file on its own includes, so that a missing
# #include still fails a build: the fuzz build does so (Makefile).
function(odocal_precompile_headers target)
  if(ARGN)
    target_precompile_headers(${target} PRIVATE ${ARGN})
  endif()
endfunction()
