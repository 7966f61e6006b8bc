# ODOCAL_SANITIZE instruments odocal's targets with ASan + UBSan (CI runs the test suite this way).
function(odocal_set_sanitizers target)
  if(ODOCAL_SANITIZE)
    set(flags -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
    # -O1 as ASan's own documentation advises: Eigen and Ceres at -O0 made the sanitized suite
    # eleven times slower than the Release one (docs/reliability.md). Assertions stay on.
    # -g1: the line tables that a sanitizer's report needs for file and line, without the types
    # and locals of every Eigen and Ceres template: a quarter of the build's time, two thirds of
    # its disk (docs/reliability.md).
    target_compile_options(${target} PRIVATE ${flags} -O1 -g1)
    # Under ASan, Eigen stops trusting malloc's 16-byte alignment and over-allocates, storing the
    # real pointer in front; Debian's Ceres is not built so, and a matrix allocated by one side
    # and freed by the other is a bad free. glibc and ASan both align to 16: say so.
    target_compile_definitions(${target} PRIVATE EIGEN_MALLOC_ALREADY_ALIGNED=1)
    # libstdc++'s own precondition checks: an index past a vector's size but inside its capacity
    # is memory ASan sees as valid (the batch's reverted GNSS adaptation read one for months),
    # and a normal distribution with a sigma of 0 is outside the standard's contract.
    target_compile_definitions(${target} PRIVATE _GLIBCXX_ASSERTIONS)
    target_link_options(${target} PRIVATE ${flags})
  endif()
endfunction()

# ODOCAL_FUZZ (with ODOCAL_SANITIZE, clang): the library's code also carries libFuzzer's coverage
# instrumentation, so that the harnesses in fuzz/ link against the objects the sanitized test suite
# uses and CI compiles the library twice instead of three times. The tests themselves stay
# uninstrumented for coverage: they only need ASan and UBSan.
#
# COUNTERS_ONLY leaves out the comparison and indirect-call tracing (libFuzzer's way to guess magic
# values), which matters to parsers and costs numeric code a callback in every integer compare of
# every Eigen loop: on the estimation layer it made the sanitized suite 40 % slower (488 s against
# 346 s, docs/reliability.md "Build time").
function(odocal_instrument_for_fuzzing target)
  cmake_parse_arguments(arg "COUNTERS_ONLY" "" "" ${ARGN})
  if(NOT ODOCAL_FUZZ)
    return()
  endif()
  if(arg_COUNTERS_ONLY)
    target_compile_options(${target} PRIVATE -fsanitize-coverage=inline-8bit-counters,pc-table)
  else()
    target_compile_options(${target} PRIVATE -fsanitize=fuzzer-no-link)
  endif()
endfunction()
