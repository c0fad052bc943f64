#pragma once
/** @file `inkgraph check-dataset DIR`: whether a data set made with --dataset (app/Dataset.h) is finished and whole.
 *  Reads files only; no GL. */

#include <cstddef>
#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace inkgraph {

/** What checkDataset() found. */
struct DatasetReport {
    std::vector<std::string> errors;   ///< each makes the data set not whole
    std::vector<std::string> warnings; ///< worth a look, not a defect: a file the index does not list, a failed still
    std::size_t stills = 0;            ///< index lines with status "ok"
    std::size_t failed = 0;            ///< index lines with status "failed"
    std::size_t files = 0;             ///< files verified whole (size, checksum, format); not those in `errors`
};

/** Verifies the data set in `folder`: the index(es) and card(s) exist and every index line parses; with a sharded
 *  index, shards 0 to N-1 all present; every file an index lists exists, is non-empty, has the recorded size and
 *  checksum and is whole for its format (PNG: signature and IEND chunk last; EXR, TIFF, JPEG: signature (JPEG: and end
 *  marker); JSON: parses; SVG: its closing tag); no journal left (an unfinished run); no temporary file or staging
 *  folder of a killed run anywhere under `folder`; the card's counts equal the index's. Files the index does not list
 *  are warnings. */
DatasetReport checkDataset(const std::filesystem::path& folder);

/** `inkgraph check-dataset DIR` (arguments after the command's name): prints one line per problem (at most
 *  kShownProblems, then "and N more") and a summary on `out`. Returns 0 when the data set is whole, 1 when not, 2 for
 *  a bad command line (no DIR, or DIR not a folder). */
int runCheckDatasetCommand(const std::vector<std::string>& arguments, std::ostream& out, std::ostream& err);

/** The text of `inkgraph check-dataset --help`. */
std::string checkDatasetHelp();

inline constexpr std::size_t kShownProblems = 20;

} // namespace inkgraph
