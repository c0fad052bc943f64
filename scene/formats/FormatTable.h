#pragma once
/** @file The input formats, one row each: what loadScene(), referencedFiles() and every message that lists the
 *  supported formats iterate. A reader file defines its row (`FormatReader fooFormat()`); formatReaders() in
 *  FormatTable.cpp lists them (docs/contributing.md, "An input format"). Internal to the scene layer. */

#include "scene/formats/FormatReaders.h"

#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace inkgraph::detail {

/** One input format. */
struct FormatReader {
    std::string name;                    ///< as help text and messages name it: "glTF", "OBJ", "PLY"
    std::vector<std::string> extensions; ///< lowercase, with the dot: ".ply"
    /** Reads the whole file's bytes (`path` names the file in messages and resolves what it names), charging `budget`
     *  before allocating. Throws SceneError. */
    RawScene (*read)(const std::string& path, std::string_view content, MeshBudget& budget,
                     const LoadOptions& options) = nullptr;
    /** The files a regular file `path` of this format names besides itself, without loading it; null when the format
     *  names none. Best effort, nothing thrown (referencedFiles()). */
    std::vector<std::string> (*referencedFiles)(const std::string& path) = nullptr;
    /** Whether LoadOptions::animation means anything for it; otherwise a given animation is a warning. */
    bool hasAnimations = false;
};

/** Every input format, in the order messages list them. */
std::span<const FormatReader> formatReaders();

/** The format whose extensions hold `path`'s (in any case), or null. */
const FormatReader* formatReaderFor(const std::string& path);

/** `path`'s extension in lowercase, with its dot (".obj"), or "" for none. */
std::string lowercaseExtension(const std::string& path);

/** Every extension of every format, in the table's order: ".gltf, .glb, .vrm, .obj, .stl, .ply". */
std::string supportedExtensions();

} // namespace inkgraph::detail
