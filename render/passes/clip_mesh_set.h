#pragma once
// The active clip meshes and their maps (CAO section 3.6: one clipping camera and map set per mesh). Owns
// the GPU side of steps II and III: for each mesh, depth maps of one or two intervals (depth peeling for
// concave meshes) and, when AO needs them, the dilated maps; all meshes' maps live in two 2-D array
// textures, the depth maps at a fine resolution over each mesh's bounds, the dilated maps at one coarser
// resolution over the bounds and the dilation margin (render/model/clipping_camera.h). A rigid motion changes only the mesh's camera matrix (an entry of a
// uniform block);
// maps are redrawn only when a mesh's geometry or scale, the dilation radius or the map resolution change.

#include "render/model/clipping_camera.h"
#include "render/model/depth_interval_pyramid.h"
#include "mesh/limits.h"
#include "mesh/rigid_pose.h"
#include "mesh/triangle_mesh.h"
#include "gl/objects.h"
#include "gl/program.h"

#include <cstdint>
#include <limits>
#include <memory>
#include <string>
#include <vector>

namespace curette::clip {

struct ClipMapSettings {
    double pixelMm = 0.5;        // target dilated-map pixel size (the renderer passes half the smallest voxel spacing)
    int minResolution = 64;
    int maxResolution = 1024;
    // The depth maps' pixels per side over their square (the mesh's bounds): a face across the map lies within
    // half a depth pixel, a 2000th of the mesh's extent, of where the mesh puts it.
    int depthResolution = 1024;
};

class ClipMeshSet {
public:
    static constexpr int maxMeshes = kMaxClipMeshes;
    static constexpr int layersPerMesh = 4;  // front 1, back 1, front 2, back 2

    explicit ClipMeshSet(ClipMapSettings settings = {});
    ~ClipMeshSet();

    // Adds a mesh (geometry in local millimetres, scaled by `scale`, placed by `pose`); returns its index.
    // Throws InputError when the limit is reached, the scale is not positive and finite, or the mesh is empty.
    int add(std::shared_ptr<const TriangleMesh> geometry, glm::dvec3 scale, const RigidPose& pose, std::string name);
    void remove(int index);
    void clear();
    void setPose(int index, const RigidPose& pose);
    void setScale(int index, glm::dvec3 scale);
    // Whether mesh `index` also cuts tubes (they are always clipped by none otherwise).
    void setClipsTubes(int index, bool clips);
    bool clipsTubes(int index) const { return meshes_[static_cast<std::size_t>(index)].clipsTubes; }
    // The radius of the LAO influence around the meshes: the clipping cameras leave room for it, so the maps
    // are the same whichever shading mode runs (CAO equals LAO only under the very same clipping).
    void setDilationRadiusMm(double radiusMm);
    // Whether the dilated maps are drawn (cao needs them; solid, phong, lao and dos do not).
    void setDilatedMapsNeeded(bool needed);
    bool dilatedMapsNeeded() const { return dilatedNeeded_; }

    int count() const { return static_cast<int>(meshes_.size()); }
    const RigidPose& pose(int index) const { return meshes_[static_cast<std::size_t>(index)].pose; }
    glm::dvec3 scale(int index) const { return meshes_[static_cast<std::size_t>(index)].scale; }
    const std::string& name(int index) const { return meshes_[static_cast<std::size_t>(index)].name; }
    const TriangleMesh* geometry(int index) const { return meshes_[static_cast<std::size_t>(index)].geometry.get(); }
    const ClippingCamera& camera(int index) const { return meshes_[static_cast<std::size_t>(index)].camera; }
    int intervals(int index) const { return meshes_[static_cast<std::size_t>(index)].intervals; }
    // Whether some map pixel of mesh `index` sees more than two intervals: interval 2 then ends at the
    // farthest back face (beyond the second interval the mesh clips like its hull).
    bool deeperThanTwoIntervals(int index) const { return meshes_[static_cast<std::size_t>(index)].deeperThanTwoIntervals; }
    // The dilated maps' resolution (pixels a side; the wanted one of the meshes last drawn) and the arrays'
    // allocated one (at least that: it grows with headroom and shrinks only below half, to reallocate rarely).
    int resolution() const { return mapResolution_; }
    int allocatedResolution() const { return resolution_; }
    // The depth maps' resolution (fixed: ClipMapSettings::depthResolution).
    int depthResolution() const { return settings_.depthResolution; }
    double dilationRadiusMm() const { return dilationRadiusMm_; }
    // The radius the dilation kernel uses for mesh `index`: R plus sqrt(2) map pixels plus a rounding margin.
    double kernelRadiusMm(int index) const;

