#include "render/model/slice_view.h"

#include "plan/distance_transform.h"
#include "render/model/volume_geometry.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace curette {

namespace {

// The image axes of each view (the display orientation in slice_view.h): right, down and the plane's normal.
struct ViewAxes {
    glm::dvec3 right, down, normal;
};
ViewAxes viewAxes(SliceAxis axis) {
    switch (axis) {
        case SliceAxis::Axial: return {{-1, 0, 0}, {0, -1, 0}, {0, 0, 1}};     // Left right, anterior up
        case SliceAxis::Coronal: return {{-1, 0, 0}, {0, 0, -1}, {0, 1, 0}};   // Left right, superior up
        case SliceAxis::Sagittal: return {{0, -1, 0}, {0, 0, -1}, {1, 0, 0}};  // anterior left, superior up
    }
    return {};
}

// The patient-axis letter of a world direction along one RAS axis.
char directionLetter(glm::dvec3 d) {
    if (d.x > 0.5) return 'R';
    if (d.x < -0.5) return 'L';
    if (d.y > 0.5) return 'A';
    if (d.y < -0.5) return 'P';
    if (d.z > 0.5) return 'S';
    return 'I';
}

// 5x7 glyphs of the six letters, one byte a row, bit 4 the leftmost column.
const std::uint8_t* glyph(char letter) {
    static const std::uint8_t a[7] = {0x0E, 0x11, 0x11, 0x1F, 0x11, 0x11, 0x11};
    static const std::uint8_t p[7] = {0x1E, 0x11, 0x11, 0x1E, 0x10, 0x10, 0x10};
    static const std::uint8_t l[7] = {0x10, 0x10, 0x10, 0x10, 0x10, 0x10, 0x1F};
    static const std::uint8_t r[7] = {0x1E, 0x11, 0x11, 0x1E, 0x14, 0x12, 0x11};
    static const std::uint8_t s[7] = {0x0F, 0x10, 0x10, 0x0E, 0x01, 0x01, 0x1E};
    static const std::uint8_t i[7] = {0x0E, 0x04, 0x04, 0x04, 0x04, 0x04, 0x0E};
    switch (letter) {
        case 'A': return a;
        case 'P': return p;
        case 'L': return l;
        case 'R': return r;
        case 'S': return s;
        default: return i;
    }
}

// Straight-alpha `rgb` at `alpha` over an opaque pixel.
void blend(Image& image, int x, int y, glm::vec3 rgb, float alpha) {
    if (x < 0 || y < 0 || x >= image.width || y >= image.height) return;
    glm::vec4& p = image.at(x, y);
    p = glm::vec4(glm::mix(glm::vec3(p), rgb, alpha), 1.0f);
}

void drawLetter(Image& image, char letter, int x0, int y0) {
    const std::uint8_t* rows = glyph(letter);
    for (int y = 0; y < 7; ++y)
        for (int x = 0; x < 5; ++x)
            if (rows[y] & (0x10 >> x)) blend(image, x0 + x, y0 + y, kLetterColor, 1.0f);
}

// A 1-pixel line between two points in pixel coordinates: every pixel the segment passes, sampled at most a
// quarter pixel apart.
void drawSegment(Image& image, glm::dvec2 a, glm::dvec2 b, glm::vec3 rgb) {
    double length = glm::length(b - a);
    int steps = std::max(1, static_cast<int>(std::ceil(length * 4.0)));
    if (steps > 4 * (image.width + image.height) * 4) return;   // far outside: nothing of it is in view
    for (int s = 0; s <= steps; ++s) {
        glm::dvec2 p = glm::mix(a, b, static_cast<double>(s) / steps);
        blend(image, static_cast<int>(std::floor(p.x)), static_cast<int>(std::floor(p.y)), rgb, 1.0f);
    }
}

}  // namespace

const char* sliceAxisName(SliceAxis axis) {
    switch (axis) {
        case SliceAxis::Axial: return "axial";
        case SliceAxis::Coronal: return "coronal";
        case SliceAxis::Sagittal: return "sagittal";
    }
    return "?";
}

SlicePlane slicePlane(glm::ivec3 dims, const glm::dmat4& indexToWorld, SliceAxis axis, glm::dvec3 crosshair) {
    const ViewAxes axes = viewAxes(axis);
    const glm::dvec3 spacing = plan::gridSpacingMm(indexToWorld);
    SlicePlane plane;
    plane.axis = axis;
    plane.pixelMm = std::min({spacing.x, spacing.y, spacing.z});
    plane.right = axes.right;
    plane.down = axes.down;
    plane.normal = axes.normal;
    double lo[2] = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
    double hi[2] = {-lo[0], -lo[1]};
    for (const glm::dvec3& world : VolumeGeometry{dims, indexToWorld}.worldCorners()) {   // the voxels' outer corners
        double u = glm::dot(world, axes.right), v = glm::dot(world, axes.down);
        lo[0] = std::min(lo[0], u), hi[0] = std::max(hi[0], u);
        lo[1] = std::min(lo[1], v), hi[1] = std::max(hi[1], v);
    }
    plane.sizePx = glm::ivec2(std::max(1, static_cast<int>(std::ceil((hi[0] - lo[0]) / plane.pixelMm - 1e-9))),
                              std::max(1, static_cast<int>(std::ceil((hi[1] - lo[1]) / plane.pixelMm - 1e-9))));
    plane.topLeft = lo[0] * axes.right + lo[1] * axes.down + glm::dot(crosshair, axes.normal) * axes.normal;
    return plane;
}

