#pragma once
/** @file The settings of the line types besides width and colour: each one flag (`--<name>`) and one style-file
 *  name (`<name>`), declared once here or in the room of the only type that uses it, and listed by every line type it
 *  applies to (passes/lines/LineType.h). The command line, --help, style files, range checks and the "has no effect"
 *  refusals are all generated from these declarations (flags/FlagTable.cpp). */

#include <map>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace inkgraph {

struct LineParameter {
    std::string name;      ///< "depth-jump": the flag --depth-jump and the style setting depth-jump
    std::string valueName; ///< "R", for --help
    /** What it does, after the generated "<types>: "; '\n' breaks a help line. "{default}" stands for the default,
     *  which --help writes in from defaultNumber or defaultChoice, so that the value is stated once. */
    std::string help;
    std::vector<std::string> choices;       ///< empty: a number; else the words it takes ("3", "5")
    std::optional<double> defaultNumber;    ///< numbers: the value when not given; nullopt: "not given" means something
    std::string defaultChoice;              ///< choices: the value when not given
    double low = 0.0, high = 0.0;           ///< numbers: the accepted range ...
    bool lowOpen = false, highOpen = false; ///< ... with open ends where set
    std::string rangeText; ///< the message for a value outside: "degrees must lie above 0 and below 180"

    bool isChoice() const { return !choices.empty(); }
    /** Checks and converts `text` (the flag's value). Throws std::invalid_argument with "--<name>: <rangeText>, got
     *  '<text>'" (numbers) or "--<name>: expected A or B, got '<text>'" (choices). */
    std::variant<double, std::string> parse(const std::string& text) const;
};

/** The number a flag's value `text` writes: decimal or scientific, with an optional sign. Throws
 *  std::invalid_argument "<flag>: '<text>' ..." saying what is wrong: blanks around it, not a number, not finite, or
 *  beyond a double's range (1e-400, 1e400). The command line's flags and the line parameters read numbers so. */
double parseFlagNumber(const std::string& flag, const std::string& text);

/** The values given for line parameters, by name; a parameter not given has its declared default. */
class LineParameterValues {
public:
    void set(const LineParameter& parameter, std::variant<double, std::string> value);
    bool isGiven(const LineParameter& parameter) const { return mValues.count(parameter.name) != 0; }
    /** A number parameter's value. Throws std::logic_error for a choice, or a number with no default not given. */
    double number(const LineParameter& parameter) const;
    /** A number parameter's value when given or defaulted; nullopt when neither. */
    std::optional<double> numberIfSet(const LineParameter& parameter) const;
    /** A choice parameter's value. */
    const std::string& choice(const LineParameter& parameter) const;

private:
    std::map<std::string, std::variant<double, std::string>> mValues;
};

/** The parameters several line types share. */
namespace line_parameters {
extern const LineParameter kCreaseAngle;         ///< crease, normal-edge
extern const LineParameter kDepthJump;           ///< the G-buffer line types and suggestive-object
extern const LineParameter kSuggestiveThreshold; ///< suggestive, suggestive-object
extern const LineParameter kSuggestiveFade;      ///< suggestive, suggestive-object
extern const LineParameter kSuggestiveSeed;      ///< suggestive, suggestive-object: hysteresis
} // namespace line_parameters

} // namespace inkgraph
