#include "render/pass_bindings.h"

#include "gl/bindings.h"

#include <optional>

namespace curette {

namespace {
using R = Resource;
namespace b = binding;

// nullopt with `privateUnit` set: a pass's own buffer; nullopt without: a unit no frame pass should bind.
struct Lookup {
    std::optional<Resource> resource;
    bool privateUnit = false;
};

Lookup sampler(unsigned unit) {
    switch (unit) {
        case b::volume: return {R::Volume};
        case b::transferFunction: return {R::TransferFunction};
        case b::gradientOpacity: return {R::GradientOpacity};
        case b::occupancy: return {R::Occupancy};
        case b::ambient: return {R::Ambient};   // V_AO, or a preview's V_PAO standing in for it
        case b::opacity: return {R::ClippedOpacity};
        case b::precomputedAo: return {R::PrecomputedAo};
        case b::mask: return {R::CategoryMask};
        case b::clipDepth:
        case b::clipNormals:
        case b::clipDilated: return {R::ClipMaps};
        case b::occlusionPrevious: return {R::OcclusionBuffers};
        case b::tubeDepth:
        case b::tubeColor:
        case b::tubeNormal:
        case b::partialOcclusion: return {R::GBuffer};
        case b::labelIds:
        case b::labelField:
        case b::labelOpacity:
        case b::labelStyles: return {R::LabelVolume};
        case b::drilledFraction:
        case b::drillNearBricks: return {R::DrilledRemoval};
        case b::ismosLayerFront:
        case b::ismosLayerAlpha: return {R::IsmosLayers};
        case b::ismosLayerBack: return {R::IsmosLayerBacks};
        case b::ismosFit: return {R::IsmosFit};
        case b::seenBricks: return {R::SeenBricks};
        case b::tubeImpostorPoints: return {R::TubeGeometry};
        case b::gradientVolume: return {R::GradientVolume};
        default: return {};
    }
}

Lookup image(unsigned unit, Pass pass) {
    switch (unit) {
        case b::imageOutput: return {R::OutputImage};
        case b::imageOpacity: return {R::ClippedOpacity};
        case b::imageMask: return {R::CategoryMask};
        // The LAO kernel writes V_PAO in step I and V_AO in step V through the same unit.
        case b::imageAmbient: return {pass == Pass::LaoPrecompute ? R::PrecomputedAo : R::Ambient};
        case b::imageDilation: return {R::ClipMaps};
        case b::imageOcclusionNext: return {R::OcclusionBuffers};
        case b::imagePartialOcclusion: return {R::GBuffer};
        case b::imageIsmosLayerFront:
        case b::imageIsmosLayerAlpha: return {R::IsmosLayers};
        case b::imageIsmosLayerBack: return {R::IsmosLayerBacks};
        case b::imageIsmosFit: return {R::IsmosFit};
        case b::imageTubeNearestDepth:
        case b::imageTubeNearestSegment:
        case b::imageTubeColor:
        case b::imageTubeNormal:
        case b::imageTubeDepth: return {R::GBuffer};
        case b::imageGradientVolume: return {R::GradientVolume};
        default: return {};
    }
}

Lookup storageBlock(unsigned unit) {
    switch (unit) {
        case b::ssboLaoDirections: return {R::LaoDirections};
        case b::ssboVisitBricks: return {R::VisitedBricks};
        case b::ssboRecomputeList:
        case b::ssboDispatch: return {R::RecomputeList};
        case b::ssboIsmosLightSamples: return {R::IsmosLightSamples};
        case b::ssboSampleCounter:
        case b::ssboAntiAliasing:
        case b::ssboPoissonDisk:
        case b::ssboTileSpans: return {std::nullopt, true};
        case b::ssboTubeCandidates: return {R::GBuffer};
        default: return {};
    }
}

Lookup uniformBlock(unsigned unit) {
    if (unit == b::uboClipMeshes) return {R::ClipMaps};   // the clipping cameras the maps were drawn with
    return {};
}

void add(BoundResources& out, const Lookup& l, const char* kind, unsigned unit) {
    if (l.resource) out.resources.insert(*l.resource);
    else if (!l.privateUnit) out.unknown.push_back(std::string(kind) + " " + std::to_string(unit));
}
}  // namespace

void addResourcesBound(BoundResources& out, const gl::ProgramBindings& bindings) {
    for (unsigned u : bindings.samplers) add(out, sampler(u), "sampler unit", u);
    for (unsigned u : bindings.images) add(out, image(u, out.pass), "image unit", u);
    for (unsigned u : bindings.storageBlocks) add(out, storageBlock(u), "storage block", u);
    for (unsigned u : bindings.uniformBlocks) add(out, uniformBlock(u), "uniform block", u);
}

}  // namespace curette
