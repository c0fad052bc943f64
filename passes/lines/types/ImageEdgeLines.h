#pragma once
/** @file The kernels of the image-space line types contour, depth-edge and normal-edge (postfx/Contour.h,
 *  postfx/ImageEdges.h), each reading G-buffer fields of the pass named `gbuffer`. */

#include "passes/lines/LineKernel.h"
#include "postfx/Contour.h"
#include "postfx/ImageEdges.h"

#include <string>
#include <vector>

namespace inkgraph {

class ContourKernel : public LineKernel {
public:
    ContourKernel(std::string gbuffer, ContourSettings settings) : mGBuffer(std::move(gbuffer)), mSettings(settings) {}
    std::vector<std::string> inputs() const override { return {mGBuffer + ".nDotV", mGBuffer + ".depth"}; }
    /** n.v only where the depth is > 0: a pair is marked only when both its pixels are covered
     *  (postfx/NeighbourPairs.h classifyPair()). */
    ReadExtent extentOf(std::size_t input) const override {
        return input == 0 ? ReadExtent::CoveredPixels : ReadExtent::WholeImage;
    }
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override {
        return extractContours(inputs[0], inputs[1], mSettings);
    }

private:
    std::string mGBuffer;
    ContourSettings mSettings;
};

class DepthEdgeKernel : public LineKernel {
public:
    DepthEdgeKernel(std::string gbuffer, DepthEdgeSettings settings)
        : mGBuffer(std::move(gbuffer)), mSettings(settings) {}
    std::vector<std::string> inputs() const override { return {mGBuffer + ".depth"}; }
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override { return extractDepthEdges(inputs[0], mSettings); }

private:
    std::string mGBuffer;
    DepthEdgeSettings mSettings;
};

class NormalEdgeKernel : public LineKernel {
public:
    NormalEdgeKernel(std::string gbuffer, NormalEdgeSettings settings)
        : mGBuffer(std::move(gbuffer)), mSettings(settings) {}
    std::vector<std::string> inputs() const override { return {mGBuffer + ".normal", mGBuffer + ".depth"}; }
    /** The normal only where the depth is > 0, as the contour's n.v. */
    ReadExtent extentOf(std::size_t input) const override {
        return input == 0 ? ReadExtent::CoveredPixels : ReadExtent::WholeImage;
    }
    LineSkeleton find(const std::vector<cv::Mat>& inputs) override {
        return extractNormalEdges(inputs[0], inputs[1], mSettings);
    }

private:
    std::string mGBuffer;
    NormalEdgeSettings mSettings;
};

} // namespace inkgraph
