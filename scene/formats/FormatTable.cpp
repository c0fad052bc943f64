#include "scene/formats/FormatTable.h"

#include <algorithm>
#include <cctype>
#include <filesystem>

namespace inkgraph {

namespace detail {

// Each reader file defines its row; a new format is a file of its own, declared here and placed in the list, whose
// order is the order messages and help text name the formats in (docs/contributing.md, "An input format").
FormatReader gltfFormat();
FormatReader glbFormat();
FormatReader vrmFormat();
FormatReader objFormat();
FormatReader stlFormat();
FormatReader plyFormat();

std::span<const FormatReader> formatReaders() {
    static const std::vector<FormatReader> readers{gltfFormat(), glbFormat(), vrmFormat(),
                                                   objFormat(),  stlFormat(), plyFormat()};
    return readers;
}

std::string lowercaseExtension(const std::string& path) {
    std::string extension = std::filesystem::path(path).extension().string();
    std::ranges::transform(extension, extension.begin(), [](unsigned char c) { return char(std::tolower(c)); });
    return extension;
}

const FormatReader* formatReaderFor(const std::string& path) {
    const std::string extension = lowercaseExtension(path);
    for (const FormatReader& reader : formatReaders()) {
        if (std::ranges::find(reader.extensions, extension) != reader.extensions.end()) return &reader;
    }
    return nullptr;
}

std::string supportedExtensions() {
    std::string list;
    for (const FormatReader& reader : formatReaders()) {
        for (const std::string& extension : reader.extensions) list += (list.empty() ? "" : ", ") + extension;
    }
    return list;
}

} // namespace detail

std::string modelFileExtensions() { return detail::supportedExtensions(); }

std::string modelFormatNames() {
    std::string list;
    for (const detail::FormatReader& reader : detail::formatReaders()) {
        list += (list.empty() ? "" : ", ") + reader.name;
    }
    return list;
}

} // namespace inkgraph
