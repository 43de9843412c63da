# Install rules for the engine as a package: the archive, the public headers, the exported target
# ballbox::engine with ballboxConfig.cmake and its version file, and ballbox.pc for pkg-config.
# All in the component "engine", so `cmake --install BUILD --component engine` needs only the
# engine built.
set_target_properties(engine PROPERTIES
  OUTPUT_NAME ballbox_engine  # libballbox_engine.a: a bare libengine.a would be ambiguous in lib/
  EXPORT_NAME engine)         # ballbox:: + engine

install(TARGETS engine EXPORT ballboxTargets
        ARCHIVE DESTINATION ${CMAKE_INSTALL_LIBDIR} COMPONENT engine)
# The whole folder, so a new public header needs no edit here.
install(DIRECTORY ${PROJECT_SOURCE_DIR}/engine/include/engine
        DESTINATION ${CMAKE_INSTALL_INCLUDEDIR} COMPONENT engine
        FILES_MATCHING PATTERN "*.h")

# find_package(ballbox): the config, its version and the targets, all relocatable (paths relative
# to the installed files), so `--prefix` at install time works.
set(BALLBOX_CMAKE_DIR ${CMAKE_INSTALL_LIBDIR}/cmake/ballbox)
install(EXPORT ballboxTargets NAMESPACE ballbox:: DESTINATION ${BALLBOX_CMAKE_DIR} COMPONENT engine)
include(CMakePackageConfigHelpers)
configure_package_config_file(${CMAKE_CURRENT_LIST_DIR}/ballboxConfig.cmake.in
                              ${CMAKE_CURRENT_BINARY_DIR}/ballboxConfig.cmake
                              INSTALL_DESTINATION ${BALLBOX_CMAKE_DIR})
# A 0.x version promises nothing across minor releases (semver), so a request for 0.1 accepts
# 0.1.z only; SameMajorVersion would hand 0.2 to a program written against 0.1. From 1.0 on,
# SameMajorVersion fits.
write_basic_package_version_file(${CMAKE_CURRENT_BINARY_DIR}/ballboxConfigVersion.cmake
                                 COMPATIBILITY SameMinorVersion)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ballboxConfig.cmake
              ${CMAKE_CURRENT_BINARY_DIR}/ballboxConfigVersion.cmake
        DESTINATION ${BALLBOX_CMAKE_DIR} COMPONENT engine)

# pkg-config: the prefix found from the .pc file's own folder (${pcfiledir}), so the file stays
# right under `--prefix` and DESTDIR; an absolute libdir can only be written as it is.
if(IS_ABSOLUTE ${CMAKE_INSTALL_LIBDIR})
  set(BALLBOX_PC_PREFIX ${CMAKE_INSTALL_PREFIX})
else()
  file(RELATIVE_PATH BALLBOX_PC_UP /${CMAKE_INSTALL_LIBDIR}/pkgconfig /)  # ../.. (lib/pkgconfig)
  string(REGEX REPLACE "/$" "" BALLBOX_PC_UP ${BALLBOX_PC_UP})
  set(BALLBOX_PC_PREFIX "\${pcfiledir}/${BALLBOX_PC_UP}")
endif()
foreach(dir LIBDIR INCLUDEDIR)
  if(IS_ABSOLUTE ${CMAKE_INSTALL_${dir}})
    set(BALLBOX_PC_${dir} ${CMAKE_INSTALL_${dir}})
  else()
    set(BALLBOX_PC_${dir} "\${prefix}/${CMAKE_INSTALL_${dir}}")
  endif()
endforeach()
configure_file(${CMAKE_CURRENT_LIST_DIR}/ballbox.pc.in ${CMAKE_CURRENT_BINARY_DIR}/ballbox.pc @ONLY)
install(FILES ${CMAKE_CURRENT_BINARY_DIR}/ballbox.pc
        DESTINATION ${CMAKE_INSTALL_LIBDIR}/pkgconfig COMPONENT engine)
