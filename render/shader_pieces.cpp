#include "render/shader_pieces.h"

#include "gl/bindings.h"
#include "render/worker_deal.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <string>

namespace curette {

void CameraRayPiece::apply(gl::Program& p) const {
    double aspect = double(frame.size.x) / frame.size.y;
    glm::dmat4 viewProjection = frame.camera.projection(aspect) * frame.camera.view();
    p.set("inverseViewProjection", glm::mat4(glm::inverse(viewProjection)));
    p.set("eyeWorld", glm::vec3(frame.camera.position()));
    p.set("outputSize", frame.size);
}

int TileOrderPiece::defaultRowsPerBand() { return llvmpipeWorkerThreads(); }

namespace {
// The tiles of an image (or of the part of it that meets a region) in bands of rows.
struct TileBands {
    glm::uvec2 tiles;                 // of the whole image
    unsigned perBand;
    unsigned firstColumn, columns;    // the tile columns that meet the region
    unsigned firstBand, bands;        // the bands that meet it
};
TileBands tileBands(glm::ivec2 size, int rowsPerBand, glm::uvec3 group, const std::optional<PixelRect>& region) {
    glm::uvec2 tiles = (glm::uvec2(glm::max(size, glm::ivec2(1))) + glm::uvec2(group) - 1u) / glm::uvec2(group);
    unsigned perBand = static_cast<unsigned>(std::clamp(rowsPerBand, 1, static_cast<int>(tiles.y)));
    unsigned allBands = (tiles.y + perBand - 1) / perBand;
    if (!region) return {tiles, perBand, 0, tiles.x, 0, allBands};
    PixelRect r = region->clampedTo(size);
    if (r.empty()) return {tiles, perBand, 0, 0, 0, 0};
    glm::uvec2 first = glm::uvec2(r.min) / glm::uvec2(group), last = (glm::uvec2(r.max) - 1u) / glm::uvec2(group);
    return {tiles, perBand, first.x, last.x - first.x + 1, first.y / perBand, last.y / perBand - first.y / perBand + 1};
}
}  // namespace

int TileOrderPiece::bandCount(glm::uvec3 workGroupSize) const {
    return static_cast<int>(tileBands(size, rowsPerBand, workGroupSize, region).bands);
}

void TileOrderPiece::dispatch(gl::Program& p) const { dispatchBands(p, 0, bandCount(p.workGroupSize())); }

void TileOrderPiece::dispatchBands(gl::Program& p, int firstBand, int bands) const {
    TileBands t = tileBands(size, rowsPerBand, p.workGroupSize(), region);
    unsigned first = static_cast<unsigned>(std::clamp(firstBand, 0, static_cast<int>(t.bands)));
    unsigned count = std::min(static_cast<unsigned>(std::max(bands, 0)), t.bands - first);
    if (count == 0 || t.columns == 0) return;
    p.set("tileBands", count);
    p.set("firstBand", t.firstBand + first);
    p.set("rowsPerBand", t.perBand);
    p.set("tileGrid", t.tiles);
    p.set("firstTileColumn", t.firstColumn);
    p.use();
    glDispatchCompute(t.columns, count * t.perBand, 1);
}

void VolumePiece::apply(gl::Program& p) const {
    const VolumeGeometry& g = volume.geometry();
    p.set("worldToTexture", glm::mat4(g.worldToTexture()));
    p.set("texelSize", glm::vec3(1.0 / glm::dvec3(g.dims)));
    p.set("gradientToWorld", glm::mat3(g.gradientIndexToWorld() * volume.valueScale()));
    glBindTextureUnit(binding::volume, volume.texture());
}

void SampleShadingPiece::addDefines(gl::Defines& defines, ShadingMode mode) {
    // ismos colours samples as its base does (the ray caster passes the base itself; the slab pass, which
    // runs ismos frames with tubes, gets phong, the default base).
    if (mode == ShadingMode::Ismos) mode = ShadingMode::Phong;
    defines.emplace_back("SHADING", std::to_string(static_cast<int>(mode)));
}

void SampleShadingPiece::addCutFaceDefines(gl::Defines& defines, const CutFaceSettings& settings, int clipMeshes) {
    if (settings.enabled && clipMeshes > 0) defines.emplace_back("CUT_FACES", "1");
}

void SampleShadingPiece::apply(gl::Program& p) const {
    p.set("cutFaceNormalDepthMm", static_cast<float>(cutFace.normalDepthMm));
    if (!usesAmbientOcclusion(mode)) return;
    p.set("ambientScale", static_cast<float>(ambientScale));
    if (ambient) glBindTextureUnit(binding::ambient, ambient);
}

}  // namespace curette
