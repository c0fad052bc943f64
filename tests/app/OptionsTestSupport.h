#pragma once
/** @file What the option tests share: the message a command line is refused with. */

#include "flags/Options.h"

#include <string>
#include <vector>

namespace inkgraph::test {

/** The UsageError message parseRenderOptions() gives `arguments`, or "(no error)" when it accepts them. */
inline std::string usageMessage(std::vector<std::string> arguments) {
    try {
        parseRenderOptions(arguments);
    } catch (const UsageError& error) {
        return error.what();
    }
    return "(no error)";
}

} // namespace inkgraph::test
