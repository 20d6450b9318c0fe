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
