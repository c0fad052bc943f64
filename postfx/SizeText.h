#pragma once
// How the post stage's error messages write an image size.

#include <opencv2/core.hpp>

#include <string>

namespace inkgraph {

/** "WIDTHxHEIGHT", e.g. "1024x768". */
inline std::string sizeText(cv::Size size) { return std::to_string(size.width) + "x" + std::to_string(size.height); }

} // namespace inkgraph
