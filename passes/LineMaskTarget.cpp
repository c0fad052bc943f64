#include "passes/LineMaskTarget.h"

#include <glm/gtc/type_ptr.hpp>
#include <opencv2/imgproc.hpp>

#include <algorithm>
#include <stdexcept>
#include <string>

namespace inkgraph {

namespace {

/** Binds the mask and its depth (already attached), sets the viewport and clears the mask, and the depth when
 *  `clearDepth`; false with the framebuffer unbound when `eye` is inside the model. */
bool startLineMask(GlPassContext& gl, GlFramebuffer& framebuffer, bool clearDepth, GpuScene& scene,
                   const glm::dvec3& eye) {
    framebuffer.attachColor(0, gl.outputTexture("lines"));
    framebuffer.finish({0});
    framebuffer.bind();
    glViewport(0, 0, gl.widthOf("lines"), gl.heightOf("lines"));
    if (clearDepth) {
        clearColorAndDepth(1);
    } else {
        const GLfloat none[4] = {0.0f, 0.0f, 0.0f, 0.0f};
        glClearBufferfv(GL_COLOR, 0, none);
    }
    if (scene.containsPoint(eye)) {
        glBindFramebuffer(GL_FRAMEBUFFER, 0);
        return false;
    }
    return true;
}

} // namespace

float bandWidthPixels(float widthPixels, int maskRows) {
    return widthPixels * std::max(1.0f, float(maskRows) / float(kBandReferenceRows));
}

int bandOpeningPixels(float widthPixels, int maskRows) {
    const int bySize = maskRows / kBandReferenceRows;
    const int byWidth = int(bandWidthPixels(widthPixels, maskRows) / 2.0f);
    return std::max(1, std::min(bySize, byWidth));
}

cv::Mat openedBand(const cv::Mat& band, float widthPixels) {
    const int side = bandOpeningPixels(widthPixels, band.rows);
    if (side <= 1) return band;
    // Every pixel of a side x side square inside the band: the squares' corners (erode, anchored at the top left),
    // then each corner's square (dilate, anchored at the bottom right). cv::morphologyEx anchors both steps at the
    // middle, which for an even side moves the result a pixel down and right.
    const cv::Mat square = cv::getStructuringElement(cv::MORPH_RECT, cv::Size(side, side));
    cv::Mat corners, opened;
    cv::erode(band, corners, square, cv::Point(0, 0), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    cv::dilate(corners, opened, square, cv::Point(side - 1, side - 1), 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    // Where the model hides most of a band, what shows of it can narrow to a pixel between wider stretches (a box's
    // side seen at a grazing angle); the band's pixels within `side` of what the opening kept stay, so such a
    // remnant still joins its stretches, while a sliver apart from the band goes.
    cv::Mat nearKept;
    cv::dilate(opened, nearKept, cv::getStructuringElement(cv::MORPH_RECT, cv::Size(2 * side + 1, 2 * side + 1)));
    return band & nearKept;
}

cv::Mat1f bandLocalWidths(const cv::Mat& band) {
    if (band.empty() || band.type() != CV_8UC1)
        throw std::invalid_argument("bandLocalWidths(): 'band' must be a non-empty CV_8UC1");
    // A frame of zeros around it: distanceTransform would otherwise take the picture's edge for more band.
    cv::Mat framed;
    cv::copyMakeBorder(band, framed, 1, 1, 1, 1, cv::BORDER_CONSTANT, cv::Scalar(0));
    cv::Mat1f distance;
    cv::distanceTransform(framed, distance, cv::DIST_L2, cv::DIST_MASK_PRECISE, CV_32F);
    cv::Mat1f widths = distance(cv::Rect(1, 1, band.cols, band.rows)) * 2.0f + 0.5f;
    widths.setTo(0.0f, band == 0);
    return widths;
}

bool beginLineMask(GlPassContext& gl, GlFramebuffer& framebuffer, PassDepthBuffer& depth, GpuScene& scene,
                   const glm::dvec3& eye) {
    framebuffer.attachDepth(depth.sized(gl.widthOf("lines"), gl.heightOf("lines")));
    return startLineMask(gl, framebuffer, true, scene, eye);
}

bool beginLineMask(GlPassContext& gl, GlFramebuffer& framebuffer, const GlTexture& modelDepth, GpuScene& scene,
                   const glm::dvec3& eye) {
    if (modelDepth.width() != gl.widthOf("lines") || modelDepth.height() != gl.heightOf("lines"))
        throw std::logic_error("beginLineMask(): model depth '" + modelDepth.label() + "' is " +
                               std::to_string(modelDepth.width()) + "x" + std::to_string(modelDepth.height()) +
                               ", the mask " + std::to_string(gl.widthOf("lines")) + "x" +
                               std::to_string(gl.heightOf("lines")));
    framebuffer.attachDepth(modelDepth);
    return startLineMask(gl, framebuffer, false, scene, eye);
}

void drawModelDepth(const GlProgram& program, GpuScene& scene, const glm::mat4& viewFromModel,
                    const glm::mat4& clipFromView) {
    glColorMask(GL_FALSE, GL_FALSE, GL_FALSE, GL_FALSE);
    program.use();
    glUniformMatrix4fv(program.uniform("viewFromModel"), 1, GL_FALSE, glm::value_ptr(viewFromModel));
    glUniformMatrix4fv(program.uniform("clipFromView"), 1, GL_FALSE, glm::value_ptr(clipFromView));
    const bool transparency = scene.hasTransparency();
    const std::vector<GpuScene::DrawMesh>& meshes = scene.meshes();
    for (std::size_t index = 0; index < meshes.size(); ++index) {
        if (transparency) scene.bindMaterial(program, index, MaterialUse::Coverage);
        meshes[index].vertexArray.bind();
        glDrawElements(GL_TRIANGLES, meshes[index].indexCount, GL_UNSIGNED_INT, nullptr);
    }
}

std::vector<std::string> materialAlphaDefines(const GpuScene& scene) {
    if (!scene.hasTransparency()) return {};
    return {"MATERIAL_ALPHA 1", "MATERIAL_SOLID_ONLY 1"};
}

} // namespace inkgraph
