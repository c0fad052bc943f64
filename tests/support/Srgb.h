#pragma once
/** @file The sRGB transfer curve in double, for tests that predict the 8-bit codes the shaders write (encode, then
 *  round to nearest) and read linear values back from them. */

#include <algorithm>
#include <cmath>

namespace inkgraph::test {

inline double encodeSrgb(double linear) {
    const double x = std::clamp(linear, 0.0, 1.0);
    return x <= 0.0031308 ? 12.92 * x : 1.055 * std::pow(x, 1.0 / 2.4) - 0.055;
}

inline double decodeSrgb(double encoded) {
    return encoded <= 0.04045 ? encoded / 12.92 : std::pow((encoded + 0.055) / 1.055, 2.4);
}

/** The 8-bit code a shader writes for a linear value. */
inline int srgbCode(double linear) { return int(std::lround(255.0 * encodeSrgb(linear))); }

/** The linear value of an 8-bit code. */
inline double linearOf(int code) { return decodeSrgb(code / 255.0); }

} // namespace inkgraph::test
