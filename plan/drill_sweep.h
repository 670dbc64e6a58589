#pragma once
// The region a drill burr sweeps between two poses: the union of the burr over its motion, not its poses
// sampled at frame times, so a fast stroke leaves no ridges. The burr is the analytic solid its mesh
// approximates (mesh/solid_shape.h), scaled per axis like the mesh.
//
// Under a translation d the burr S sweeps S + [0, 1] d, and a point x lies in it when the convex function
// t -> sdf(local(x - t d)) has a minimum <= 0 on [0, 1] (sdf of a convex solid is convex, the local map
// affine): a straight stroke of a sphere is its capsule, exactly. A rotation is followed in sub-steps, each a
// translation at the sub-step's starting orientation, so small that no point of the burr turns by more than
// `rotationToleranceMm` within one: a rotating burr's sweep is exact to that distance (the union misses at
// most a shell that thin at the sweep's surface).
//
// distanceBound() lets the removal settle whole voxels: per step the same minimum over t, bracketed (the
// golden-section bracket holds the minimiser, and the function is |motion|-Lipschitz in t), turned into world
// mm by the smallest scale (a world step of L moves the local point by at most L / min|scale|; the shapes'
// distances are 1-Lipschitz), and far from a step the distance to its path less the burr's bounding radius.

#include "mesh/rigid_pose.h"
#include "mesh/solid_shape.h"
#include "plan/removal_volume.h"

#include <glm/glm.hpp>

#include <vector>

namespace curette::plan {

struct DrillTool {
    clip::SolidShape shape;
    glm::dvec3 scale{1.0};
};

// The default rotation tolerance: an eighth of a millimetre.
inline constexpr double kDrillRotationToleranceMm = 0.125;

class DrillSweep {
public:
    DrillSweep(const DrillTool& tool, const clip::RigidPose& from, const clip::RigidPose& to,
               double rotationToleranceMm = kDrillRotationToleranceMm);

    bool contains(glm::dvec3 world) const;
    // A conservative signed distance to the sweep (a DistanceBound, plan/removal_volume.h).
    double distanceBound(glm::dvec3 world) const;
    glm::dvec3 boundsMin() const { return boundsMin_; }   // world box holding the sweep
    glm::dvec3 boundsMax() const { return boundsMax_; }
    int substeps() const { return static_cast<int>(steps_.size()); }

private:
    struct Step {
        glm::dmat4 worldToLocal{1.0};   // at the step's start, scale included
        glm::dvec3 localMotion{0.0};    // the step's translation seen in that frame: local(x - t d) = local(x) - t * this
        glm::dvec3 worldFrom{0.0}, worldTo{0.0};   // the burr centre's path in the step
    };
    bool insideStep(const Step& step, glm::dvec3 world) const;
    double stepDistanceBound(const Step& step, glm::dvec3 world) const;

    DrillTool tool_;
    double boundingRadiusMm_ = 0;   // of the scaled burr about its centre
    double smallestScale_ = 1;      // min |scale|: local distances times this are world distances at least
    std::vector<Step> steps_;
    glm::dvec3 boundsMin_{0.0}, boundsMax_{0.0};
};

// Removes (erase: restores) what `sweep` holds from `removal` (RemovalVolume::apply with the sweep's bound).
std::size_t applySweep(RemovalVolume& removal, const DrillSweep& sweep, bool erase, BrickMaskMap* before = nullptr);

}  // namespace curette::plan
