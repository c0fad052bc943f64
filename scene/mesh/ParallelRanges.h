#pragma once
/** @file Independent loops over large meshes split across the machine's cores: plain std::threads, started and
 *  joined inside the call, so no thread outlives it (the scene library links no thread pool, and the processes that
 *  only load models end without joining anything). Callers make their results independent of the split: each chunk
 *  writes only its own items or its own buffer, and buffers are combined in chunk order. */

#include <algorithm>
#include <cstddef>
#include <exception>
#include <system_error>
#include <thread>
#include <vector>

namespace inkgraph {

/** How many chunks parallelRanges() splits `count` items into: one per hardware thread, but none smaller than
 *  `minChunk` items (a thread costs tens of microseconds), and at least one. */
inline std::size_t parallelChunkCount(std::size_t count, std::size_t minChunk) {
    const std::size_t threads = std::max<std::size_t>(1, std::thread::hardware_concurrency());
    return std::clamp<std::size_t>(count / std::max<std::size_t>(1, minChunk), 1, threads);
}

/** Calls fn(chunk, begin, end) for the parallelChunkCount(count, minChunk) contiguous chunks of [0, count), chunk 0
 *  on the calling thread, the others on threads joined before returning. The first exception a chunk throws is
 *  rethrown here once every chunk has finished. */
template <class Fn>
void parallelRanges(std::size_t count, std::size_t minChunk, Fn&& fn) {
    const std::size_t chunks = parallelChunkCount(count, minChunk);
    const auto bounds = [&](std::size_t chunk) { return count * chunk / chunks; };
    if (chunks == 1) {
        fn(std::size_t(0), std::size_t(0), count);
        return;
    }
    std::vector<std::exception_ptr> errors(chunks);
    std::vector<std::thread> workers;
    workers.reserve(chunks - 1);
    const auto run = [&](std::size_t chunk) {
        try {
            fn(chunk, bounds(chunk), bounds(chunk + 1));
        } catch (...) {
            errors[chunk] = std::current_exception();
        }
    };
    for (std::size_t chunk = 1; chunk < chunks; ++chunk) {
        try {
            workers.emplace_back(run, chunk);
        } catch (const std::system_error&) {
            run(chunk); // no thread to be had: this one does the chunk
        }
    }
    run(0);
    for (std::thread& worker : workers) worker.join();
    for (const std::exception_ptr& error : errors)
        if (error) std::rethrow_exception(error);
}

} // namespace inkgraph
