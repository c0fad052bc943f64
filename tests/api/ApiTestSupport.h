#pragma once
/** @file What the API's tests share: the Error a call throws, as a value to compare; an image's bytes; files written
 *  for them. */

#include <inkgraph/inkgraph.h>

#include <filesystem>
#include <fstream>
#include <functional>
#include <string>
#include <vector>

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

/** The image's pixels, rows packed (without the room a caller's rows may leave after them). */
inline std::vector<std::uint8_t> bytesOf(const api::Image& image) {
    std::vector<std::uint8_t> bytes;
    for (int row = 0; row < image.height(); ++row)
        bytes.insert(bytes.end(), image.data() + row * image.rowBytes(),
                     image.data() + row * image.rowBytes() + image.packedRowBytes());
    return bytes;
}

/** Writes `text` (any bytes) as the file `path`. */
inline void writeText(const std::filesystem::path& path, const std::string& text) {
    std::ofstream file(path, std::ios::binary);
    file << text;
}

} // namespace inkgraph::test
