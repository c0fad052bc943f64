#!/usr/bin/env bash
# Sanitized builds only (ctest `exit_threads_are_quiet`): runs every test of the given GoogleTest binaries as its own
# process, as ctest does, with AddressSanitizer's and LeakSanitizer's thread logs, and fails when a process's leak check
# met a thread in flight: one whose teardown AddressSanitizer had begun ("Tn exited" before the check) and that the
# check's tracer still processed, or one it found but could not place ("not found in registry"). Such a thread is
# the race that made the tracer crash at exit (docs/robustness.md, "How a process ends"); the check sees it whether
# or not the tracer happens to crash on it.
# Usage: check-exit-threads.sh TEST_BINARY...   (ASAN_OPTIONS and LSAN_OPTIONS of scripts/test-sanitized.sh apply)
set -uo pipefail
if [ $# -eq 0 ]; then echo "check-exit-threads.sh: no test binary given" >&2; exit 2; fi
logs=$(mktemp -d)
trap 'rm -rf "$logs"' EXIT
export ASAN_OPTIONS="${ASAN_OPTIONS:-detect_leaks=1}:verbosity=1"
export LSAN_OPTIONS="${LSAN_OPTIONS:-}:log_threads=1"
export LP_NUM_THREADS=1
# The test-output folders of these processes are their own, so ctest runs this beside the same tests (not RUN_SERIAL).
export INKGRAPH_TEST_OUTPUT_ROOT="$logs/output"
processes=0
in_flight=0
for binary in "$@"; do
    # gtest's list: suite lines end with '.', test lines are indented; parameter comments follow a '#'.
    tests=$("$binary" --gtest_list_tests 2>/dev/null | awk '/^[^ ]/ { suite = $1 } /^  / { print suite $1 }')
    if [ -z "$tests" ]; then echo "check-exit-threads.sh: '$binary' lists no test" >&2; exit 2; fi
    for test in $tests; do
        log="$logs/$processes.log"
        if ! "$binary" --gtest_filter="$test" > "$log" 2>&1; then
            echo "FAILED: $test (its own run failed; log follows)"; tail -30 "$log"; exit 1
        fi
        processes=$((processes + 1))
        # The tracer prints under its own pid; the first thread it processes is the main thread, whose id is the pid.
        verdict=$(awk '
            match($0, /^==[0-9]+==T[0-9]+: stack \[0x[0-9a-f]+,/) {
                split(substr($0, RSTART, RLENGTH), part, /==|: stack \[|,/); holder[part[4]] = part[3] }
            !checking && match($0, /==T[0-9]+ exited/) { exited[substr($0, RSTART + 2, RLENGTH - 9)] = 1 }
            /Processing thread/ { checking = 1 }
            checking && match($0, /Stack at 0x[0-9a-f]+-/) {
                s = substr($0, RSTART + 9, RLENGTH - 10); if ((s in holder) && (holder[s] in exited)) busy = busy " " holder[s] }
            checking && /not found in registry/ { missing++ }
            END {
                if (!checking) print "no-check"
                else if (busy != "" || missing > 0) print "in-flight:" busy (missing ? " and " missing " not in the registry" : "")
                else print "quiet" }' "$log")
        case "$verdict" in
            quiet) ;;
            no-check) echo "FAILED: $test: no leak check ran (is this a sanitized build?)"; exit 1 ;;
            *) echo "in flight at the leak check of $test:${verdict#in-flight:}"; in_flight=$((in_flight + 1)) ;;
        esac
    done
done
echo "$processes processes, $in_flight with a thread in flight at the leak check"
[ "$in_flight" -eq 0 ]
