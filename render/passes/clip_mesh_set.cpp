#include "render/passes/clip_mesh_set.h"

#include "mesh/surface_normals.h"

#include "base/error.h"
#include "base/log.h"
#include "gl/bindings.h"
#include "render/passes/clip_mesh_gpu.h"

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstring>
#include <limits>

namespace curette::clip {

namespace {

constexpr float kInfinity = std::numeric_limits<float>::infinity();

// Whether any pixel of the resolution x resolution corner of a 2-D texture is finite.
bool anyFinite(GLuint texture, int resolution) {
    std::vector<float> values(static_cast<std::size_t>(resolution) * static_cast<std::size_t>(resolution));
    glGetTextureSubImage(texture, 0, 0, 0, 0, resolution, resolution, 1, GL_RED, GL_FLOAT, static_cast<GLsizei>(values.size() * sizeof(float)),
                         values.data());
    return std::any_of(values.begin(), values.end(), [](float v) { return std::isfinite(v); });
}

}  // namespace

ClipMeshSet::ClipMeshSet(ClipMapSettings settings) : settings_(settings) {}
ClipMeshSet::~ClipMeshSet() = default;

int ClipMeshSet::add(std::shared_ptr<const TriangleMesh> geometry, glm::dvec3 scale, const RigidPose& pose, std::string name) {
    if (count() >= maxMeshes)
        throw InputError(name, "clip_meshes", "at most " + std::to_string(maxMeshes) + " clip meshes at once",
                         std::to_string(count() + 1));
    if (!geometry || geometry->triangles.empty())
        throw InputError(name, "mesh", "a mesh with triangles", "an empty mesh");
    for (int a = 0; a < 3; ++a)
        if (!(scale[a] > 0.0) || !std::isfinite(scale[a]))
            throw InputError(name, "scale", "three positive finite factors (a zero scale has no inside)",
                             std::to_string(scale.x) + ", " + std::to_string(scale.y) + ", " + std::to_string(scale.z));
    Mesh mesh;
    mesh.geometry = std::move(geometry);
    mesh.scale = scale;
    mesh.pose = pose;
    mesh.name = std::move(name);
    uploadGeometry(mesh);
    meshes_.push_back(std::move(mesh));
    ++version_;
    return count() - 1;
}

void ClipMeshSet::remove(int index) {
    meshes_.erase(meshes_.begin() + index);
    // Later meshes move down one slot in the arrays: their maps must be redrawn there.
    for (std::size_t i = static_cast<std::size_t>(index); i < meshes_.size(); ++i) meshes_[i].mapsDirty = true;
    ++version_;
}

void ClipMeshSet::clear() {
    meshes_.clear();
    ++version_;
}

void ClipMeshSet::setPose(int index, const RigidPose& pose) {
    Mesh& m = meshes_[static_cast<std::size_t>(index)];
    if (m.pose == pose) return;
    m.pose = pose;
    ++version_;
}

void ClipMeshSet::setScale(int index, glm::dvec3 scale) {
    Mesh& m = meshes_[static_cast<std::size_t>(index)];
    for (int a = 0; a < 3; ++a)
        if (!(scale[a] > 0.0) || !std::isfinite(scale[a]))
            throw InputError(m.name, "scale", "three positive finite factors (a zero scale has no inside)",
                             std::to_string(scale.x) + ", " + std::to_string(scale.y) + ", " + std::to_string(scale.z));
    if (m.scale == scale) return;
    m.scale = scale;
    uploadGeometry(m);
    ++version_;
}

void ClipMeshSet::setClipsTubes(int index, bool clips) {
    Mesh& m = meshes_[static_cast<std::size_t>(index)];
    if (m.clipsTubes == clips) return;
    m.clipsTubes = clips;
    ++version_;
}

void ClipMeshSet::setDilationRadiusMm(double radiusMm) {
    if (radiusMm == dilationRadiusMm_) return;
    dilationRadiusMm_ = radiusMm;
    for (Mesh& m : meshes_) m.mapsDirty = true;  // the margin and the dilated maps depend on it
    ++version_;
}

void ClipMeshSet::setDilatedMapsNeeded(bool needed) {
    if (needed == dilatedNeeded_) return;
    dilatedNeeded_ = needed;
    // Depth maps stay as they are; only the dilated ones appear (drawn at the next update) or go.
    if (needed)
        for (Mesh& m : meshes_) m.dilatedDirty = true;
}

double ClipMeshSet::kernelRadiusMm(int index) const {
    // Derivation of the map term of the dilation radius (the volume terms are derived in
    // AmbientOcclusion::dilationRadiusMm; docs/architecture.md "The CAO exactness contract"): a point s inside
    // the mesh and a voxel v within R of it map to pixels at most |v - s|_xy + sqrt(2) px apart (each lies within sqrt(2)/2 px of its pixel centre),
    // so a kernel of radius R + sqrt(2) px over pixel centres covers every such pair; a small epsilon absorbs
    // float rounding of the map transforms and depth comparisons.
    // The point s is looked up in the depth reduced to the dilated map's pixels (dilation.comp's source,
    // clip_reduce.comp), so px is the dilated map's pixel.
    double px = camera(index).pixelMm();
    return dilationRadiusMm_ + std::sqrt(2.0) * px + 1e-3 * dilationRadiusMm_ + 1e-3;
}

void ClipMeshSet::uploadGeometry(Mesh& mesh) {
    mesh.localMin = glm::dvec3(std::numeric_limits<double>::infinity());
    mesh.localMax = -mesh.localMin;
    for (const glm::vec3& q : mesh.geometry->positions) {
        glm::dvec3 p = glm::dvec3(q) * mesh.scale;
        mesh.localMin = glm::min(mesh.localMin, p);
        mesh.localMax = glm::max(mesh.localMax, p);
    }
    glm::dvec3 centre = 0.5 * (mesh.localMin + mesh.localMax);
    mesh.hullRadius = 0.0;
    for (const glm::vec3& q : mesh.geometry->positions)
        mesh.hullRadius = std::max(mesh.hullRadius, glm::length(glm::dvec3(q) * mesh.scale - centre));
    // One vertex per triangle corner: its scaled position and the surface normal there (mesh/surface_normals.h),
    // which step II draws into the normal maps for the cut faces.
    std::vector<glm::vec3> normals = cornerNormals(*mesh.geometry, mesh.scale);
    std::vector<CornerVertex> corners(normals.size());
    for (std::size_t t = 0; t < mesh.geometry->triangles.size(); ++t)
        for (int c = 0; c < 3; ++c) {
            std::size_t i = 3 * t + static_cast<std::size_t>(c);
            corners[i] = {glm::vec3(glm::dvec3(mesh.geometry->positions[mesh.geometry->triangles[t][c]]) * mesh.scale), normals[i]};
        }
    mesh.vertices = gl::createBuffer();
    glNamedBufferStorage(mesh.vertices.name(), static_cast<GLsizeiptr>(corners.size() * sizeof(CornerVertex)), corners.data(), 0);
    mesh.vertexCount = static_cast<GLsizei>(corners.size());
    mesh.mapsDirty = true;
}

void ClipMeshSet::allocateArrays(int layers) {
    auto makeArray = [&](const char* label, int resolution, int count, GLenum format = GL_R32F) {
        gl::Texture t = gl::createTexture(GL_TEXTURE_2D_ARRAY);
        glTextureStorage3D(t.name(), 1, format, resolution, resolution, count);
        glTextureParameteri(t.name(), GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        glTextureParameteri(t.name(), GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        glObjectLabel(GL_TEXTURE, t.name(), -1, label);
        return t;
    };
    const int depth = settings_.depthResolution;
    depthMaps_ = makeArray("clip depth maps (Z_front, Z_back per interval)", depth, layers);
    normalMaps_ = makeArray("clip normal maps (octahedral mesh-local normal per depth-map pixel)", depth, layers, GL_RG16_SNORM);
    dilatedAllocated_ = dilatedNeeded_;
    dilatedMaps_ = dilatedAllocated_ ? makeArray("clip dilated maps (D_front, D_back per interval)", resolution_, layers) : gl::Texture();
    allocatedLayers_ = layers;
    scratch_ = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(scratch_.name(), 1, GL_R32F, depth, depth);
    normalScratch_ = gl::createTexture(GL_TEXTURE_2D);
    glTextureStorage2D(normalScratch_.name(), 1, GL_RG16_SNORM, depth, depth);
    reducedArray_ = makeArray("clip depth reduced to the dilated maps' pixels", resolution_, 1);
    scratchArray_ = makeArray("clip dilation, first pass", resolution_, 1);
    depthBuffer_ = gl::createRenderbuffer();
    glNamedRenderbufferStorage(depthBuffer_.name(), GL_DEPTH_COMPONENT32F, depth, depth);
    framebuffer_ = gl::createFramebuffer();
    glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT0, scratch_.name(), 0);
    glNamedFramebufferTexture(framebuffer_.name(), GL_COLOR_ATTACHMENT1, normalScratch_.name(), 0);
    const GLenum drawBuffers[2] = {GL_COLOR_ATTACHMENT0, GL_COLOR_ATTACHMENT1};
    glNamedFramebufferDrawBuffers(framebuffer_.name(), 2, drawBuffers);
    glNamedFramebufferRenderbuffer(framebuffer_.name(), GL_DEPTH_ATTACHMENT, GL_RENDERBUFFER, depthBuffer_.name());
    if (glCheckNamedFramebufferStatus(framebuffer_.name(), GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE)
        throw SystemError("clip depth-map framebuffer is incomplete");
}

int ClipMeshSet::wantedResolution() const {
    // One resolution for all maps: enough for the largest mesh at the target pixel size.
    int wanted = settings_.minResolution;
    for (const Mesh& m : meshes_) {
        double extent = std::max(m.localMax.x - m.localMin.x, m.localMax.y - m.localMin.y) + 2.0 * dilationRadiusMm_;
        wanted = std::max(wanted, static_cast<int>(std::ceil(extent / settings_.pixelMm)) + 8);
    }
    return std::min(wanted, settings_.maxResolution);
}

bool ClipMeshSet::needsReallocation(int wanted, bool dilatedNeeded) const {
    return resolution_ == 0 || wanted > resolution_ || wanted < resolution_ / 2 || allocatedLayers_ < layersPerMesh * count() ||
           (dilatedNeeded && !dilatedAllocated_);
}

bool ClipMeshSet::mapsCurrent(bool dilatedNeeded) const {
    if (meshes_.empty()) return true;
    int wanted = wantedResolution();
    if (!depthProgram_ || needsReallocation(wanted, dilatedNeeded) || wanted != mapResolution_) return false;
    for (const Mesh& m : meshes_)
        if (m.mapsDirty || (dilatedNeeded && m.dilatedDirty)) return false;
    return true;
}

int ClipMeshSet::meshesNeedingMaps(bool dilatedNeeded) const {
    if (!depthProgram_ || needsReallocation(wantedResolution(), dilatedNeeded) || wantedResolution() != mapResolution_) return count();
    int n = 0;
    for (const Mesh& m : meshes_) n += m.mapsDirty || (dilatedNeeded && m.dilatedDirty);
    return n;
}

std::size_t ClipMeshSet::geometryBytes() const {
    std::size_t bytes = 0;
    for (const Mesh& m : meshes_) bytes += static_cast<std::size_t>(m.vertexCount) * sizeof(CornerVertex);
    return bytes;
}

void ClipMeshSet::update(int meshes) {
    if (!depthProgram_) {
        depthProgram_ = gl::Program::graphics("clip_depth.vert", "clip_depth.frag");
        reduceProgram_ = gl::Program::compute("clip_reduce.comp");
        dilationProgram_ = gl::Program::compute("dilation.comp");
        vertexArray_ = gl::createVertexArray();
    }
    if (meshes_.empty()) {
        uploadCameras();
        return;
    }
    int wanted = wantedResolution();
    // Grow in steps of 25% so a mesh that scales up a little does not reallocate every frame.
    bool reallocate = needsReallocation(wanted, dilatedNeeded_);
    if (reallocate) {
        if (resolution_ == 0 || wanted > resolution_ || wanted < resolution_ / 2)
            resolution_ = std::min(settings_.maxResolution, std::max(wanted, resolution_ == 0 ? wanted : wanted + wanted / 4));
        allocateArrays(layersPerMesh * std::max(count(), 4));
        for (Mesh& m : meshes_) m.mapsDirty = true;
    }
    // The maps are drawn at the wanted resolution, not the allocated one, so they depend on the meshes alone
    // and not on what the set held before: a renderer that once held a larger mesh draws what a fresh one draws.
    if (wanted != mapResolution_) {
        mapResolution_ = wanted;
        for (Mesh& m : meshes_) m.mapsDirty = true;
    }
    int drawn = 0;
    for (int i = 0; i < count() && drawn < meshes; ++i) {
        Mesh& m = meshes_[static_cast<std::size_t>(i)];
        if (m.mapsDirty || (dilatedNeeded_ && m.dilatedDirty)) ++drawn;
        if (m.mapsDirty) {
            m.camera = fitClippingCamera(m.localMin, m.localMax, dilationRadiusMm_, mapResolution_, settings_.depthResolution);
            m.camera.hullRadiusMm = m.hullRadius;
            renderMaps(i);
            m.intervalsRead.reset();
            m.mapsDirty = false;
            m.dilatedDirty = true;
            ++mapRenders_;
        }
        if (dilatedNeeded_ && m.dilatedDirty) {
            dilateMaps(i);
            m.dilatedDirty = false;
        }
    }
    uploadCameras();
}

void ClipMeshSet::renderMaps(int index) {
    Mesh& m = meshes_[static_cast<std::size_t>(index)];
    const int base = layersPerMesh * index;
    glBindFramebuffer(GL_FRAMEBUFFER, framebuffer_.name());
    const int depth = settings_.depthResolution;
    glViewport(0, 0, depth, depth);
    glEnable(GL_DEPTH_TEST);
    glDepthFunc(GL_LESS);
    glDepthMask(GL_TRUE);
    glEnable(GL_CULL_FACE);
    // The camera looks along local +z with x right and y up, so faces turned towards it (normal.z < 0) wind
    // clockwise on screen: call those front faces.
    glFrontFace(GL_CW);
    glDisable(GL_BLEND);
    depthProgram_.use();
    depthProgram_.set("localToClip", glm::mat4(m.camera.localToClip()));
    glBindVertexArray(vertexArray_.name());
    glVertexArrayVertexBuffer(vertexArray_.name(), 0, m.vertices.name(), 0, sizeof(CornerVertex));
    for (GLuint attribute : {0u, 1u}) {
        glEnableVertexArrayAttrib(vertexArray_.name(), attribute);
        glVertexArrayAttribFormat(vertexArray_.name(), attribute, 3, GL_FLOAT, GL_FALSE,
                                  attribute == 0 ? offsetof(CornerVertex, position) : offsetof(CornerVertex, normal));
        glVertexArrayAttribBinding(vertexArray_.name(), attribute, 0);
    }
    glBindTextureUnit(binding::clipDepth, depthMaps_.name());

    auto copyLayer = [&](int layer) {
        glCopyImageSubData(scratch_.name(), GL_TEXTURE_2D, 0, 0, 0, 0, depthMaps_.name(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, depth, depth, 1);
        glCopyImageSubData(normalScratch_.name(), GL_TEXTURE_2D, 0, 0, 0, 0, normalMaps_.name(), GL_TEXTURE_2D_ARRAY, 0, 0, 0, layer, depth, depth, 1);
    };
    // Layers: 0 front 1, 1 back 1, 2 front 2 (peeled behind 0), 3 back 2 (peeled behind 1), and a probe
    // front 3 (peeled behind 2) that tells whether the mesh needs more than two intervals (then layer 3 is
    // redrawn as the farthest back face, below).
    for (int layer = 0; layer < 5; ++layer) {
        bool front = layer % 2 == 0;
        const float clearDepth = 1.0f;
        const float clearColor[4] = {front ? kInfinity : -kInfinity, 0, 0, 0}, noNormal[4] = {0, 0, 0, 0};
        glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, 0, clearColor);
        glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, 1, noNormal);
        glClearNamedFramebufferfv(framebuffer_.name(), GL_DEPTH, 0, &clearDepth);
        glCullFace(front ? GL_BACK : GL_FRONT);
        depthProgram_.set("peelAgainst", layer >= 2 ? base + layer - 2 : -1);
        glDrawArrays(GL_TRIANGLES, 0, m.vertexCount);
        if (layer == 2) m.intervals = anyFinite(scratch_.name(), depth) ? 2 : 1;
        if (layer == 4) {
            m.deeperThanTwoIntervals = anyFinite(scratch_.name(), depth);
            if (m.deeperThanTwoIntervals) {
                log::warn("clip mesh \"" + m.name + "\" has more than two depth intervals seen from its clipping camera "
                          "(local +z); beyond the second it clips like its hull (CAO section 3.4, step II)");
                // Back 2 becomes the farthest back face, so interval 2 runs from front 2 to the mesh's last
                // exit: the third and later intervals (and the gaps between them) are clipped, as the hull would
                // clip them, instead of being left as holes. Pixels with two intervals keep their back 2 (it
                // is their farthest back face); pixels with one have no front 2, so no interval 2.
                const float farthestClear = 0.0f, backClear[4] = {-kInfinity, 0, 0, 0}, noNormal[4] = {0, 0, 0, 0};
                glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, 0, backClear);
                glClearNamedFramebufferfv(framebuffer_.name(), GL_COLOR, 1, noNormal);
                glClearNamedFramebufferfv(framebuffer_.name(), GL_DEPTH, 0, &farthestClear);
                glDepthFunc(GL_GREATER);
                glCullFace(GL_FRONT);
                depthProgram_.set("peelAgainst", -1);
                glDrawArrays(GL_TRIANGLES, 0, m.vertexCount);
                glDepthFunc(GL_LESS);
                copyLayer(base + 3);
            }
            break;
        }
        copyLayer(base + layer);
    }
    glDisable(GL_CULL_FACE);
    glDisable(GL_DEPTH_TEST);
    glFrontFace(GL_CCW);
    glBindFramebuffer(GL_FRAMEBUFFER, 0);
}

void ClipMeshSet::dilateMaps(int index) {
    const Mesh& m = meshes_[static_cast<std::size_t>(index)];
    const int base = layersPerMesh * index;
    gl::Program& p = dilationProgram_;
    p.set("resolution", mapResolution_);
    p.set("radiusMm", static_cast<float>(kernelRadiusMm(index)));
    p.set("pixelMm", static_cast<float>(m.camera.pixelMm()));
    glm::uvec3 items(static_cast<unsigned>(mapResolution_), static_cast<unsigned>(mapResolution_), 1u);
    for (int layer = 0; layer < layersPerMesh; ++layer) {
        p.set("backMap", layer % 2 == 1 ? 1 : 0);
        if (layer >= 2 * m.intervals) {
            const float empty = layer % 2 == 0 ? kInfinity : -kInfinity;
            glClearTexSubImage(dilatedMaps_.name(), 0, 0, 0, base + layer, mapResolution_, mapResolution_, 1, GL_RED, GL_FLOAT, &empty);
            continue;
        }
        // The depth reduced to the dilated maps' pixels, then pass 1 along x into the scratch array and pass 2
        // along y into the dilated array.
        gl::Program& reduce = reduceProgram_;
        reduce.set("resolution", mapResolution_);
        reduce.set("depthResolution", settings_.depthResolution);
        reduce.set("depthOffset", glm::vec2(m.camera.depthOffset()));
        reduce.set("depthScale", static_cast<float>(m.camera.depthScale()));
        reduce.set("backMap", layer % 2 == 1 ? 1 : 0);
        reduce.set("sourceLayer", base + layer);
        glBindTextureUnit(binding::clipDepth, depthMaps_.name());
        glBindImageTexture(binding::imageDilation, reducedArray_.name(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        reduce.dispatchCovering(items);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindTextureUnit(binding::clipDepth, reducedArray_.name());
        glBindImageTexture(binding::imageDilation, scratchArray_.name(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        p.set("sourceLayer", 0);
        p.set("destinationLayer", 0);
        p.set("direction", glm::ivec2(1, 0));
        p.dispatchCovering(items);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
        glBindTextureUnit(binding::clipDepth, scratchArray_.name());
        glBindImageTexture(binding::imageDilation, dilatedMaps_.name(), 0, GL_TRUE, 0, GL_WRITE_ONLY, GL_R32F);
        p.set("sourceLayer", 0);
        p.set("destinationLayer", base + layer);
        p.set("direction", glm::ivec2(0, 1));
        p.dispatchCovering(items);
        glMemoryBarrier(GL_TEXTURE_FETCH_BARRIER_BIT | GL_SHADER_IMAGE_ACCESS_BARRIER_BIT);
    }
}

void ClipMeshSet::mapBoxLocal(int index, glm::dvec3& lo, glm::dvec3& hi) const {
    const ClippingCamera& c = camera(index);
    lo = glm::dvec3(c.mapOrigin, c.localMin.z - c.marginMm);
    hi = glm::dvec3(c.mapOrigin + c.mapSizeMm, c.localMax.z + c.marginMm);
}

double ClipMeshSet::mapBoxSlackMm(int index) const {
    // A thousandth of the box's size, far above float rounding of the map transform, so no point a map could
    // call inside is ever taken for far.
    glm::dvec3 lo, hi;
    mapBoxLocal(index, lo, hi);
    return 1e-3 * glm::length(hi - lo) + 1e-3;
}

void ClipMeshSet::dilatedBoxLocal(int index, glm::dvec3& lo, glm::dvec3& hi) const {
    // Where a map lookup (clip_test.glsl insideMeshMaps, nearest pixel) can answer "inside":
    //  - a depth map pixel is finite only where rasterising the mesh covered its centre, so that centre lies
    //    in the mesh's local x, y bounds; its values are local depths in [localMin.z, localMax.z];
    //  - a reduced pixel (clip_reduce.comp: a dilated-map pixel's square widened by a depth pixel d) is finite
    //    only where that widened square meets a finite depth pixel, so its centre lies within px/2 + 1.5 d of
    //    the bounds along x and y;
    //  - a dilated pixel is finite only within floor(K / px) pixels along x and along y of a finite reduced
    //    pixel (dilation.comp's two passes, K = kernelRadiusMm), and its value moves the depth by at most
    //    k(0, 0) = 2 (K - K/2) = K;
    //  - a point is looked up in the pixel holding it, at most half a pixel from that pixel's centre.
    // So every point either map calls inside lies within K + px + 1.5 d of the bounds across the map (2 d
    // below) and within K along the depth; the map box's float slack (mapBoxSlackMm) is added for rounding.
    const ClippingCamera& c = camera(index);
    double k = kernelRadiusMm(index), slack = mapBoxSlackMm(index);
    const double across = k + c.pixelMm() + 2.0 * c.depthPixelMm() + slack;
    glm::dvec3 grow(across, across, k + slack);
    lo = c.localMin - grow;
    hi = c.localMax + grow;
}

void ClipMeshSet::depthBoxLocal(int index, glm::dvec3& lo, glm::dvec3& hi) const {
    // As dilatedBoxLocal without the dilation: a finite depth pixel's centre lies in the mesh's local x, y
    // bounds and its values in its z bounds, and a point is looked up in the depth pixel holding it. A whole
    // depth pixel instead of half, the float slack and depthBoxMarginMm on top.
    const ClippingCamera& c = camera(index);
    double pixel = c.depthPixelMm();
    double slack = mapBoxSlackMm(index) + depthBoxMarginMm;
    glm::dvec3 grow(pixel + slack, pixel + slack, slack);
    lo = c.localMin - grow;
    hi = c.localMax + grow;
}

ClipMeshSet::Ball ClipMeshSet::depthBallLocal(int index) const {
    // A point the depth maps call inside lies in a pixel whose centre's ray meets the mesh there, so within half
    // a pixel's diagonal (across the map) of a point of the mesh's hull, which lies within hullRadiusMm of the
    // bounds' centre. The depth box's growth across the map (a whole pixel, the slack and the margin) covers the
    // half diagonal.
    glm::dvec3 lo, hi;
    depthBoxLocal(index, lo, hi);
    return hullBallGrownAs(index, hi);
}

ClipMeshSet::Ball ClipMeshSet::reachBallLocal(int index) const {
    // Every point within R of a point the depth maps call inside lies within hullRadiusMm + d / sqrt(2) + R of
    // the centre (depthBallLocal, d the depth pixel). The dilated box's growth across the map, K + px + 2 d +
    // slack with K = R + sqrt(2) px + rounding (kernelRadiusMm), is more than d / sqrt(2) + R.
    glm::dvec3 lo, hi;
    dilatedBoxLocal(index, lo, hi);
    return hullBallGrownAs(index, hi);
}

ClipMeshSet::Ball ClipMeshSet::hullBallGrownAs(int index, glm::dvec3 boxHi) const {
    // A box's growth across the map is the same along x and y (depthBoxLocal, dilatedBoxLocal).
    const ClippingCamera& c = camera(index);
    return {0.5 * (c.localMin + c.localMax), c.hullRadiusMm + (boxHi.x - c.localMax.x)};
}

ClipMeshSet::WorldBox ClipMeshSet::mapBoxWorldBounds(int index) const {
    glm::dvec3 lo, hi;
    mapBoxLocal(index, lo, hi);
    glm::dmat4 toWorld = pose(index).matrix();
    WorldBox box{glm::dvec3(std::numeric_limits<double>::infinity()), glm::dvec3(-std::numeric_limits<double>::infinity())};
    for (int corner = 0; corner < 8; ++corner) {
        glm::dvec3 local((corner & 1) ? hi.x : lo.x, (corner & 2) ? hi.y : lo.y, (corner & 4) ? hi.z : lo.z);
        glm::dvec3 world(toWorld * glm::dvec4(local, 1.0));
        box.min = glm::min(box.min, world);
        box.max = glm::max(box.max, world);
    }
    return box;
}

void ClipMeshSet::uploadCameras() {
    if (!cameraBuffer_) {
        cameraBuffer_ = gl::createBuffer();
        glNamedBufferStorage(cameraBuffer_.name(), maxMeshes * sizeof(CameraGpu), nullptr, GL_DYNAMIC_STORAGE_BIT);
    }
    std::vector<CameraGpu> cameras(meshes_.size());
    for (std::size_t i = 0; i < meshes_.size(); ++i) {
        glm::mat4 m(meshes_[i].camera.worldToMap(meshes_[i].pose));
        std::memcpy(cameras[i].worldToMap, &m[0][0], sizeof cameras[i].worldToMap);
        cameras[i].info[0] = static_cast<std::int32_t>(layersPerMesh * i);
        cameras[i].info[1] = meshes_[i].intervals;
        cameras[i].info[2] = mapResolution_;
        cameras[i].info[3] = meshes_[i].clipsTubes ? 1 : 0;
        // The map box (x, y across the map, z over the depth range plus margin) and its slack (mapBoxSlackMm).
        glm::dvec3 lo, hi;
        mapBoxLocal(static_cast<int>(i), lo, hi);
        cameras[i].mapBox[0] = static_cast<float>(meshes_[i].camera.mapSizeMm);
        cameras[i].mapBox[1] = static_cast<float>(lo.z);
        cameras[i].mapBox[2] = static_cast<float>(hi.z);
        cameras[i].mapBox[3] = static_cast<float>(mapBoxSlackMm(static_cast<int>(i)));
        // The depth box in map coordinates (x, y over the map side, z the local depth).
        depthBoxLocal(static_cast<int>(i), lo, hi);
        glm::dmat4 localToMap = meshes_[i].camera.localToMap();
        glm::dvec3 mapLo(localToMap * glm::dvec4(lo, 1.0)), mapHi(localToMap * glm::dvec4(hi, 1.0));
        for (int k = 0; k < 3; ++k) {
            cameras[i].depthBoxLo[k] = static_cast<float>(mapLo[k]);
            cameras[i].depthBoxHi[k] = static_cast<float>(mapHi[k]);
        }
        cameras[i].depthBoxLo[3] = cameras[i].depthBoxHi[3] = 0.0f;
        // The depth ball (depthBallLocal) in world millimetres.
        Ball ball = depthBallLocal(static_cast<int>(i));
        glm::dvec3 centre(meshes_[i].pose.matrix() * glm::dvec4(ball.centre, 1.0));
        for (int k = 0; k < 3; ++k) cameras[i].depthBall[k] = static_cast<float>(centre[k]);
        cameras[i].depthBall[3] = static_cast<float>(ball.radius);
        const ClippingCamera& c = meshes_[i].camera;
        cameras[i].depthMap[0] = static_cast<float>(c.depthOffset().x);
        cameras[i].depthMap[1] = static_cast<float>(c.depthOffset().y);
        cameras[i].depthMap[2] = static_cast<float>(c.depthScale());
        cameras[i].depthMap[3] = static_cast<float>(c.depthResolution);
    }
    if (!cameras.empty())
        glNamedBufferSubData(cameraBuffer_.name(), 0, static_cast<GLsizeiptr>(cameras.size() * sizeof(CameraGpu)), cameras.data());
}

void ClipMeshSet::addDefines(gl::Defines& defines) const {
    if (meshes_.empty()) defines.emplace_back("NO_CLIP_MESHES", "1");
}

void ClipMeshSet::apply(gl::Program& program) const {
    program.set("clipMeshCount", count());
    program.set("clipDepthBoxTests", depthBoxTests_ ? 1 : 0);
    glBindBufferBase(GL_UNIFORM_BUFFER, binding::uboClipMeshes, cameraBuffer_.name());
    glBindTextureUnit(binding::clipDepth, depthMaps_.name());
    glBindTextureUnit(binding::clipDilated, dilatedAllocated_ ? dilatedMaps_.name() : depthMaps_.name());
    glBindTextureUnit(binding::clipNormals, normalMaps_.name());
}

const DepthIntervalPyramid& ClipMeshSet::depthIntervals(int index) const {
    const Mesh& m = meshes_[static_cast<std::size_t>(index)];
    if (!m.intervalsRead) {
        std::vector<std::vector<float>> fronts, backs;
        for (int j = 0; j < m.intervals; ++j) {
            fronts.push_back(readMap(index, 2 * j, false));
            backs.push_back(readMap(index, 2 * j + 1, false));
        }
        m.intervalsRead = std::make_shared<const DepthIntervalPyramid>(settings_.depthResolution, fronts, backs);
    }
    return *m.intervalsRead;
}

std::vector<float> ClipMeshSet::readMap(int index, int layer, bool dilated) const {
    const int side = dilated ? mapResolution_ : settings_.depthResolution;
    std::vector<float> values(static_cast<std::size_t>(side) * static_cast<std::size_t>(side));
    glMemoryBarrier(GL_TEXTURE_UPDATE_BARRIER_BIT);  // the dilated maps are written by image stores
    glGetTextureSubImage(dilated ? dilatedMaps_.name() : depthMaps_.name(), 0, 0, 0, layersPerMesh * index + layer,
                         side, side, 1, GL_RED, GL_FLOAT, static_cast<GLsizei>(values.size() * sizeof(float)), values.data());
    return values;
}

std::size_t ClipMeshSet::gpuBytes() const {
    const std::size_t layer = static_cast<std::size_t>(resolution_) * static_cast<std::size_t>(resolution_) * 4u;
    const std::size_t depthLayer = static_cast<std::size_t>(settings_.depthResolution) * static_cast<std::size_t>(settings_.depthResolution) * 4u;
    // The depth, normal (4 bytes a pixel too) and dilated arrays, the two single-layer arrays, and the render
    // target (depth, normal) with its depth buffer.
    return (2u * depthLayer + (dilatedAllocated_ ? layer : 0u)) * static_cast<std::size_t>(allocatedLayers_) + 2u * layer + 3u * depthLayer;
}

}  // namespace curette::clip
