# The install layout and the CMake package (docs/integration.md):
#   bin/spirec, bin/spire-demo, bin/spire-tune, bin/spire-explore, bin/spire-simplify
#   include/spire/<stage>/*.h   the public compile entry point, driver/compiler.h,
#                               and the headers it includes
#   LIBDIR/libspire_*.a         the compiler's stage libraries
#   share/spire/{stdlib,pipelines}   the Spire library, found by spirec
#                               relative to itself (driver/library_location.h)
#   LIBDIR/cmake/Spire/         SpireConfig.cmake, its version file, the
#                               exported targets (Spire::spirec; with
#                               COMPONENTS compiler, Spire::compiler) and
#                               spire_add_shaders()
# LIBDIR is CMAKE_INSTALL_LIBDIR (lib for a user prefix); the Debian package
# has its own, lib/<multiarch triplet> (cmake/SpireDebian.cmake).
# Every path is relative to the prefix, so an install can be moved.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The build tree has the same layout for the Spire library: build/bin/spirec
# finds build/share/spire, which links to the source tree's folders.
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/share/spire)
foreach(folder stdlib pipelines)
  file(CREATE_LINK ${CMAKE_SOURCE_DIR}/${folder} ${CMAKE_BINARY_DIR}/share/spire/${folder} SYMBOLIC)
endforeach()

set(SPIRE_INSTALL_LIBRARYDIR ${CMAKE_INSTALL_DATADIR}/spire)
set(SPIRE_STAGES spire_support spire_reflection spire_syntax spire_sema spire_graph spire_codegen spire_compiler)
# The tools, headers and the Spire library are the same in every layout: the
# install component "spire". What depends on the library folder is installed
# by spire_install_libdir() below, once per layout.
set(CMAKE_INSTALL_DEFAULT_COMPONENT_NAME spire)

install(TARGETS spire-demo spire-tune spire-explore spire-simplify RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
# driver/compiler.h and every project header it includes, directly or not
# (tests/install checks that a program including it builds).
install(FILES
          compiler/driver/compiler.h compiler/driver/frontend.h compiler/driver/shader_library.h
          compiler/driver/exit_codes.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/spire/driver)
install(FILES
          compiler/graph/choice_space.h compiler/graph/decision_file.h compiler/graph/shader_graph.h
          compiler/graph/variant.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/spire/graph)
install(FILES compiler/reflection/reflection.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/spire/reflection)
install(FILES compiler/sema/builtins.h compiler/sema/semantic_model.h compiler/sema/strategy_catalog.h
              compiler/sema/type.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/spire/sema)
install(FILES
          compiler/support/diagnostic.h compiler/support/diagnostic_codes.def compiler/support/diagnostic_renderer.h
          compiler/support/expected.h compiler/support/file_io.h compiler/support/source_manager.h
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/spire/support)
install(FILES compiler/syntax/ast.h DESTINATION ${CMAKE_INSTALL_INCLUDEDIR}/spire/syntax)
install(DIRECTORY stdlib pipelines DESTINATION ${SPIRE_INSTALL_LIBRARYDIR})

# Before 1.0 a minor version may break compatibility. The version file names
# no path, so every layout installs the same one.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/SpireConfigVersion.cmake COMPATIBILITY SameMinorVersion)

# spire_install_libdir(<libdir> <component> [EXCLUDE_FROM_ALL]): the stage
# libraries under <libdir>, the CMake package under <libdir>/cmake/Spire and
# spirec, which the package's exported targets name, as the install component
# <component>. The exported targets and SpireConfig.cmake find the prefix by
# counting the folders of <libdir> (the prefix is three folders above
# lib/cmake/Spire, four above lib/x86_64-linux-gnu/cmake/Spire), so each
# layout has its own export sets and its own SpireConfig.cmake.
function(spire_install_libdir libdir component)
  set(cmakedir ${libdir}/cmake/Spire)
  set(generated ${CMAKE_BINARY_DIR}/package-${component})
  install(TARGETS spirec EXPORT SpireToolTargets-${component} RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR}
          COMPONENT ${component} ${ARGN})
  install(TARGETS ${SPIRE_STAGES} EXPORT SpireCompilerTargets-${component} ARCHIVE DESTINATION ${libdir}
          COMPONENT ${component} ${ARGN})
  # The archives keep their debug info (-g, RelWithDebInfo: 160 MB of
  # archives, 5 MB without it) in a plain install, for a user debugging into
  # the compiler. CMake strips executables only (`cmake --install --strip`,
  # CPACK_STRIP_FILES); this strips the archives' debug sections too, keeping
  # their symbols, so they link as before.
  set(archives)
  foreach(stage IN LISTS SPIRE_STAGES)
    list(APPEND archives "$<TARGET_FILE_NAME:${stage}>")
  endforeach()
  install(CODE "
    if(CMAKE_INSTALL_DO_STRIP)
      foreach(archive ${archives})
        execute_process(COMMAND \"${CMAKE_STRIP}\" --strip-debug
                                \"\$ENV{DESTDIR}\${CMAKE_INSTALL_PREFIX}/${libdir}/\${archive}\"
                        COMMAND_ERROR_IS_FATAL ANY)
      endforeach()
    endif()" COMPONENT ${component} ${ARGN})

  install(EXPORT SpireToolTargets-${component} FILE SpireToolTargets.cmake NAMESPACE Spire::
          DESTINATION ${cmakedir} COMPONENT ${component} ${ARGN})
  install(EXPORT SpireCompilerTargets-${component} FILE SpireCompilerTargets.cmake NAMESPACE Spire::
          DESTINATION ${cmakedir} COMPONENT ${component} ${ARGN})
  configure_package_config_file(cmake/SpireConfig.cmake.in ${generated}/SpireConfig.cmake
                                INSTALL_DESTINATION ${cmakedir}
                                PATH_VARS SPIRE_INSTALL_LIBRARYDIR)
  install(FILES ${generated}/SpireConfig.cmake ${CMAKE_BINARY_DIR}/SpireConfigVersion.cmake
                cmake/SpireShaders.cmake
          DESTINATION ${cmakedir} COMPONENT ${component} ${ARGN})
endfunction()

# A plain `cmake --install`: CMAKE_INSTALL_LIBDIR as GNUInstallDirs chose it
# for CMAKE_INSTALL_PREFIX when the build was configured: lib for /usr/local
# or a user prefix, lib/<multiarch triplet> on Debian for /usr.
spire_install_libdir(${CMAKE_INSTALL_LIBDIR} spire-libdir)
