# Install rules, the manual page, bash completion and the Debian package.
#   cmake --install build --prefix P   P/bin/penink, P/lib/penink/penink_oiio.so (found by the
#                                      binary as ../lib/penink/), P/share/penink/{styles,examples},
#                                      P/share/man/man1/penink.1.gz,
#                                      P/share/bash-completion/completions/penink
#   cpack -G DEB --config build/CPackConfig.cmake   penink_<version>_<arch>.deb (prefix /usr)
# The manual page is written at build time from the binary's own --help (packaging/man_page.sh),
# so it lists every subcommand and option the binary has.

# `make install` and CPack install what is built and do not build everything first (CPack's
# preinstall step would otherwise rebuild the tree, tests included, inside the package test).
set(CMAKE_SKIP_INSTALL_ALL_DEPENDENCY ON)

set(man_page ${CMAKE_BINARY_DIR}/penink.1)
add_custom_command(OUTPUT ${man_page} ${man_page}.gz
  COMMAND bash ${CMAKE_SOURCE_DIR}/packaging/man_page.sh $<TARGET_FILE:penink> ${man_page} ${PROJECT_VERSION}
  COMMAND gzip -9nf -k ${man_page}
  DEPENDS penink ${CMAKE_SOURCE_DIR}/packaging/man_page.sh ${CMAKE_SOURCE_DIR}/packaging/penink.1.head
          ${CMAKE_SOURCE_DIR}/packaging/penink.1.tail
  COMMENT "Writing the manual page penink.1 from penink --help")
add_custom_target(penink_man ALL DEPENDS ${man_page}.gz)

install(TARGETS penink RUNTIME DESTINATION bin)
install(TARGETS penink_oiio LIBRARY DESTINATION lib/penink)
install(TARGETS penink_mpi LIBRARY DESTINATION lib/penink)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/styles/ DESTINATION share/penink/styles)
install(DIRECTORY ${CMAKE_SOURCE_DIR}/examples/ DESTINATION share/penink/examples
        PATTERN "*.dv" EXCLUDE PATTERN "*.lod" EXCLUDE PATTERN "*.tmp-*" EXCLUDE)  # caches: built on first use
install(FILES ${man_page}.gz DESTINATION share/man/man1)
install(FILES ${CMAKE_SOURCE_DIR}/packaging/penink.bash DESTINATION share/bash-completion/completions RENAME penink)
install(FILES ${CMAKE_SOURCE_DIR}/README.md DESTINATION share/doc/penink)

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_NAME penink)
set(CPACK_PACKAGE_VERSION ${PROJECT_VERSION})
set(CPACK_PACKAGE_CONTACT "penink developers <penink@invalid>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "pen-and-ink drawings of landscapes (DEMs) and models as layered vector files")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
# Libraries the binary and the module link: found by dpkg-shlibdeps. OSMesa is dlopen()ed when a
# GL context is made, so it is named here; EGL (--gl egl) is optional.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "libosmesa6")
set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "libegl1, libegl-mesa0, libgl1-mesa-dri")
include(CPack)

# Builds the package, checks its control fields and contents, unpacks it into a temporary root
# and runs the unpacked binary (help, a render of the installed example to SVG and PNG, the
# bash completion).
add_test(NAME Install.DebianPackage
         COMMAND bash ${CMAKE_SOURCE_DIR}/tests/install/package_test.sh ${CMAKE_BINARY_DIR})
set_tests_properties(Install.DebianPackage PROPERTIES TIMEOUT 300 RUN_SERIAL ON)
