#pragma once
/** @file glTF and GLB bytes made or edited by tests that run the executable on them (tests/app). */

#include "CliTestSupport.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <string>
#include <string_view>

namespace inkgraph::test {

/** `value` as 4 little-endian bytes, as GLB headers and binary STL counts store it. */
inline std::string u32(std::uint32_t value) {
    std::string bytes;
    for (int shift = 0; shift < 32; shift += 8) bytes.push_back(char((value >> shift) & 0xFF));
    return bytes;
}

/** RFC 4648 base64 of `bytes`, for glTF data: URIs. */
inline std::string base64(std::string_view bytes) {
    static const char* kAlphabet = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
    std::string text;
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        const std::size_t count = std::min<std::size_t>(3, bytes.size() - i);
        std::uint32_t chunk = 0;
        for (std::size_t k = 0; k < 3; ++k)
            chunk = chunk << 8 | (k < count ? std::uint32_t(std::uint8_t(bytes[i + k])) : 0u);
        for (std::size_t k = 0; k < 4; ++k) text += k <= count ? kAlphabet[(chunk >> (18 - 6 * k)) & 63] : '=';
    }
    return text;
}

/** A GLB of `json` (padded with spaces as the format asks) followed by `chunks`, the file's other chunks as they are
 *  stored (length, type, data). */
inline std::string glb(const std::string& json, const std::string& chunks = "") {
    std::string padded = json;
    while (padded.size() % 4) padded += ' ';
    const std::string body = u32(std::uint32_t(padded.size())) + "JSON" + padded + chunks;
    return "glTF" + u32(2) + u32(std::uint32_t(12 + body.size())) + body;
}

/** The GLB file `path` with its JSON changed by `edit`; its binary chunk is kept byte for byte. */
inline std::string editedGlb(const std::filesystem::path& path, const std::function<void(nlohmann::json&)>& edit) {
    const std::string bytes = readText(path);
    const std::uint32_t jsonLength =
        std::uint32_t(std::uint8_t(bytes[12])) | std::uint32_t(std::uint8_t(bytes[13])) << 8 |
        std::uint32_t(std::uint8_t(bytes[14])) << 16 | std::uint32_t(std::uint8_t(bytes[15])) << 24;
    nlohmann::json document = nlohmann::json::parse(bytes.substr(20, jsonLength));
    edit(document);
    return glb(document.dump(), bytes.substr(20 + jsonLength));
}

} // namespace inkgraph::test
