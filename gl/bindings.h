#pragma once
// Texture/image units and the other values shared with the shaders (shaders/bindings.glsl is the GLSL side;
// the ShaderConstants test parses both files and fails unless every name has the same value on both sides).

namespace curette::binding {

inline constexpr unsigned volume = 0;
inline constexpr unsigned transferFunction = 1;
inline constexpr unsigned gradientOpacity = 2;
inline constexpr unsigned occupancy = 3;
inline constexpr unsigned ambient = 4;
inline constexpr unsigned opacity = 5;
inline constexpr unsigned precomputedAo = 6;
inline constexpr unsigned mask = 7;
inline constexpr unsigned clipDepth = 8;
inline constexpr unsigned clipDilated = 9;
inline constexpr unsigned occlusionPrevious = 10;
inline constexpr unsigned tubeDepth = 11;
inline constexpr unsigned tubeColor = 12;
inline constexpr unsigned tubeNormal = 13;
inline constexpr unsigned partialOcclusion = 14;
inline constexpr unsigned labelIds = 15;
inline constexpr unsigned labelStyles = 16;
inline constexpr unsigned ismosLayerFront = 17;
inline constexpr unsigned ismosLayerAlpha = 18;
inline constexpr unsigned ismosLayerBack = 19;
inline constexpr unsigned ismosFit = 20;
inline constexpr unsigned seenBricks = 21;
inline constexpr unsigned clipNormals = 22;
inline constexpr unsigned labelField = 23;
inline constexpr unsigned labelOpacity = 24;
inline constexpr unsigned drilledFraction = 25;
inline constexpr unsigned drillNearBricks = 26;
inline constexpr unsigned tubeImpostorPoints = 27;
inline constexpr unsigned gradientVolume = 28;

inline constexpr unsigned imageOutput = 0;
inline constexpr unsigned imageOpacity = 1;
inline constexpr unsigned imageMask = 2;
inline constexpr unsigned imageAmbient = 3;
inline constexpr unsigned imageDilation = 4;
inline constexpr unsigned imageOcclusionNext = 5;
inline constexpr unsigned imagePartialOcclusion = 6;
inline constexpr unsigned imageIsmosLayerFront = 7;
inline constexpr unsigned imageIsmosLayerAlpha = 8;
inline constexpr unsigned imageIsmosLayerBack = 9;
inline constexpr unsigned imageIsmosFit = 10;
inline constexpr unsigned imageTubeNearestDepth = 11;
inline constexpr unsigned imageTubeNearestSegment = 12;
inline constexpr unsigned imageTubeColor = 13;
inline constexpr unsigned imageTubeNormal = 14;
inline constexpr unsigned imageTubeDepth = 15;
inline constexpr unsigned imageGradientVolume = 16;

inline constexpr unsigned ssboSampleCounter = 0;
inline constexpr unsigned ssboLaoDirections = 1;
inline constexpr unsigned ssboVisitBricks = 2;
inline constexpr unsigned ssboRecomputeList = 3;
inline constexpr unsigned ssboDispatch = 4;
inline constexpr unsigned ssboAntiAliasing = 5;
inline constexpr unsigned ssboPoissonDisk = 8;
inline constexpr unsigned ssboProbePoints = 6;
inline constexpr unsigned ssboProbeResults = 7;
inline constexpr unsigned ssboRemovalCounts = 9;
inline constexpr unsigned ssboIsmosLightSamples = 10;
inline constexpr unsigned ssboTubeRings = 11;
inline constexpr unsigned ssboTubeStreamlines = 12;
inline constexpr unsigned ssboTubeCircle = 13;
inline constexpr unsigned ssboTubePositions = 14;
inline constexpr unsigned ssboTubeDirections = 15;
inline constexpr unsigned ssboTubeColors = 16;
inline constexpr unsigned ssboTubeIndices = 17;
inline constexpr unsigned ssboTileSpans = 18;
inline constexpr unsigned ssboTubeCandidates = 19;

inline constexpr unsigned uboClipMeshes = 0;

// G-buffer surface kinds (normal.w: tube_gbuffer.frag's surfaceKind).
inline constexpr float surfaceNone = 0.0f;
inline constexpr float surfaceTube = 1.0f;
inline constexpr float surfaceLine = 2.0f;

// V_m categories (CAO Fig. 5).
inline constexpr unsigned categoryClipped = 0;
inline constexpr unsigned categoryAffected = 1;
inline constexpr unsigned categoryUnaffected = 2;

}  // namespace curette::binding
