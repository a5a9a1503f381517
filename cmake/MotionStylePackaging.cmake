# Install layout and the Debian package (CPack DEB). Included from the top CMakeLists.txt after the
# targets exist. The executables install themselves (app/cli, app/gui: bin/); this file adds the data:
#
#   share/motionstyle/models/     shipped networks (*.net), the loss network's reconstruction memory
#                                 (*.memory) with their NOTICE and recipe
#   share/motionstyle/samples/    demo clips with their licences
#   share/applications/           motionstyle.desktop
#   share/icons/hicolor/          motionstyle.svg (scalable) and a 256 px PNG
#   share/mime/packages/          the BVH MIME type the desktop entry opens
#   share/man/man1/               motionstyle-cli.1.gz, motionstyle.1.gz
#   share/doc/motionstyle/        copyright and every licence or notice that ships
#
# core/common/resource_paths.h finds share/motionstyle from bin/ (<exe>/../share/motionstyle), so the
# layout must keep bin/ and share/ siblings under one prefix.
#
# Build the package:  cmake --build B --target package   (or: cd B && cpack -G DEB)
# It must be configured with -DMOTIONSTYLE_ARCH=portable: a native build would crash with "illegal
# instruction" on an older CPU (checked below).

include(GNUInstallDirs)

set(_resources "${PROJECT_SOURCE_DIR}/resources")
set(_packaging "${PROJECT_SOURCE_DIR}/packaging")
set(MOTIONSTYLE_DATA_INSTALL_DIR "${CMAKE_INSTALL_DATADIR}/motionstyle")

# --- data ---------------------------------------------------------------------------------------
# Only the files meant to ship: training leaves *.checkpoint and logs next to the networks.
install(DIRECTORY "${_resources}/models/" DESTINATION "${MOTIONSTYLE_DATA_INSTALL_DIR}/models"
        FILES_MATCHING PATTERN "*.net" PATTERN "*.memory" PATTERN "*.png" PATTERN "NOTICE" PATTERN "README.md" PATTERN "*.sh")
install(DIRECTORY "${_resources}/samples/" DESTINATION "${MOTIONSTYLE_DATA_INSTALL_DIR}/samples"
        FILES_MATCHING PATTERN "*.bvh" PATTERN "LICENSE*" PATTERN "README.md")

# --- desktop integration ------------------------------------------------------------------------
if(MOTIONSTYLE_BUILD_GUI)
  install(FILES "${_packaging}/motionstyle.desktop" DESTINATION "${CMAKE_INSTALL_DATADIR}/applications")
  install(FILES "${_packaging}/motionstyle.svg" DESTINATION "${CMAKE_INSTALL_DATADIR}/icons/hicolor/scalable/apps")
  install(FILES "${_packaging}/motionstyle.png" DESTINATION "${CMAKE_INSTALL_DATADIR}/icons/hicolor/256x256/apps")
  install(FILES "${_packaging}/motionstyle-mime.xml" DESTINATION "${CMAKE_INSTALL_DATADIR}/mime/packages"
          RENAME motionstyle.xml)
endif()

# --- man pages (gzipped, reproducibly: -n drops the name and time stamp) -----------------------------
set(_man_pages "${_packaging}/motionstyle-cli.1")
if(MOTIONSTYLE_BUILD_GUI)
  list(APPEND _man_pages "${_packaging}/motionstyle.1")
endif()
# The pages are hand-written: say so when their header lags behind the project's version.
foreach(page IN LISTS _man_pages)
  file(STRINGS "${page}" _title REGEX "^\\.TH ")
  if(NOT _title MATCHES "\"MotionStyle ${PROJECT_VERSION}\"")
    message(WARNING "${page}: its .TH line (${_title}) does not name MotionStyle ${PROJECT_VERSION}")
  endif()
endforeach()
find_program(MOTIONSTYLE_GZIP gzip)
set(_man_outputs "")
foreach(page IN LISTS _man_pages)
  get_filename_component(_name "${page}" NAME)
  if(MOTIONSTYLE_GZIP)
    set(_out "${PROJECT_BINARY_DIR}/man/${_name}.gz")
    add_custom_command(OUTPUT "${_out}"
      COMMAND "${CMAKE_COMMAND}" -E make_directory "${PROJECT_BINARY_DIR}/man"
      COMMAND "${MOTIONSTYLE_GZIP}" -9 -n -c "${page}" > "${_out}"
      DEPENDS "${page}" VERBATIM)
    list(APPEND _man_outputs "${_out}")
  else()
    list(APPEND _man_outputs "${page}")
  endif()
endforeach()
add_custom_target(motionstyle_man_pages ALL DEPENDS ${_man_outputs})
install(FILES ${_man_outputs} DESTINATION "${CMAKE_INSTALL_MANDIR}/man1")

