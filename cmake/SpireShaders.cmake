# spire_add_shaders(): compiles Spire sources with spirec at build time.
#
#   spire_add_shaders(TARGET <name>
#                     SOURCES <a.spire> [<b.spire> ...]
#                     OUTPUT_DIR <dir>
#                     [DECISIONS <file> | <file per source> ...]
#                     [INCLUDE_DIRS <dir> ...]
#                     [OPTIONS <spirec flag> ...])
#
# Adds the target <name> (built by default) that runs `spirec SOURCE -o DIR`
# once per source; each shader of a source gets DIR/<Shader>/ with its kernels
# and reflection.json. One DECISIONS file applies to every source; otherwise
# give one per source, in the order of SOURCES. Relative paths are relative to
# the current source directory, except OUTPUT_DIR, which is relative to the
# current binary directory. OPTIONS go to spirec as they are (--emit=glsl,
# -Werror, --pipeline NAME, ...).
#
# spirec writes a depfile (--depfile) naming every file it read, so a source
# is compiled again when it, a file it reaches through `using`, or its
# decision file changes, and only then. Ninja and Makefile generators both
# support this.
include_guard(GLOBAL)

# Absolute paths of `paths`, relative ones taken from `base`.
function(_spire_absolute_paths out base)
  set(result)
  foreach(path IN LISTS ARGN)
    cmake_path(ABSOLUTE_PATH path BASE_DIRECTORY ${base} NORMALIZE OUTPUT_VARIABLE absolute)
    list(APPEND result ${absolute})
  endforeach()
  set(${out} ${result} PARENT_SCOPE)
endfunction()

# Checks the arguments of spire_add_shaders and fails with a message that
# names the mistake.
function(_spire_check_shader_arguments)
  if(ARG_UNPARSED_ARGUMENTS)
    message(FATAL_ERROR "spire_add_shaders: unexpected arguments: ${ARG_UNPARSED_ARGUMENTS}")
  endif()
  foreach(required TARGET SOURCES OUTPUT_DIR)
    if(NOT ARG_${required})
      message(FATAL_ERROR "spire_add_shaders: ${required} is required")
    endif()
  endforeach()
  list(LENGTH ARG_SOURCES sourceCount)
  list(LENGTH ARG_DECISIONS decisionCount)
  if(decisionCount GREATER 1 AND NOT decisionCount EQUAL sourceCount)
    message(FATAL_ERROR "spire_add_shaders(${ARG_TARGET}): DECISIONS names ${decisionCount} files for "
                        "${sourceCount} sources; give one file for all sources or one per source")
  endif()
  if(NOT TARGET Spire::spirec)
    message(FATAL_ERROR "spire_add_shaders: Spire::spirec is not defined; call find_package(Spire) first")
  endif()
endfunction()

function(spire_add_shaders)
  cmake_parse_arguments(ARG "" "TARGET;OUTPUT_DIR" "SOURCES;DECISIONS;INCLUDE_DIRS;OPTIONS" ${ARGN})
  _spire_check_shader_arguments()
  _spire_absolute_paths(sources ${CMAKE_CURRENT_SOURCE_DIR} ${ARG_SOURCES})
  _spire_absolute_paths(decisions ${CMAKE_CURRENT_SOURCE_DIR} ${ARG_DECISIONS})
  _spire_absolute_paths(includeDirs ${CMAKE_CURRENT_SOURCE_DIR} ${ARG_INCLUDE_DIRS})
  _spire_absolute_paths(outputDir ${CMAKE_CURRENT_BINARY_DIR} ${ARG_OUTPUT_DIR})
  set(includeFlags)
  foreach(dir IN LISTS includeDirs)
    list(APPEND includeFlags -I ${dir})
  endforeach()
  # Per source: a stamp (the command's output, touched after spirec
  # succeeds) and the depfile whose target it is.
  set(stateDir ${CMAKE_CURRENT_BINARY_DIR}/spire_shaders/${ARG_TARGET})
  set(stamps)
  set(stems)
  list(LENGTH decisions decisionCount)
  set(index 0)
  foreach(source IN LISTS sources)
    cmake_path(GET source STEM stem)
    if(stem IN_LIST stems)
      set(stem ${stem}-${index})
    endif()
    list(APPEND stems ${stem})
    set(decisionFile)
    if(decisionCount EQUAL 1)
      set(decisionFile ${decisions})
    elseif(decisionCount GREATER 1)
      list(GET decisions ${index} decisionFile)
    endif()
    set(decisionFlags)
    if(decisionFile)
      set(decisionFlags --decisions ${decisionFile})
    endif()
    set(stamp ${stateDir}/${stem}.stamp)
    add_custom_command(
      OUTPUT ${stamp}
      COMMAND ${CMAKE_COMMAND} -E make_directory ${stateDir}
      COMMAND Spire::spirec ${source} -o ${outputDir} ${decisionFlags} ${includeFlags} ${ARG_OPTIONS}
              --depfile ${stateDir}/${stem}.d --depfile-target ${stamp}
      COMMAND ${CMAKE_COMMAND} -E touch ${stamp}
      DEPENDS ${source} ${decisionFile} $<TARGET_FILE:Spire::spirec>
      DEPFILE ${stateDir}/${stem}.d
      COMMENT "Compiling Spire shaders in ${source}"
      VERBATIM)
    list(APPEND stamps ${stamp})
    math(EXPR index "${index} + 1")
  endforeach()
  add_custom_target(${ARG_TARGET} ALL DEPENDS ${stamps})
endfunction()
