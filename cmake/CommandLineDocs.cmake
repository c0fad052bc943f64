# Writes the man page and the bash completion by running the freshly built program (app/CommandLineDocs.h):
#   cmake -DPROGRAM=build/inkgraph -DMAN_PAGE=... -DBASH_COMPLETION=... -P CommandLineDocs.cmake
# Each file is written under a temporary name and renamed, so a failed run leaves no truncated file that make would
# take as up to date. A sanitized build's program runs here too: its leak check is for the tests, not the build.
set(ENV{ASAN_OPTIONS} "detect_leaks=0")
foreach(pair "--man;${MAN_PAGE}" "--bash-completion;${BASH_COMPLETION}")
    list(GET pair 0 topic)
    list(GET pair 1 output)
    get_filename_component(folder "${output}" DIRECTORY)
    file(MAKE_DIRECTORY "${folder}")
    execute_process(COMMAND "${PROGRAM}" help ${topic}
        OUTPUT_FILE "${output}.tmp" ERROR_VARIABLE errors RESULT_VARIABLE result)
    if(NOT result EQUAL 0)
        file(REMOVE "${output}.tmp")
        message(FATAL_ERROR "'${PROGRAM} help ${topic}' failed (${result}): ${errors}")
    endif()
    file(RENAME "${output}.tmp" "${output}")
endforeach()