# --- licences -----------------------------------------------------------------------------------
set(MOTIONSTYLE_DOC_INSTALL_DIR "${CMAKE_INSTALL_DATADIR}/doc/motionstyle")
install(FILES "${_packaging}/copyright" DESTINATION "${MOTIONSTYLE_DOC_INSTALL_DIR}")
install(FILES "${_resources}/models/NOTICE" DESTINATION "${MOTIONSTYLE_DOC_INSTALL_DIR}" RENAME NOTICE.models)
install(FILES "${_resources}/samples/LICENSE.bvh11" "${_resources}/samples/LICENSE.zombie"
        DESTINATION "${MOTIONSTYLE_DOC_INSTALL_DIR}")
foreach(licence LICENSE LICENSE.md LICENSE.txt COPYING)
  if(EXISTS "${PROJECT_SOURCE_DIR}/${licence}")
    install(FILES "${PROJECT_SOURCE_DIR}/${licence}" DESTINATION "${MOTIONSTYLE_DOC_INSTALL_DIR}")
  endif()
endforeach()

# --- CPack: Debian package ----------------------------------------------------------------------
set(MOTIONSTYLE_PACKAGE_MAINTAINER "MotionStyle maintainers <motionstyle@localhost>"
    CACHE STRING "Maintainer field of the Debian package: Name <e-mail>")

set(CPACK_GENERATOR "DEB")
set(CPACK_PACKAGE_NAME "motionstyle")
set(CPACK_PACKAGE_VENDOR "MotionStyle")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${PROJECT_DESCRIPTION}")
set(CPACK_PACKAGE_CONTACT "${MOTIONSTYLE_PACKAGE_MAINTAINER}")
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_STRIP_FILES ON)

set(CPACK_DEBIAN_PACKAGE_NAME "motionstyle")
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)  # motionstyle_<version>_<arch>.deb
set(CPACK_DEBIAN_PACKAGE_MAINTAINER "${MOTIONSTYLE_PACKAGE_MAINTAINER}")
set(CPACK_DEBIAN_PACKAGE_SECTION "graphics")
set(CPACK_DEBIAN_PACKAGE_PRIORITY "optional")
set(CPACK_DEBIAN_COMPRESSION_TYPE "xz")  # the networks are most of the bytes; xz packs them best
find_program(MOTIONSTYLE_DPKG dpkg)
if(MOTIONSTYLE_DPKG)
  execute_process(COMMAND "${MOTIONSTYLE_DPKG}" --print-architecture
                  OUTPUT_VARIABLE CPACK_DEBIAN_PACKAGE_ARCHITECTURE OUTPUT_STRIP_TRAILING_WHITESPACE)
else()
  set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE "amd64")
endif()
set(CPACK_DEBIAN_PACKAGE_DESCRIPTION
"${PROJECT_DESCRIPTION}
MotionStyle gives a motion-capture clip the style of another: an old man's
walk, an angry or a proud one. It implements \"Fast Neural Style Transfer
for Motion Data\" (Holden et al. 2017): a small per-style network restyles
a clip in milliseconds, then inverse kinematics (Ceres) locks the feet,
restores bone lengths and puts the result back on the user's own skeleton
for BVH export.
.
The package holds the Qt desktop app (motionstyle), the command-line tool
(motionstyle-cli), default networks for a range of styles (CC BY-NC 4.0,
see /usr/share/doc/motionstyle/NOTICE.models) and demo clips.")

# Runtime libraries: dpkg-shlibdeps reads the binaries' NEEDED entries and the libraries' symbols
# files, so the Depends line follows what the build actually links (Qt 6, VTK 9.1, Ceres, ...).
# What the binaries load at run time without linking is added by hand (the xcb platform plugin is
# in libqt6gui6 itself):
#   libgl1-mesa-dri: an OpenGL 3.2 core driver for the VTK viewport (llvmpipe when no GPU driver);
#   shared-mime-info, desktop-file-utils, hicolor-icon-theme: their triggers register the BVH MIME
#   type, the desktop entry and the icon (recommended: a headless CLI-only install works without).
find_program(MOTIONSTYLE_DPKG_SHLIBDEPS dpkg-shlibdeps)
if(MOTIONSTYLE_DPKG_SHLIBDEPS)
  set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
else()
  message(WARNING "dpkg-shlibdeps not found (package dpkg-dev): the .deb's Depends line will lack the "
                  "shared libraries; install dpkg-dev before building a package")
endif()
if(MOTIONSTYLE_BUILD_GUI)
  set(CPACK_DEBIAN_PACKAGE_DEPENDS "libgl1-mesa-dri")
  set(CPACK_DEBIAN_PACKAGE_RECOMMENDS "shared-mime-info, desktop-file-utils, hicolor-icon-theme")
endif()

if(NOT MOTIONSTYLE_ARCH STREQUAL "portable")
  message(STATUS "MotionStyle: MOTIONSTYLE_ARCH=${MOTIONSTYLE_ARCH}; configure with "
                 "-DMOTIONSTYLE_ARCH=portable before building a package for other machines")
endif()

include(CPack)