    // The world-space axis-aligned box around mesh `index`'s map box (its clipping camera's x, y extent over
    // the depth range plus margin): no clip or dilation lookup of a point outside it can answer "inside".
    struct WorldBox {
        glm::dvec3 min, max;
    };
    WorldBox mapBoxWorldBounds(int index) const;
    // Mesh `index`'s map box in its pose's local frame (x, y: the map; z: the depth range plus margin), and the
    // slack the shaders' near test adds to it (clip_test.glsl nearAnyClipMesh) for float rounding of the map
    // transform.
    void mapBoxLocal(int index, glm::dvec3& lo, glm::dvec3& hi) const;
    double mapBoxSlackMm(int index) const;
    // The dilated box of mesh `index`, in its pose's local frame: the box outside which neither its depth maps
    // nor its dilated maps call any point inside (derivation in the .cpp). It lies inside the map box. Steps IV
    // and V visit the bricks these boxes reach (render/mesh_voxel_box.h). Valid after update().
    void dilatedBoxLocal(int index, glm::dvec3& lo, glm::dvec3& hi) const;
    // The depth box of mesh `index`, in its pose's local frame: the box outside which its depth maps (not the
    // dilated ones) call no point inside, grown by depthBoxMarginMm. The ray caster tests a sample against the
    // maps only where its ray meets this box (clip_test.glsl rayClipSpan), step IV and the removal field only
    // the meshes whose box is within a voxel's sample reach (nearDepthBox). Valid after update().
    void depthBoxLocal(int index, glm::dvec3& lo, glm::dvec3& hi) const;
    // Balls in the pose's local frame, around the centre of the mesh's bounds (derivations in the .cpp). Valid
    // after update().
    //  - depthBallLocal: holds every point the depth maps call inside, like the depth box (and grown as much;
    //    the passes test both, clip_test.glsl rayClipSpan and nearDepthBox);
    //  - reachBallLocal: holds every point within R (dilationRadiusMm) of such a point, grown as the dilated box
    //    is across the map. Where a mesh can change a voxel's V_o (a clip sample inside) or its LAO (a changed
    //    V_o within reach) lies in both its reach ball and its dilated box (render/mesh_voxel_box.h). Unlike the
    //    box, the ball need not hold the whole dilated shape: the separable kernel reaches past it at the map's
    //    diagonals, where the shape holds no voxel whose AO the mesh changes.
    struct Ball {
        glm::dvec3 centre{0.0};
        double radius = 0.0;
    };
    Ball depthBallLocal(int index) const;
    Ball reachBallLocal(int index) const;
    // For the rounding between a point computed one way where the box is tested (from a ray parameter, or a
    // voxel centre rather than its sample) and another where the maps are: far above it, small beside a mesh.
    static constexpr double depthBoxMarginMm = 0.5;
    // Whether the passes use the depth boxes to skip the clip tests no depth map can answer "inside": the ray
    // caster tests only the stretch of each ray that meets one (clip_test.glsl rayClipSpan), step IV a voxel's
    // samples only against the meshes whose depth box lies within their reach (nearDepthBox), and not at all in
    // the bricks beyond every mesh's reach or deep inside one (render/mesh_voxel_box.h). On by default; off
    // tests every sample against every mesh, with the same answers (the tests' and `bench cao`'s reference).
    void setDepthBoxTests(bool on) { depthBoxTests_ = on; }
    bool depthBoxTests() const { return depthBoxTests_; }

    // Changes whenever the clipped region may have changed (a pose, a scale, a mesh added or removed).
    std::uint64_t version() const { return version_; }
    // How many times step II/III ran for a mesh (tests check rigid motion does not redraw).
    std::uint64_t mapRenderCount() const { return mapRenders_; }

