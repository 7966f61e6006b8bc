# ODOCAL_SANITIZE instruments odocal's targets with ASan + UBSan (CI runs the test suite this way).
function(odocal_set_sanitizers target)
  if(ODOCAL_SANITIZE)
    set(flags -fsanitize=address,undefined -fno-sanitize-recover=all -fno-omit-frame-pointer)
    target_compile_options(${target} PRIVATE ${flags})
    target_link_options(${target} PRIVATE ${flags})
  endif()
endfunction()
