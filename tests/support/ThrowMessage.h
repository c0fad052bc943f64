#pragma once
/** @file The message of the exception a call throws, for tests that check what an error says. No GL. */

#include <stdexcept>
#include <string>

namespace inkgraph::test {

/** The message of the std::invalid_argument `call` throws, or "" when it throws none (so a test comparing the
 *  message fails visibly, with the call that did not throw). */
template <class Call>
std::string invalidArgumentMessage(Call call) {
    try {
        call();
    } catch (const std::invalid_argument& error) {
        return error.what();
    }
    return "";
}

} // namespace inkgraph::test
