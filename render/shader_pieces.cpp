#include "render/shader_pieces.h"

#include "gl/bindings.h"
#include "render/model/worker_deal.h"

#include <glm/gtc/matrix_inverse.hpp>

#include <algorithm>
#include <string>

namespace curette {

void CameraRayPiece::apply(gl::Program& p) const {
    p.set("inverseViewProjection", glm::mat4(glm::inverse(frame.camera.viewProjection(frame.size))));
    p.set("eyeWorld", glm::vec3(frame.camera.position()));
    p.set("outputSize", frame.size);
}

int TileOrderPiece::defaultRowsPerBand() { return llvmpipeWorkerThreads(); }

namespace {
// Tiles across and down an image of `size` pixels.
glm::uvec2 tilesCovering(glm::ivec2 size, glm::uvec2 tileSize) { return (glm::uvec2(glm::max(size, glm::ivec2(1))) + tileSize - 1u) / tileSize; }
}  // namespace

TileSpans tileSpansOf(const PixelRegion& region, glm::uvec2 tileSize) {
    TileSpans t;
    t.tileSize = tileSize;
    glm::uvec2 tiles = tilesCovering(region.size, tileSize);
    t.rows.assign(tiles.y, glm::uvec2(0));
    t.firstRow = tiles.y;
    for (std::size_t y = 0; y < region.rows.size(); ++y) {
        glm::ivec2 run = region.rows[y];
        if (run.x >= run.y) continue;
        unsigned row = static_cast<unsigned>(y) / tileSize.y;
        glm::uvec2 columns(static_cast<unsigned>(run.x) / tileSize.x, (static_cast<unsigned>(run.y) - 1u) / tileSize.x + 1u);
        glm::uvec2& span = t.rows[row];
        span = span.x >= span.y ? columns : glm::uvec2(std::min(span.x, columns.x), std::max(span.y, columns.y));
        t.firstRow = std::min(t.firstRow, row);
        t.endRow = std::max(t.endRow, row + 1);
        t.widest = std::max(t.widest, span.y - span.x);
    }
    if (t.endRow == 0) t.firstRow = 0;
    return t;
}

namespace {
// The tiles of an image (or the rows of tiles that spans cover) in bands of rows.
struct TileBands {
    glm::uvec2 tiles;                 // of the whole image
    unsigned perBand;
    unsigned columns;                 // the dispatch's width
    unsigned firstBand, bands;        // the bands it covers
};
TileBands tileBands(glm::ivec2 size, int rowsPerBand, glm::uvec3 group, const TileSpans* spans) {
    glm::uvec2 tiles = tilesCovering(size, glm::uvec2(group));
    unsigned perBand = static_cast<unsigned>(std::clamp(rowsPerBand, 1, static_cast<int>(tiles.y)));
    if (!spans) return {tiles, perBand, tiles.x, 0, (tiles.y + perBand - 1) / perBand};
    if (spans->endRow == 0) return {tiles, perBand, 0, 0, 0};
    unsigned first = spans->firstRow / perBand;
    return {tiles, perBand, spans->widest, first, (spans->endRow + perBand - 1) / perBand - first};
}
}  // namespace

namespace {
// Tiles across a part of a band.
unsigned partColumns(glm::uvec3 group) { return std::max(1u, TileOrderPiece::kPartPixels / std::max(group.x, 1u)); }
unsigned partsPerBand(const TileBands& t, glm::uvec3 group) { return (t.columns + partColumns(group) - 1) / partColumns(group); }
}  // namespace

int TileOrderPiece::partCount(glm::uvec3 workGroupSize) const {
    TileBands t = tileBands(size, rowsPerBand, workGroupSize, spans);
    return static_cast<int>(t.bands * partsPerBand(t, workGroupSize));
}

void TileOrderPiece::dispatch(gl::Program& p) const { dispatchParts(p, 0, partCount(p.workGroupSize())); }

void TileOrderPiece::dispatchParts(gl::Program& p, int firstPart, int parts) const {
    const glm::uvec3 group = p.workGroupSize();
    TileBands t = tileBands(size, rowsPerBand, group, spans);
    const unsigned perBand = partsPerBand(t, group), across = partColumns(group), total = t.bands * perBand;
    unsigned first = static_cast<unsigned>(std::clamp(firstPart, 0, static_cast<int>(total)));
    unsigned count = std::min(static_cast<unsigned>(std::max(parts, 0)), total - first);
    if (count == 0 || t.columns == 0) return;
    p.set("rowsPerBand", t.perBand);
    p.set("tileGrid", t.tiles);
    p.set("tileSpansOn", spans ? 1 : 0);
    if (spans) glBindBufferBase(GL_SHADER_STORAGE_BUFFER, binding::ssboTileSpans, spanBuffer);
    auto dispatchRun = [&](unsigned band, unsigned bands, unsigned column, unsigned columns) {
        p.set("tileBands", bands);
        p.set("firstBand", t.firstBand + band);
        p.set("firstColumn", column);
        p.use();
        glDispatchCompute(columns, bands * t.perBand, 1);
    };
    while (count > 0) {
        unsigned band = first / perBand, within = first % perBand;
        if (within == 0 && count >= perBand) {   // whole bands
            unsigned bands = count / perBand;
            dispatchRun(band, bands, 0, t.columns);
            first += bands * perBand, count -= bands * perBand;
        } else {                                 // a run of parts within one band
            unsigned n = std::min(count, perBand - within);
            unsigned column = within * across;
            dispatchRun(band, 1, column, std::min(n * across, t.columns - column));
            first += n, count -= n;
        }
    }
}

void VolumePiece::apply(gl::Program& p) const {
    const VolumeGeometry& g = volume.geometry();
    p.set("worldToTexture", glm::mat4(g.worldToTexture()));
    p.set("texelSize", glm::vec3(1.0 / glm::dvec3(g.dims)));
    p.set("gradientToWorld", glm::mat3(g.gradientIndexToWorld() * volume.valueScale()));
    glBindTextureUnit(binding::volume, volume.texture());
}

void VolumeLayoutPiece::addDefines(gl::Defines& defines) const {
    if (!layout.folded()) return;
    defines.emplace_back("VOLUME_FOLD", "1");
    defines.emplace_back("VOLUME_FOLD_AXIS", std::to_string(layout.foldAxis));
    defines.emplace_back("VOLUME_ACROSS_AXIS", std::to_string(layout.acrossAxis));
}

void VolumeLayoutPiece::apply(gl::Program& p) const {
    p.set("volumeFold", glm::ivec3(layout.stride, layout.pieces, layout.acrossPitch()));
    p.set("volumeFoldDims", glm::vec3(layout.dims));
    p.set("volumeFoldTexels", glm::vec3(layout.texels));
}

void NoDataPiece::addDefines(gl::Defines& defines) const {
    if (volume.hasNoData()) defines.emplace_back("NO_DATA", "1");
}

void NoDataPiece::apply(gl::Program& p) const {
    p.set("noDataSide", volume.noData().side);
    p.set("noDataBound", volume.noData().bound);
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
    p.set("cutFaceNormalOpacity", static_cast<float>(cutFace.normalOpacity));
    if (!usesAmbientOcclusion(mode)) return;
    p.set("ambientScale", static_cast<float>(ambientScale));
    if (ambient) glBindTextureUnit(binding::ambient, ambient);
}

void TubeSurfacePiece::addDefines(gl::Defines& defines) { defines.emplace_back("TUBES", "1"); }

void TubeSurfacePiece::apply(gl::Program& p) const {
    glBindTextureUnit(binding::tubeDepth, depth);
    glBindTextureUnit(binding::tubeColor, color);
    glBindTextureUnit(binding::tubeNormal, normal);
    const TransferFunction::Material& m = shading.material;
    p.set("tubeMaterial", glm::vec4(glm::dvec4(m.ambient, m.diffuse, m.specular, m.specularPower)));
    p.set("tubeLineDiffuseExponent", static_cast<float>(shading.lineDiffuseExponent));
    p.set("tubeViewForward", glm::vec3(frame.camera.forward()));
}

}  // namespace curette
