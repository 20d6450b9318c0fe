# The install layout and the CMake package (docs/integration.md):
#   bin/spirec, bin/spire-demo, bin/spire-tune, bin/spire-explore, bin/spire-simplify
#   include/spire/<stage>/*.h   the public compile entry point, driver/compiler.h,
#                               and the headers it includes
#   lib/libspire_*.a            the compiler's stage libraries
#   share/spire/{stdlib,pipelines}   the Spire library, found by spirec
#                               relative to itself (driver/library_location.h)
#   lib/cmake/Spire/            SpireConfig.cmake, its version file, the
#                               exported targets (Spire::spirec; with
#                               COMPONENTS compiler, Spire::compiler) and
#                               spire_add_shaders()
# Every path is relative to the prefix, so an install can be moved.
include(GNUInstallDirs)
include(CMakePackageConfigHelpers)

# The build tree has the same layout for the Spire library: build/bin/spirec
# finds build/share/spire, which links to the source tree's folders.
file(MAKE_DIRECTORY ${CMAKE_BINARY_DIR}/share/spire)
foreach(folder stdlib pipelines)
  file(CREATE_LINK ${CMAKE_SOURCE_DIR}/${folder} ${CMAKE_BINARY_DIR}/share/spire/${folder} SYMBOLIC)
endforeach()

set(SPIRE_INSTALL_CMAKEDIR ${CMAKE_INSTALL_LIBDIR}/cmake/Spire)
set(SPIRE_INSTALL_LIBRARYDIR ${CMAKE_INSTALL_DATADIR}/spire)
set(SPIRE_STAGES spire_support spire_reflection spire_syntax spire_sema spire_graph spire_codegen spire_compiler)

install(TARGETS spirec EXPORT SpireToolTargets RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS spire-demo spire-tune spire-explore spire-simplify RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR})
install(TARGETS ${SPIRE_STAGES} EXPORT SpireCompilerTargets ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR})
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

install(EXPORT SpireToolTargets NAMESPACE Spire:: DESTINATION ${SPIRE_INSTALL_CMAKEDIR})
install(EXPORT SpireCompilerTargets NAMESPACE Spire:: DESTINATION ${SPIRE_INSTALL_CMAKEDIR})
configure_package_config_file(cmake/SpireConfig.cmake.in ${CMAKE_BINARY_DIR}/SpireConfig.cmake
                              INSTALL_DESTINATION ${SPIRE_INSTALL_CMAKEDIR}
                              PATH_VARS SPIRE_INSTALL_LIBRARYDIR)
# Before 1.0 a minor version may break compatibility.
write_basic_package_version_file(${CMAKE_BINARY_DIR}/SpireConfigVersion.cmake COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_BINARY_DIR}/SpireConfig.cmake ${CMAKE_BINARY_DIR}/SpireConfigVersion.cmake
              cmake/SpireShaders.cmake
        DESTINATION ${SPIRE_INSTALL_CMAKEDIR})