    // Whether update() has nothing to draw: every mesh's depth maps (and, with `dilatedNeeded`, its dilated
    // maps) match its geometry, scale and the dilation radius, at a resolution that still fits.
    bool mapsCurrent(bool dilatedNeeded) const;
    int meshesNeedingMaps(bool dilatedNeeded) const;   // of them, those update() would draw (all, when the size changes)
    // Steps II and III for meshes that need them, and the per-mesh cameras into the uniform block; at most
    // `meshes` of them (the viewer draws them a mesh an iteration). Each mesh's maps depend on it alone, so the
    // maps are the same however the meshes were spread over calls.
    void update(int meshes = std::numeric_limits<int>::max());
    // Only the per-mesh cameras (a rigid motion needs nothing else).
    void uploadCameras();
    // The binder of shaders/clip_test.glsl: clipMeshCount, the uniform block of clipping cameras and the map
    // arrays on their units.
    void apply(gl::Program& program) const;
    // NO_CLIP_MESHES while the set is empty, for the passes that test every sample (the ray caster, the slab
    // pass): their clip tests are then compiled out, not skipped at run time (clip_test.glsl).
    void addDefines(gl::Defines& defines) const;

    // Mesh `index`'s depth intervals summarised for region queries on the CPU (step IV's bricks deep inside a
    // mesh, render/mesh_voxel_box.h): read back and built on first use after its maps were drawn. Valid after
    // update().
    const DepthIntervalPyramid& depthIntervals(int index) const;
    // Reads one map layer back (tests): layer 0..3 = front 1, back 1, front 2, back 2; depthResolution() or
    // resolution() pixels a side.
    std::vector<float> readMap(int index, int layer, bool dilated) const;
    std::size_t gpuBytes() const;        // the map arrays
    std::size_t geometryBytes() const;   // the meshes' vertex buffers

    // Mesh `index`'s vertex buffer as step II draws it: vertexCount(index) CornerVertex, three per triangle, in
    // the scaled mesh-local frame (pose(index).matrix() places them in the world). The clip-mesh overlay
    // (render/clip_mesh_overlay.h) draws the same buffer.
    struct CornerVertex {
        glm::vec3 position, normal;   // scaled mesh-local
    };
    GLuint vertexBuffer(int index) const { return meshes_[static_cast<std::size_t>(index)].vertices.name(); }
    GLsizei vertexCount(int index) const { return meshes_[static_cast<std::size_t>(index)].vertexCount; }

private:
    struct Mesh {
        std::shared_ptr<const TriangleMesh> geometry;
        glm::dvec3 scale{1.0};
        RigidPose pose;
        std::string name;
        ClippingCamera camera;
        int intervals = 1;
        bool deeperThanTwoIntervals = false;
        bool clipsTubes = false;
        bool mapsDirty = true;
        bool dilatedDirty = true;
        gl::Buffer vertices;   // CornerVertex per triangle corner
        mutable std::shared_ptr<const DepthIntervalPyramid> intervalsRead;   // depthIntervals, until the maps are drawn again
        GLsizei vertexCount = 0;
        glm::dvec3 localMin{0.0}, localMax{0.0};
        double hullRadius = 0.0;   // the farthest scaled vertex from the centre of localMin..localMax
    };
    void uploadGeometry(Mesh& mesh);
    // The ball around mesh `index`'s hull grown as a box with upper corner `boxHi` is grown across the map.
    Ball hullBallGrownAs(int index, glm::dvec3 boxHi) const;
    void allocateArrays(int layers);
    void renderMaps(int index);
    void dilateMaps(int index);
    int wantedResolution() const;
    bool needsReallocation(int wanted, bool dilatedNeeded) const;

    ClipMapSettings settings_;
    std::vector<Mesh> meshes_;
    double dilationRadiusMm_ = 0.0;
    bool dilatedNeeded_ = false;
    int resolution_ = 0;        // allocated
    int mapResolution_ = 0;     // drawn (<= resolution_)
    int allocatedLayers_ = 0;
    bool dilatedAllocated_ = false;
    std::uint64_t version_ = 1, mapRenders_ = 0;
    bool depthBoxTests_ = true;
    gl::Texture depthMaps_, normalMaps_, dilatedMaps_, reducedArray_, scratchArray_, scratch_, normalScratch_;
    gl::Renderbuffer depthBuffer_;
    gl::Framebuffer framebuffer_;
    gl::VertexArray vertexArray_;
    gl::Buffer cameraBuffer_;
    gl::Program depthProgram_, reduceProgram_, dilationProgram_;
};

}  // namespace curette::clip
