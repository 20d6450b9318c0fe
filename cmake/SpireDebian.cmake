# A Debian package of the install (cmake/SpirePackage.cmake), made with
# `cpack -G DEB --config build/CPackConfig.cmake`: spire_<version>_<arch>.deb
# with everything under /usr. Its Depends are the Debian 12 packages whose
# shared libraries the tools load (ldd of spirec, spire-demo, spire-tune);
# what only building on Spire::compiler needs is suggested. Checked by the
# DebianPackage test (tests/install/deb_test.sh).
set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME spire)
set(CPACK_PACKAGE_VENDOR "Spire")
set(CPACK_PACKAGE_CONTACT "Spire developers <spire@invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Spire shader compiler (spirec), its library, demo engine and CMake package")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
# Debian keeps libraries, and the CMake packages that name them, under
# /usr/lib/<multiarch triplet> (GNUInstallDirs picks that folder only when
# CMAKE_INSTALL_PREFIX is /usr, and this build may have been configured for
# another prefix). When the build's own library folder is another, the
# package installs the libraries and the CMake package a second way, the
# component spire-deb-libdir, which a plain install leaves out.
set(SPIRE_DEB_LIBDIR lib)
if(CMAKE_LIBRARY_ARCHITECTURE)
  set(SPIRE_DEB_LIBDIR lib/${CMAKE_LIBRARY_ARCHITECTURE})
endif()
set(spire_deb_libdir_component spire-libdir)
if(NOT CMAKE_INSTALL_LIBDIR STREQUAL SPIRE_DEB_LIBDIR)
  set(spire_deb_libdir_component spire-deb-libdir)
  spire_install_libdir(${SPIRE_DEB_LIBDIR} ${spire_deb_libdir_component} EXCLUDE_FROM_ALL)
endif()
# find_package searches <prefix>/lib/<triplet>/cmake only once a language is
# enabled (it needs CMAKE_LIBRARY_ARCHITECTURE), and a project that only
# compiles shaders may enable none (project(... LANGUAGES NONE)). So the
# package also has /usr/share/cmake/Spire, searched in every project, whose
# SpireConfig.cmake loads the one under lib/<triplet>.
if(NOT SPIRE_DEB_LIBDIR STREQUAL "lib")
  set(forward ${CMAKE_BINARY_DIR}/package-share-cmake/SpireConfig.cmake)
  file(WRITE ${forward}
       "# The Spire CMake package is ${SPIRE_DEB_LIBDIR}/cmake/Spire (cmake/SpireDebian.cmake says why this file).\n"
       "include(\"\${CMAKE_CURRENT_LIST_DIR}/../../../${SPIRE_DEB_LIBDIR}/cmake/Spire/SpireConfig.cmake\")\n")
  set(exclude)
  if(spire_deb_libdir_component STREQUAL "spire-deb-libdir")
    set(exclude EXCLUDE_FROM_ALL)
  endif()
  install(FILES ${forward} ${CMAKE_BINARY_DIR}/SpireConfigVersion.cmake DESTINATION ${CMAKE_INSTALL_DATADIR}/cmake/Spire
          COMPONENT ${spire_deb_libdir_component} ${exclude})
endif()
# One package (no CPack components) of the two install components.
set(CPACK_INSTALL_CMAKE_PROJECTS "${CMAKE_BINARY_DIR};${PROJECT_NAME};spire;/"
                                 "${CMAKE_BINARY_DIR};${PROJECT_NAME};${spire_deb_libdir_component};/")
# Strips the tools and the debug info of the static libraries
# (spire_install_libdir in cmake/SpirePackage.cmake): a user of the package
# links the libraries and runs the tools; debugging into them takes a build
# of the sources. With the libraries' debug info the package was 50 MB
# (203 MB installed), without it 18 MB (45 MB installed). There is no -dbg
# package: the tools' debug info alone is 430 MB (bin/ is 473 MB unstripped,
# 41 MB stripped), and whoever debugs Spire builds it from its sources.
set(CPACK_STRIP_FILES ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION devel)
set(CPACK_DEBIAN_PACKAGE_DEPENDS
    "libc6 (>= 2.36), libstdc++6 (>= 12), libgcc-s1, libfmt9, libvulkan1, libglfw3, libstb0, libtinygltf2d")
# spire-demo and spire-tune render through a Vulkan driver (lavapipe).
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "mesa-vulkan-drivers")
# spire_add_shaders() needs CMake and a build tool; Spire::compiler needs
# the headers and static libraries of what it links.
set(CPACK_DEBIAN_PACKAGE_SUGGESTS
    "cmake (>= 3.25), ninja-build | make, libfmt-dev, nlohmann-json3-dev, libcli11-dev, glslang-dev, spirv-tools")
include(CPack)
