# `cpack -G DEB` in the build folder (docs/install.md): one Debian package per install component,
#   inkgraph_<version>_amd64.deb          runtime: the program, its data, man page, completion, private libraries
#   inkgraph-dev_<version>_amd64.deb      dev: headers and CMake package files (when the build installs them)
#   python3-inkgraph_<version>_amd64.deb  python: the Python package (when the build installs it)
# Depends come from dpkg-shlibdeps (Debian's package names for every library the binaries link), plus what it cannot
# see: libepoxy opens libEGL.so.1 and libGL.so.1 with dlopen, and EGL needs a driver: Mesa's EGL and its llvmpipe
# (swrast_dri.so) render without a GPU. Included last in the top-level CMakeLists.txt: the components are those of
# every install() rule defined before it.
set(CPACK_PACKAGE_NAME inkgraph)
set(CPACK_PACKAGE_VENDOR inkgraph)
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "headless anime- and comic-style renderer")
set(CPACK_PACKAGE_DESCRIPTION "inkgraph renders 3-D models (glTF, GLB, VRM, OBJ, STL, PLY) as anime- and comic-style \
stills with shading and line drawings, through OpenGL 4.5 core on EGL with no window or display (a GPU's driver, or \
Mesa's llvmpipe).")
set(CPACK_PACKAGE_CONTACT "inkgraph maintainers <inkgraph@localhost>")
set(CPACK_GENERATOR DEB)
set(CPACK_STRIP_FILES ON)

# Every component is a package of its own, also when there is only one (CPack would otherwise make one monolithic
# package from the settings below that are not per component). No file may lack a component.
get_cmake_property(INKGRAPH_COMPONENTS COMPONENTS)
if("Unspecified" IN_LIST INKGRAPH_COMPONENTS)
    message(FATAL_ERROR "An install() rule has no COMPONENT: give it runtime, dev or python "
                        "(cmake/InkgraphPackaging.cmake makes one Debian package of each)")
endif()
set(CPACK_COMPONENTS_ALL ${INKGRAPH_COMPONENTS})
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_DEBIAN_ENABLE_COMPONENT_DEPENDS ON)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION graphics)
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)

set(CPACK_DEBIAN_RUNTIME_PACKAGE_NAME inkgraph)
set(CPACK_DEBIAN_RUNTIME_PACKAGE_DEPENDS "libegl1, libgl1, libegl-mesa0, libgl1-mesa-dri")

set(CPACK_DEBIAN_DEV_PACKAGE_NAME inkgraph-dev)
set(CPACK_DEBIAN_DEV_PACKAGE_SECTION libdevel)
set(CPACK_DEBIAN_DEV_PACKAGE_DEPENDS "")
set(CPACK_COMPONENT_DEV_DEPENDS runtime)

set(CPACK_DEBIAN_PYTHON_PACKAGE_NAME python3-inkgraph)
set(CPACK_DEBIAN_PYTHON_PACKAGE_SECTION python)
# The Python the extension is built for, and NumPy (python/CMakeLists.txt: INKGRAPH_PYTHON_DEB_DEPENDS); inkgraph
# itself through the component's dependency on runtime. dpkg-shlibdeps is not asked: it cannot see libinkgraph.so,
# which is in the runtime package, and the module links nothing else that package does not need too.
set(CPACK_DEBIAN_PYTHON_PACKAGE_DEPENDS "${INKGRAPH_PYTHON_DEB_DEPENDS}")
set(CPACK_DEBIAN_PYTHON_PACKAGE_SHLIBDEPS OFF)
set(CPACK_COMPONENT_PYTHON_DEPENDS runtime)

include(CPack)
