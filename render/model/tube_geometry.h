#pragma once
// Tubes and illuminated lines built from streamlines on the CPU (drawn by render/passes/tube_set.h). Each polyline
// is cleaned (duplicate points dropped), optionally smoothed and resampled (centripetal Catmull-Rom), then a
// circle is swept along it with rotation-minimising frames (the double reflection method of Wang, Jüttler,
// Zheng and Liu 2008: parallel transport, never Frenet, so no flips at inflections and no twist).

#include "base/progress.h"
#include "base/tractogram.h"
#include "base/transfer_function.h"
#include "render/model/tube_impostors.h"
#include "render/model/tube_vertices.h"

#include <string>

namespace curette {

struct TubeSettings {
    enum class Smoothing { None, CatmullRom };
    enum class Coloring { Direction, Scalar, Uniform };
    double radiusMm = 0.5;
    int sides = 8;
    bool caps = true;
    Smoothing smoothing = Smoothing::CatmullRom;
    double stepMm = 0.5;                   // resampling step of the smoothed curve
    Coloring coloring = Coloring::Direction;  // |tangent| as RGB, the DTI convention
    std::string scalarName;                // for Coloring::Scalar
    double scalarMin = 0, scalarMax = 0;   // colour-map range; equal: the data's range
    glm::dvec3 uniformColor{0.9, 0.85, 0.3};
};

struct TubeBuildStats {
    std::size_t streamlines = 0, skippedSinglePoint = 0, duplicatePointsRemoved = 0, rings = 0;
};

// Triangles with outward normals (TubeVertices::lines == false): expandTubeRings(sweepTubeRings(...)).
TubeVertices buildTubes(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats* stats = nullptr);

// The rings a tube is swept through, before any vertex exists: the sweep (cleaning, smoothing, frames,
// colours) is done once on the CPU, and the rings are expanded into vertices and indices either here
// (expandTubeRings, the oracle) or on the GPU (render/passes/gpu_tube_builder.h), which write the same layout:
// per streamline its rings' vertices (ring i, side k at firstVertex + i * sides + k), then with caps the
// start cap (centre, then `sides` rim vertices) and the end cap; indices: per ring pair 6 per side, then
// 3 per side for each cap.
struct TubeRing {
    glm::dvec3 point, tangent, normal;   // centre, unit tangent, unit rotation-minimising normal
    glm::vec4 color;                     // of the ring's vertices (and of a cap at an end ring)
};
struct TubeStreamline {
    std::uint32_t firstRing = 0, ringCount = 0;      // ringCount >= 2
    std::uint32_t firstVertex = 0, firstIndex = 0;
    double radiusMm = 0.5;
    std::uint32_t sides = 8;
    bool caps = true;
    std::uint32_t vertexCount() const { return ringCount * sides + (caps ? 2 * (sides + 1) : 0); }
    std::uint32_t indexCount() const { return (ringCount - 1) * sides * 6 + (caps ? 2 * 3 * sides : 0); }
};
struct TubeRings {
    std::vector<TubeRing> rings;
    std::vector<TubeStreamline> streamlines;
    std::size_t vertexCount = 0, indexCount = 0;   // of the expanded tubes
    // Appends `other`, its vertices and indices numbered after these.
    void append(const TubeRings& other);
};
// `progress`, when given, advances by one per streamline (a whole-brain set takes seconds).
TubeRings sweepTubeRings(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats* stats = nullptr, Progress* progress = nullptr);
TubeVertices expandTubeRings(const TubeRings& rings);
// The same sweep's points for impostor tubes (render/model/tube_impostors.h): one bundle of the settings'
// radius and caps, its points where the rings would be, coloured as they are. `sides` is not used.
TubeImpostors sweepTubeImpostors(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats* stats = nullptr,
                                 Progress* progress = nullptr);
// Line segments with tangents for illuminated-line shading (TubeVertices::lines == true).
TubeVertices buildIlluminatedLines(const Tractogram& tracts, const TubeSettings& settings, TubeBuildStats* stats = nullptr);

// The cleaned (and smoothed/resampled) polyline of streamline `s`, its unit tangents and the rotation-
// minimising normals: what the tube is swept along (exposed for tests).
struct SweptCurve {
    std::vector<glm::dvec3> points, tangents, normals;
};
SweptCurve sweepCurve(const Tractogram& tracts, std::size_t s, const TubeSettings& settings, std::size_t* duplicatesRemoved = nullptr);

// Seed 004 eq. 3.12-3.15: the colour of a line with unit tangent `tangent`, lit from `toLight` and seen from
// `toViewer` (unit vectors), with material ka, kd, ks, shininess and the diffuse exponent p of eq. 3.15.
// The CPU oracle of shaders/illuminated_lines.glsl (there the albedo multiplies ambient and diffuse only).
glm::dvec3 illuminatedLineColor(glm::dvec3 albedo, glm::dvec3 tangent, glm::dvec3 toLight, glm::dvec3 toViewer,
                                const TransferFunction::Material& material, double diffuseExponent);

// A perceptually ordered colour map (viridis-like, by piecewise-linear stops) for scalar colouring.
glm::dvec3 colorMap(double t);

}  // namespace curette
