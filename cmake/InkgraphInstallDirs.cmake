# The install layout (docs/install.md), before any target is defined, so each folder's CMakeLists.txt can use it.
# GNUInstallDirs' folders are relative to the prefix; gl/BinaryLocation.h finds the installed files relative to the
# binary, so an installed tree can be moved as a whole.
include(GNUInstallDirs)

# Shaders and shade maps: ${INKGRAPH_INSTALL_DATADIR}/{shaders,shademaps}.
set(INKGRAPH_INSTALL_DATADIR ${CMAKE_INSTALL_DATADIR}/inkgraph)
# Private shared libraries and modules: the OpenImageIO module, libinkgraph_draco.so.
set(INKGRAPH_INSTALL_PRIVATE_LIBDIR ${CMAKE_INSTALL_LIBDIR}/inkgraph)

# The man page and the bash completion, generated at build time (app/CMakeLists.txt).
set(INKGRAPH_MAN_PAGE ${PROJECT_BINARY_DIR}/share/man/man1/inkgraph.1)
set(INKGRAPH_BASH_COMPLETION ${PROJECT_BINARY_DIR}/share/bash-completion/completions/inkgraph)

# RPATH policy: installed files carry no build-tree RPATH (CMake's default: the build RPATH is replaced at install);
# a binary that needs our private libraries gets an $ORIGIN-relative RUNPATH to ${INKGRAPH_INSTALL_PRIVATE_LIBDIR}
# and nothing else, since every other library it links is Debian's, found on the system's paths.
#   inkgraph_set_install_rpath(TARGET DESTINATION): TARGET is installed in DESTINATION (relative to the prefix).
function(inkgraph_set_install_rpath target destination)
    file(RELATIVE_PATH private "/prefix/${destination}" "/prefix/${INKGRAPH_INSTALL_PRIVATE_LIBDIR}")
    set_target_properties(${target} PROPERTIES INSTALL_RPATH "$ORIGIN/${private}")
endfunction()
