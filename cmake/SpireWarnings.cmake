# Warning flags for every target of the project, applied with
# spire_set_warnings(target).
function(spire_set_warnings target)
  target_compile_options(${target} PRIVATE -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor
                                           -Wold-style-cast -Wcast-align -Woverloaded-virtual
                                           -Wimplicit-fallthrough)
  if(SPIRE_WERROR)
    target_compile_options(${target} PRIVATE -Werror)
  endif()
endfunction()
