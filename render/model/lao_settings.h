#pragma once
// The LAO settings of lao/cao shading (CAO steps I, IV, V): plain data the scene reader fills and
// render/passes/ambient_occlusion.h uses.

#include "render/model/lao_directions.h"

namespace curette {

struct LaoSettings {
    LaoDirectionSet directions;
    int samples = 20;                // M, samples per ray (eq. 2); the paper's Engine scene uses 20
    double stepMm = 1.0;             // distance between LAO samples (the paper: 1 mm)
    int antiAliasingSamples = 32;    // N of Algorithm 2 (the paper: 32)
    // Shading: colour = TF colour * ambientScale * A. With 2 an open flat surface (A = 0.5) shows its TF
    // colour (the reference implementation also doubles LAO). Not part of V_AO, so not of the contract.
    double ambientScale = 2.0;
    // Step V: a full-grid dispatch that decides per voxel (early exit), or a compacted list of the voxels to
    // recompute (atomic append + indirect dispatch). `curette bench cao` measures both (its "Step V dispatch"
    // table): on the head at K = 26 the compacted list took 710 ms against 982 ms for the grid (both over the
    // CAO dispatch region), 803 against 1645 ms when both still visited the whole volume.
    enum class Dispatch { Compacted, FullGrid } dispatch = Dispatch::Compacted;
    // Steps I and V cast LAO rays only from voxels a visible sample can read (shaders/lao_common.glsl,
    // ambientSeen: voxels in a seen brick, one a visible sample can lie in); elsewhere V_AO is 1, which no pixel
    // reads. The image is the same either way, bit for bit; off is the paper's LAO of every voxel, for
    // comparison (`curette bench cao --unseen-voxels compute`).
    bool onlyWhereSeen = true;

    bool operator==(const LaoSettings& o) const {
        return directions.pattern == o.directions.pattern && directions.count == o.directions.count &&
               directions.jitter == o.directions.jitter && directions.seed == o.directions.seed &&
               directions.skyWeighting == o.directions.skyWeighting && samples == o.samples && stepMm == o.stepMm &&
               antiAliasingSamples == o.antiAliasingSamples && dispatch == o.dispatch && onlyWhereSeen == o.onlyWhereSeen && ambientScale == o.ambientScale;
    }
};

}  // namespace curette
