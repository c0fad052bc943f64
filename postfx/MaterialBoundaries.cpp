#include "postfx/MaterialBoundaries.h"

#include <stdexcept>

namespace inkgraph {

LineSkeleton extractIdBoundaries(const cv::Mat& ids, const std::string& fieldName) {
    if (ids.empty() || ids.type() != CV_32FC1)
        throw std::invalid_argument("extractIdBoundaries(): '" + fieldName + "' must be a non-empty CV_32FC1 image");
    LineSkeleton skeleton;
    skeleton.mask = cv::Mat::zeros(ids.size(), CV_8UC1);
    // Ids are whole numbers stored exactly in float, so comparing them for equality is exact.
    auto isBoundary = [](float a, float b) { return a > 0.0f && b > 0.0f && a != b; };
    for (int row = 0; row < ids.rows; ++row) {
        const float* here = ids.ptr<float>(row);
        const float* below = row + 1 < ids.rows ? ids.ptr<float>(row + 1) : nullptr;
        uchar* mask = skeleton.mask.ptr<uchar>(row);
        for (int col = 0; col < ids.cols; ++col) {
            if (col + 1 < ids.cols && isBoundary(here[col], here[col + 1])) {
                mask[col] = 255;
                skeleton.points.push_back({cv::Point2f(float(col) + 0.5f, float(row)), 1.0f});
            }
            if (below && isBoundary(here[col], below[col])) {
                mask[col] = 255;
                skeleton.points.push_back({cv::Point2f(float(col), float(row) + 0.5f), 1.0f});
            }
        }
    }
    return skeleton;
}

LineSkeleton extractMaterialBoundaries(const cv::Mat& materialId) {
    return extractIdBoundaries(materialId, "materialId");
}

} // namespace inkgraph