namespace {

double sampleTrilinear(const VolumeData& volume, const glm::dmat4& worldToIndex, glm::dvec3 world) {
    const double nan = std::numeric_limits<double>::quiet_NaN();
    glm::dvec3 index = glm::dvec3(worldToIndex * glm::dvec4(world, 1.0));
    const glm::dvec3 dims(volume.dims);
    if (glm::any(glm::lessThan(index, glm::dvec3(-0.5))) || glm::any(glm::greaterThan(index, dims - 0.5))) return nan;
    glm::dvec3 base = glm::floor(index), f = index - base;
    double sum = 0;
    for (int c = 0; c < 8; ++c) {
        glm::ivec3 o(c & 1, (c >> 1) & 1, (c >> 2) & 1);
        double w = (o.x ? f.x : 1 - f.x) * (o.y ? f.y : 1 - f.y) * (o.z ? f.z : 1 - f.z);
        if (w == 0) continue;
        glm::ivec3 v = glm::clamp(glm::ivec3(base) + o, glm::ivec3(0), volume.dims - 1);
        double value = volume.value(v.x, v.y, v.z);
        if (std::isnan(value)) return nan;
        sum += w * value;
    }
    return sum;
}

}  // namespace

std::optional<glm::ivec3> nearestVoxel(glm::ivec3 dims, const glm::dmat4& worldToIndex, glm::dvec3 world) {
    glm::dvec3 index = glm::dvec3(worldToIndex * glm::dvec4(world, 1.0));
    glm::ivec3 v(glm::floor(index + 0.5));
    if (glm::any(glm::lessThan(v, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(v, dims))) return std::nullopt;
    return v;
}

SliceLabelSet sliceLabelSet(const LabelMap& onScanGrid, const LabelTable& table, const std::vector<bool>& shownById,
                            const std::vector<int>& protectedIds) {
    SliceLabelSet set;
    set.labels = &onScanGrid;
    int largest = 0;
    for (const LabelEntry& e : table.entries) largest = std::max(largest, e.id);
    for (int id : protectedIds) largest = std::max(largest, id);
    set.outlineById.assign(static_cast<std::size_t>(largest) + 1, glm::vec4(0.0f));
    for (const LabelEntry& e : table.entries)
        if (e.id > 0 && static_cast<std::size_t>(e.id) < shownById.size() && shownById[static_cast<std::size_t>(e.id)])
            set.outlineById[static_cast<std::size_t>(e.id)] = glm::vec4(glm::vec3(e.rgba), 1.0f);
    for (int id : protectedIds)
        if (id > 0) set.outlineById[static_cast<std::size_t>(id)] = glm::vec4(kProtectedColor, 1.0f);
    return set;
}

std::vector<std::pair<glm::dvec3, glm::dvec3>> meshCrossSection(const plan::PosedMesh& mesh, const SlicePlane& plane) {
    std::vector<std::pair<glm::dvec3, glm::dvec3>> segments;
    if (!mesh.geometry) return segments;
    const std::vector<glm::dvec3> world = mesh.worldVertices();
    std::vector<double> offset(world.size());
    for (std::size_t i = 0; i < world.size(); ++i) offset[i] = plane.offsetMm(world[i]);
    // A vertex exactly on the plane counts as above it, so each crossing triangle has exactly two crossing edges.
    for (const glm::uvec3& t : mesh.geometry->triangles) {
        glm::dvec3 points[2];
        int n = 0;
        for (int e = 0; e < 3; ++e) {
            unsigned a = t[e], b = t[(e + 1) % 3];
            bool aAbove = offset[a] >= 0, bAbove = offset[b] >= 0;
            if (aAbove == bAbove) continue;
            double s = offset[a] / (offset[a] - offset[b]);
            if (n < 2) points[n] = world[a] + s * (world[b] - world[a]);
            ++n;
        }
        if (n == 2) segments.emplace_back(points[0], points[1]);
    }
    return segments;
}

SliceImage renderSlice(const VolumeData& volume, SliceAxis axis, glm::dvec3 crosshair, GreyWindow window, const SliceOverlays& overlays) {
    SliceImage slice;
    slice.plane = slicePlane(volume.dims, volume.indexToWorld, axis, crosshair);
    slice.crosshair = crosshair;
    slice.window = window;
    const SlicePlane& plane = slice.plane;
    const int w = plane.sizePx.x, h = plane.sizePx.y;
    Image& image = slice.image;
    image.width = w;
    image.height = h;
    image.pixels.assign(static_cast<std::size_t>(w) * static_cast<std::size_t>(h), glm::vec4(0, 0, 0, 1));
    const glm::dmat4 worldToIndex = glm::inverse(volume.indexToWorld);
    const double span = window.hi > window.lo ? window.hi - window.lo : 1.0;

    // The voxel nearest each pixel centre (-1 outside the grid): what the overlays read.
    std::vector<std::int64_t> voxelOf(image.pixels.size(), -1);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            glm::dvec3 world = plane.worldAt({x + 0.5, y + 0.5});
            std::size_t p = static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x);
            double value = sampleTrilinear(volume, worldToIndex, world);
            if (!std::isnan(value)) image.pixels[p] = glm::vec4(glm::vec3(static_cast<float>(std::clamp((value - window.lo) / span, 0.0, 1.0))), 1.0f);
            if (auto v = nearestVoxel(volume.dims, worldToIndex, world))
                voxelOf[p] = static_cast<std::int64_t>(volume.linearIndex(v->x, v->y, v->z));
        }
    // Draws a per-pixel key's outline: pixels whose key is drawn and differs from a 4-neighbour's (the image's
    // edge is no neighbour).
    auto outline = [&](const std::vector<int>& key, auto colorOf) {
        for (int y = 0; y < h; ++y)
            for (int x = 0; x < w; ++x) {
                int k = key[static_cast<std::size_t>(y) * static_cast<std::size_t>(w) + static_cast<std::size_t>(x)];
                glm::vec4 color = colorOf(k);
                if (color.a <= 0) continue;
                auto other = [&](int nx, int ny) {
                    return nx >= 0 && ny >= 0 && nx < w && ny < h &&
                           key[static_cast<std::size_t>(ny) * static_cast<std::size_t>(w) + static_cast<std::size_t>(nx)] != k;
                };
                if (other(x - 1, y) || other(x + 1, y) || other(x, y - 1) || other(x, y + 1)) blend(image, x, y, glm::vec3(color), color.a);
            }
    };
    std::vector<int> key(image.pixels.size());
    if (overlays.removedRegion && overlays.removedRegion->size() == volume.voxelCount()) {
        const std::vector<std::uint8_t>& removed = *overlays.removedRegion;
        for (std::size_t p = 0; p < key.size(); ++p) {
            key[p] = voxelOf[p] >= 0 && removed[static_cast<std::size_t>(voxelOf[p])] ? 1 : 0;
            if (key[p]) blend(image, static_cast<int>(p % std::size_t(w)), static_cast<int>(p / std::size_t(w)), kRemovedColor, kRemovedFillAlpha);
        }
        outline(key, [](int k) { return k ? glm::vec4(kRemovedColor, 1.0f) : glm::vec4(0.0f); });
    }
    for (const SliceLabelSet& set : overlays.labelSets) {
        if (!set.labels || set.labels->ids.size() != volume.voxelCount()) continue;
        for (std::size_t p = 0; p < key.size(); ++p) key[p] = voxelOf[p] >= 0 ? set.labels->ids[static_cast<std::size_t>(voxelOf[p])] : 0;
        outline(key, [&](int k) {
            return k > 0 && static_cast<std::size_t>(k) < set.outlineById.size() ? set.outlineById[static_cast<std::size_t>(k)] : glm::vec4(0.0f);
        });
    }
    for (const SliceMesh& m : overlays.meshes)
        for (const auto& [a, b] : meshCrossSection(m.mesh, plane))
            drawSegment(image, plane.pixelAt(a), plane.pixelAt(b), m.held ? kHeldMeshColor : kMeshColor);
    if (overlays.crosshairLines) {
        glm::dvec2 c = plane.pixelAt(crosshair);
        int cx = static_cast<int>(std::floor(c.x)), cy = static_cast<int>(std::floor(c.y));
        for (int y = 0; y < h; ++y) blend(image, cx, y, kCrosshairColor, kCrosshairAlpha);
        for (int x = 0; x < w; ++x)
            if (x != cx) blend(image, x, cy, kCrosshairColor, kCrosshairAlpha);
    }
    if (overlays.orientationLetters && w >= 16 && h >= 16) {
        drawLetter(image, directionLetter(-plane.down), w / 2 - 2, 2);
        drawLetter(image, directionLetter(plane.down), w / 2 - 2, h - 9);
        drawLetter(image, directionLetter(-plane.right), 2, h / 2 - 3);
        drawLetter(image, directionLetter(plane.right), w - 7, h / 2 - 3);
    }
    return slice;
}

}  // namespace curette
