#pragma once
/** @file What the command line says when it crashes. A crash is a bug (SIGSEGV, SIGBUS, SIGFPE, SIGILL, or SIGABRT,
 *  which glibc raises on a corrupted heap, "free(): corrupted unsorted chunks"): instead of a bare "Segmentation
 *  fault" the user gets a line naming the signal and the build, then the stack as return addresses that
 *  `addr2line -Cfe` resolves against the same build, to put in a bug report. The process then ends by the signal as
 *  it would have (the same exit status, the same core dump). A program that links the library keeps its own
 *  handlers: only the executable installs this one (app/main.cpp). */

namespace inkgraph {

/** Installs the report for the signals above (idempotent). `build` names what crashed ("inkgraph 0.2.0 (git
 *  6d23871)"); it is copied. The calling thread's handler runs on a stack of its own, so a stack overflow there is
 *  reported too; the report is cut after 10 s (SIGALRM) rather than hang, and a second crash while one is reported
 *  waits for that report. */
void reportCrashes(const char* build);

} // namespace inkgraph
