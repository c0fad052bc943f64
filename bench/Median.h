#pragma once
// The median the benchmarks and the trade sweep report: robust to the shared host's slow outliers.
#include <algorithm>
#include <vector>

namespace inkgraph::bench {

/** The middle value (the mean of the two middle ones for an even count); 0 for none. */
inline double median(std::vector<double> values) {
    if (values.empty()) return 0.0;
    std::sort(values.begin(), values.end());
    const std::size_t middle = values.size() / 2;
    return values.size() % 2 ? values[middle] : 0.5 * (values[middle - 1] + values[middle]);
}

} // namespace inkgraph::bench
