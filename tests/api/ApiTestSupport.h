#pragma once
/** @file What the API's tests share: the Error a call throws, as a value to compare. */

#include <inkgraph/inkgraph.h>

#include <functional>

namespace inkgraph::test {

/** The Error `call` throws; a test fails visibly when it throws none (kind Render, message "no Error thrown"). */
inline api::Error errorOf(const std::function<void()>& call) {
    try {
        call();
    } catch (const api::Error& error) {
        return error;
    }
    return api::Error(api::Error::Kind::Render, "no Error thrown");
}

} // namespace inkgraph::test
