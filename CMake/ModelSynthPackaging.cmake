# SPDX-License-Identifier: BSD-3-Clause
# Installation (`cmake --install build --prefix P`) and the Debian package (`cpack -G DEB` in the
# build folder). The build tree keeps its layout (lib/python3.11/site-packages/modelsynth,
# lib/paraview-5.11/plugins/ModelSynthPlugin); installed, relative to the prefix P:
#
#   bin/msynth                                      RPATH $ORIGIN/../lib
#   lib/libModelSynth*.so.0                         the engine and the VTK modules
#   lib/python3.11/dist-packages/modelsynth/        on /usr/bin/python3's and pvpython's sys.path
#                                                   for P = /usr and /usr/local; RPATH
#                                                   $ORIGIN/../../.. = lib
#   lib/<multiarch>/paraview-5.11/plugins/ModelSynthPlugin/ModelSynthPlugin.so
#                                                   ParaView's own plugin folder (found by name
#                                                   from /usr/bin for P = /usr); RPATH
#                                                   $ORIGIN/../../../.. = lib
#   share/modelsynth/{Data,Documentation,README.md} examples and guides
#
# Included by the top-level CMakeLists.txt after the modules, the wrapping and the plugin exist.

# The Python package: the wrapping installs into MSYNTH_PYTHON_INSTALL_DIR (see the
# vtk_module_wrap_python call); __init__.py goes beside it.
install(FILES "${MSYNTH_PYTHON_PATH}/${MSYNTH_PYTHON_PACKAGE}/__init__.py"
  DESTINATION "${MSYNTH_PYTHON_INSTALL_DIR}/${MSYNTH_PYTHON_PACKAGE}")

# The plugin installs under the multiarch lib dir, two levels deeper than our libraries.
foreach(_plugin IN LISTS msynth_plugins)
  if(TARGET ${_plugin})
    set_property(TARGET ${_plugin} APPEND PROPERTY INSTALL_RPATH "$ORIGIN/../../../..")
  endif()
endforeach()

# Examples and guides (the malformed files of the tests stay out).
install(DIRECTORY "${PROJECT_SOURCE_DIR}/Data/" DESTINATION share/modelsynth/Data
  PATTERN Malformed EXCLUDE)
install(DIRECTORY "${PROJECT_SOURCE_DIR}/Documentation/"
  DESTINATION share/modelsynth/Documentation)
install(FILES "${PROJECT_SOURCE_DIR}/README.md" DESTINATION share/modelsynth)

# ---------------------------------------------------------------------------------------------
# The Debian package: cpack -G DEB (prefix /usr).
# ---------------------------------------------------------------------------------------------
set(CPACK_PACKAGE_NAME modelsynth)
set(CPACK_PACKAGE_VENDOR "ModelSynth")
set(CPACK_PACKAGE_CONTACT "ModelSynth developers <modelsynth@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY
  "example-based model synthesis (msynth, Python package, ParaView plugin)")
set(CPACK_PACKAGE_DESCRIPTION "Model synthesis after Merrell and tile-pattern synthesis \
(BLOCKSS): the msynth command line, the modelsynth Python package for /usr/bin/python3 and \
pvpython, and the ParaView 5.11 plugin, loaded at start in login sessions \
(/etc/profile.d/modelsynth.sh).")
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGING_INSTALL_PREFIX /usr)
set(CPACK_GENERATOR DEB)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_ARCHITECTURE amd64)
# Libraries: dpkg-shlibdeps reads every ELF file's needs (ParaView's VTK, OpenVDB, TBB, CGAL's
# GMP, libpng, tinygltf, ...); our own libraries are found in the build's lib folder.
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS_PRIVATE_DIRS "${CMAKE_BINARY_DIR}/lib")
# What no ELF file names: ParaView's Python modules (vtkmodules, paraview.simple), pvpython and
# pvbatch, the interpreter the wrapping was built for, numpy (vtkmodules.numpy_interface).
set(CPACK_DEBIAN_PACKAGE_DEPENDS
  "python3-paraview (>= 5.11), python3-paraview (<< 5.12), python3 (>= 3.11), python3 (<< 3.12), python3-numpy")
# /etc/profile.d/modelsynth.sh: the plugin's folder on PV_PLUGIN_PATH (ParaView auto-loading).
set(MSYNTH_DEB_PLUGIN_DIR
  "/usr/${MSYNTH_PLUGIN_INSTALL_LIBDIR}/paraview-${ParaView_VERSION_MAJOR}.${ParaView_VERSION_MINOR}/plugins/ModelSynthPlugin")
configure_file("${CMAKE_CURRENT_LIST_DIR}/ModelSynthDebProfile.cmake.in"
  "${CMAKE_BINARY_DIR}/ModelSynthDebProfile.cmake" @ONLY)
set(CPACK_PRE_BUILD_SCRIPTS "${CMAKE_BINARY_DIR}/ModelSynthDebProfile.cmake")
file(WRITE "${CMAKE_BINARY_DIR}/debian/conffiles" "/etc/profile.d/modelsynth.sh\n")
set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${CMAKE_BINARY_DIR}/debian/conffiles")
# The package holds what runs: not the client-server wrappers' static libraries ("development").
set(CPACK_INSTALL_CMAKE_PROJECTS
  "${CMAKE_BINARY_DIR};ModelSynth;Unspecified;/"
  "${CMAKE_BINARY_DIR};ModelSynth;runtime;/"
  "${CMAKE_BINARY_DIR};ModelSynth;python;/")
include(CPack)
