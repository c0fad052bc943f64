#pragma once
// The one clock and unit of every timing the stats report (passes, post stage, load, write): milliseconds of
// std::chrono::steady_clock, as a double.

#include <chrono>

namespace inkgraph {

/** Milliseconds from `start` to now on the steady clock. */
inline double millisecondsSince(std::chrono::steady_clock::time_point start) {
    return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

} // namespace inkgraph
