#pragma once
/** @file What the API's tests share: the Error a call throws, as a value to compare; files written for them. */

#include <inkgraph/inkgraph.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>

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

/** Writes `text` (any bytes) as the file `path`. */
inline void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream file(path, std::ios::binary);
    file << text;
}

} // namespace inkgraph::test
