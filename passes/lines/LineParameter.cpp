#include "passes/lines/LineParameter.h"

#include <cctype>
#include <charconv>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace inkgraph {

double parseFlagNumber(const std::string& flag, const std::string& text) {
    if (!text.empty() && (std::isspace(static_cast<unsigned char>(text.front())) ||
                          std::isspace(static_cast<unsigned char>(text.back()))))
        throw std::invalid_argument(flag + ": '" + text + "' has blanks around the number");
    // from_chars takes no '+', which a number may carry (+2, 1e+3 it reads).
    const bool plus = text.size() > 1 && text[0] == '+' && text[1] != '-' && text[1] != '+';
    const char* begin = text.data() + (plus ? 1 : 0);
    const char* end = text.data() + text.size();
    double value = 0.0;
    const auto [stop, error] = std::from_chars(begin, end, value);
    if (error == std::errc::result_out_of_range && stop == end)
        throw std::invalid_argument(flag + ": '" + text + "' lies beyond a double's range (about 1e-308 to 1e308)");
    if (error != std::errc() || stop != end) throw std::invalid_argument(flag + ": '" + text + "' is not a number");
    if (!std::isfinite(value)) throw std::invalid_argument(flag + ": '" + text + "' is not a finite number");
    return value;
}

std::variant<double, std::string> LineParameter::parse(const std::string& text) const {
    const std::string flag = "--" + name;
    if (isChoice()) {
        for (const std::string& choice : choices)
            if (choice == text) return choice;
        std::string names;
        for (std::size_t i = 0; i < choices.size(); ++i)
            names += (i == 0 ? "" : i + 1 == choices.size() ? " or " : ", ") + choices[i];
        throw std::invalid_argument(flag + ": expected " + names + ", got '" + text + "'");
    }
    const double value = parseFlagNumber(flag, text);
    const bool aboveLow = lowOpen ? value > low : value >= low;
    const bool belowHigh = highOpen ? value < high : value <= high;
    if (!(aboveLow && belowHigh)) throw std::invalid_argument(flag + ": " + rangeText + ", got '" + text + "'");
    // The line kernels take their settings in float: a value in range that float rounds to 0 (or holds only as a
    // denormal) would reach them as 0, which a range open at 0 refuses, and fail inside the render.
    if (value != 0.0 && std::abs(value) < double(std::numeric_limits<float>::min()))
        throw std::invalid_argument(flag + ": '" + text +
                                    "' is under 1.2e-38, the smallest number the line kernels' float holds");
    return value;
}

void LineParameterValues::set(const LineParameter& parameter, std::variant<double, std::string> value) {
    mValues[parameter.name] = std::move(value);
}

std::optional<double> LineParameterValues::numberIfSet(const LineParameter& parameter) const {
    if (parameter.isChoice())
        throw std::logic_error("LineParameterValues::number(): '" + parameter.name + "' is a choice");
    if (auto given = mValues.find(parameter.name); given != mValues.end()) return std::get<double>(given->second);
    return parameter.defaultNumber;
}

double LineParameterValues::number(const LineParameter& parameter) const {
    const std::optional<double> value = numberIfSet(parameter);
    if (!value)
        throw std::logic_error("LineParameterValues::number(): '" + parameter.name + "' has no default and is not set");
    return *value;
}

const std::string& LineParameterValues::choice(const LineParameter& parameter) const {
    if (!parameter.isChoice())
        throw std::logic_error("LineParameterValues::choice(): '" + parameter.name + "' is a number");
    if (auto given = mValues.find(parameter.name); given != mValues.end()) return std::get<std::string>(given->second);
    return parameter.defaultChoice;
}

namespace line_parameters {

const LineParameter kCreaseAngle{"crease-angle",
                                 "DEG",
                                 "the angle above which an edge is a crease (default {default}, about Blender\n"
                                 "Freestyle's 134.43 degree crease angle: facets of smooth-shaded models stay uninked)",
                                 {},
                                 45.0,
                                 "",
                                 0.0,
                                 180.0,
                                 true,
                                 true,
                                 "degrees must lie above 0 and below 180"};

const LineParameter kDepthJump{
    "depth-jump",
    "R",
    "in the G-buffer, neighbouring pixels whose depths differ by more than R x the nearer depth are different "
    "surfaces; on the mesh (suggestive-object, intersection), a line point more than R x the depth behind the visible "
    "surface is hidden (default {default})",
    {},
    0.05,
    "",
    0.0,
    100.0,
    true,
    false,
    "expected a relative depth step above 0 up to 100"};

const LineParameter kSuggestiveThreshold{"suggestive-threshold",
                                         "T",
                                         "keep lines whose strength q (rtsc's fs^2 tan(theta) D_w kappa_r,\n"
                                         "fs = 5% of the bounding radius) exceeds T (default {default})",
                                         {},
                                         0.01,
                                         "",
                                         0.0,
                                         1e6,
                                         false,
                                         false,
                                         "expected a number from 0 to 1e6"};

const LineParameter kSuggestiveFade{"suggestive-fade",
                                    "F",
                                    "draw a kept line with alpha (q - T) / (q - T + F) (default {default}; 0 draws\n"
                                    "every kept line in full)",
                                    {},
                                    0.03,
                                    "",
                                    0.0,
                                    1e6,
                                    false,
                                    false,
                                    "expected a number from 0 to 1e6"};

const LineParameter kSuggestiveSeed{"suggestive-seed",
                                    "Q",
                                    "hysteresis: draw a line only in a stroke that somewhere reaches strength\n"
                                    "Q (a strong seed grows along its weaker continuations down to T, as\n"
                                    "Canny's edges do; default {default}; at most T turns it off)",
                                    {},
                                    0.04,
                                    "",
                                    0.0,
                                    1e6,
                                    false,
                                    false,
                                    "expected a number from 0 to 1e6"};

} // namespace line_parameters
} // namespace inkgraph
