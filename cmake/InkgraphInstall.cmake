# What `cmake --install build [--prefix P]` installs of the command line, all in the component "runtime" (the
# Debian package inkgraph; cmake/InkgraphPackaging.cmake). The layout is docs/install.md's; the installed program finds
# its shaders and its OpenImageIO module relative to itself (gl/BinaryLocation.h), so P can be moved afterwards.

install(TARGETS inkgraph RUNTIME DESTINATION ${CMAKE_INSTALL_BINDIR} COMPONENT runtime)
inkgraph_set_install_rpath(inkgraph ${CMAKE_INSTALL_BINDIR})

# Private libraries: the OpenImageIO module (loaded with dlopen, render/ImageIoModule.h) and the Draco decoder the
# program links (scene/CMakeLists.txt says why it is a shared library of its own).
install(TARGETS inkgraph_imageio LIBRARY DESTINATION ${INKGRAPH_INSTALL_PRIVATE_LIBDIR} COMPONENT runtime)
install(TARGETS inkgraph_draco LIBRARY DESTINATION ${INKGRAPH_INSTALL_PRIVATE_LIBDIR} COMPONENT runtime)

# Every shader the ShaderLibrary reads (not the copy-me template of passes/README.md, not the folder's README).
install(DIRECTORY ${PROJECT_SOURCE_DIR}/shaders/ DESTINATION ${INKGRAPH_INSTALL_DATADIR}/shaders COMPONENT runtime
    PATTERN _template EXCLUDE
    PATTERN *.md EXCLUDE)

# The bundled shade maps, with the README that describes them (their renders stay in the source tree).
file(GLOB INKGRAPH_SHADE_MAPS ${PROJECT_SOURCE_DIR}/shademaps/*.png)
install(FILES ${INKGRAPH_SHADE_MAPS} ${PROJECT_SOURCE_DIR}/shademaps/README.md
    DESTINATION ${INKGRAPH_INSTALL_DATADIR}/shademaps COMPONENT runtime)

# Generated from the flag table at build time (app/CMakeLists.txt).
install(FILES ${INKGRAPH_MAN_PAGE} DESTINATION ${CMAKE_INSTALL_MANDIR}/man1 COMPONENT runtime)
install(FILES ${INKGRAPH_BASH_COMPLETION} DESTINATION ${CMAKE_INSTALL_DATADIR}/bash-completion/completions
    COMPONENT runtime)

# libinkgraph.so (api/) links the Draco library too: it finds it in ${INKGRAPH_INSTALL_PRIVATE_LIBDIR}, below itself.
if(TARGET inkgraph_library)
    inkgraph_set_install_rpath(inkgraph_library ${CMAKE_INSTALL_LIBDIR})
endif()
