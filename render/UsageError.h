#pragma once
/** @file The error of a request the renderer cannot satisfy as asked: a bad flag or value on the command line, a
 *  camera that cannot be resolved, a size over the memory limit. The command line prints it with a hint to --help and
 *  exits with 2; the library raises it as Error(Usage). */

#include <stdexcept>

namespace inkgraph {

class UsageError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

} // namespace inkgraph
