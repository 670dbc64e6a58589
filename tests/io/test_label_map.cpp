// Label maps (base/label_map.h): volumes read by io::readVolume become integer ids (the mricron atlases as
// Debian ships them, mricron-data), non-integer volumes are refused naming the voxel, and nearest-label
// resampling keeps ids exact (identity, a 90-degree turn) and structures in place (JHU onto the ch2 grid).
#include "io/label_table.h"
#include "io/volume_file.h"
#include "base/error.h"
#include "base/label_map.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <random>
#include <set>

namespace curette {
namespace {

const std::filesystem::path& kTemplates = test::kMricronTemplates;


VolumeData floatVolume(glm::ivec3 dims, const std::vector<float>& values) {
    return buildVolume("made-up.nii", dims, ScalarType::Float32, reinterpret_cast<const std::uint8_t*>(values.data()), false, 1.0, 0.0,
                       glm::dmat4(1.0));
}

// World-space centroid of each label's voxels.
std::map<int, glm::dvec3> centroids(const LabelMap& map, const std::set<int>& labels) {
    std::map<int, glm::dvec3> sum;
    std::map<int, double> count;
    for (int k = 0; k < map.dims.z; ++k)
        for (int j = 0; j < map.dims.y; ++j)
            for (int i = 0; i < map.dims.x; ++i) {
                int id = map.id(i, j, k);
                if (!labels.count(id)) continue;
                sum[id] += glm::dvec3(map.indexToWorld * glm::dvec4(i, j, k, 1.0));
                count[id] += 1.0;
            }
    for (auto& [id, s] : sum) s /= count[id];
    return sum;
}

LabelMap randomLabels(glm::ivec3 dims, const glm::dmat4& affine, unsigned seed) {
    LabelMap map;
    map.dims = dims;
    map.indexToWorld = affine;
    map.ids.resize(map.voxelCount());
    std::mt19937 random(seed);
    std::uniform_int_distribution<int> id(0, 65535);
    for (std::uint16_t& v : map.ids) v = static_cast<std::uint16_t>(id(random));
    return map;
}

TEST(LabelMap, AalHas116LabelsAndEveryOneIsInItsTable) {
    SKIP_WITHOUT_MRICRON("aal.nii.gz");
    LabelMap map = labelMapFromVolume(io::readVolume(kTemplates / "aal.nii.gz"));
    EXPECT_EQ(map.dims, glm::ivec3(181, 217, 181));
    EXPECT_EQ(*std::max_element(map.ids.begin(), map.ids.end()), 116);
    LabelTable table = io::readLabelTable(kTemplates / "aal.nii.txt");
    std::set<int> inVolume(map.ids.begin(), map.ids.end());
    inVolume.erase(0);
    std::set<int> inTable;
    for (const LabelEntry& e : table.entries) inTable.insert(e.id);
    EXPECT_EQ(inVolume, inTable);
    // Voxel centre -> world as the volume: (90, 126, 72) is the AC in the MNI grid's millimetres, (0, 1, 1).
    glm::dvec3 world(map.indexToWorld * glm::dvec4(90, 126, 72, 1.0));
    EXPECT_EQ(world, glm::dvec3(0, 1, 1));
}

TEST(LabelMap, NonIntegerVolumeIsRefusedNamingTheVoxel) {
    glm::ivec3 dims(3, 4, 5);
    std::vector<float> values(60, 2.0f);
    values[static_cast<std::size_t>(1 + 3 * (2 + 4 * 3))] = 2.5f;  // voxel (1, 2, 3)
    try {
        labelMapFromVolume(floatVolume(dims, values));
        ADD_FAILURE() << "a voxel of 2.5 was taken as a label";
    } catch (const InputError& e) {
        EXPECT_EQ(e.file(), "made-up.nii");
        EXPECT_EQ(e.field(), "voxel (1, 2, 3)");
        EXPECT_EQ(e.expected(), "integer label ids 0..65535");
        EXPECT_EQ(e.got(), "2.5");
    }
    values.assign(60, 1.0f);
    values[0] = -1.0f;
    test::expectInputError([&] { labelMapFromVolume(floatVolume(dims, values)); }, "made-up.nii", "voxel (0, 0, 0)");
    values[0] = 65536.0f;
    test::expectInputError([&] { labelMapFromVolume(floatVolume(dims, values)); }, "made-up.nii", "voxel (0, 0, 0)");
}

TEST(LabelMap, IntegersWithinToleranceAndNoDataAreAccepted) {
    std::vector<float> values = {3.0004f, 65535.0f, std::numeric_limits<float>::quiet_NaN(), 6.9995f};
    LabelMap map = labelMapFromVolume(floatVolume({4, 1, 1}, values));
    EXPECT_EQ(map.ids, (std::vector<std::uint16_t>{3, 65535, 0, 7}));
    // uint16 with a slope: stored 0..100 times 2 -> ids 0..200; the table path for UNorm16.
    std::vector<std::uint16_t> stored = {0, 1, 50, 100};
    VolumeData scaled = buildVolume("scaled.nii", {4, 1, 1}, ScalarType::UInt16, reinterpret_cast<const std::uint8_t*>(stored.data()), false,
                                    2.0, 0.0, glm::dmat4(1.0));
    EXPECT_EQ(labelMapFromVolume(scaled).ids, (std::vector<std::uint16_t>{0, 2, 100, 200}));
    // A slope of 0.5 makes odd stored values half-integers: refused, at the first one.
    VolumeData halves = buildVolume("halves.nii", {4, 1, 1}, ScalarType::UInt16, reinterpret_cast<const std::uint8_t*>(stored.data()), false,
                                    0.5, 0.0, glm::dmat4(1.0));
    test::expectInputError([&] { labelMapFromVolume(halves); }, "halves.nii", "voxel (1, 0, 0)");
}

TEST(LabelMap, ResamplingOntoTheSameGridIsTheIdentity) {
    glm::dmat4 oblique = glm::translate(glm::dmat4(1.0), glm::dvec3(-91.3, 12.25, 40.0)) *
                         glm::rotate(glm::dmat4(1.0), 0.37, glm::normalize(glm::dvec3(1, 2, 3))) *
                         glm::scale(glm::dmat4(1.0), glm::dvec3(0.9, 1.1, 2.7));
    LabelMap source = randomLabels({23, 17, 11}, oblique, 7);
    LabelMap same = resampleNearest(source, source.dims, source.indexToWorld);
    EXPECT_EQ(same.ids, source.ids);
    EXPECT_EQ(same.indexToWorld, source.indexToWorld);
}

TEST(LabelMap, AalResampledOntoItsOwnGridIsTheIdentity) {
    SKIP_WITHOUT_MRICRON("aal.nii.gz");
    LabelMap aal = labelMapFromVolume(io::readVolume(kTemplates / "aal.nii.gz"));
    EXPECT_TRUE(resampleNearest(aal, aal.dims, aal.indexToWorld).ids == aal.ids);
}

TEST(LabelMap, GridTurnedBy90DegreesMapsIdsExactly) {
    // Source voxel size 0.8 x 1.5 x 2 mm at an offset. The target grid is the same voxels with the i and j
    // axes turned by 90 degrees about z: target (i, j, k) is source (nx - 1 - j, i, k), so the target has
    // dims (ny, nx, nz) and affine A * P.
    glm::ivec3 dims(9, 6, 4);
    glm::dmat4 a = glm::translate(glm::dmat4(1.0), glm::dvec3(10, -20, 5)) * glm::scale(glm::dmat4(1.0), glm::dvec3(0.8, 1.5, 2.0));
    LabelMap source = randomLabels(dims, a, 11);
    glm::dmat4 p(glm::dvec4(0, 1, 0, 0), glm::dvec4(-1, 0, 0, 0), glm::dvec4(0, 0, 1, 0), glm::dvec4(dims.x - 1, 0, 0, 1));
    glm::ivec3 turnedDims(dims.y, dims.x, dims.z);
    LabelMap turned = resampleNearest(source, turnedDims, a * p);
    for (int k = 0; k < turnedDims.z; ++k)
        for (int j = 0; j < turnedDims.y; ++j)
            for (int i = 0; i < turnedDims.x; ++i)
                ASSERT_EQ(turned.id(i, j, k), source.id(dims.x - 1 - j, i, k)) << i << " " << j << " " << k;
    // And back: the turn undone gives the source.
    EXPECT_EQ(resampleNearest(turned, dims, a).ids, source.ids);
}

TEST(LabelMap, OutsideTheSourceIsZeroAndHalfVoxelsRoundToTheNearestCentre) {
    LabelMap source;
    source.dims = {3, 1, 1};
    source.ids = {5, 6, 7};
    source.indexToWorld = glm::dmat4(1.0);
    // A target of 0.5 mm voxels from -1 to 3: centres -1 and -0.75 are outside, -0.5 .. 0.49 are voxel 0,
    // 0.5 is voxel 1 (half up), 2.25 is voxel 2, 2.5 and beyond are outside.
    glm::dmat4 fine = glm::translate(glm::dmat4(1.0), glm::dvec3(-1, 0, 0)) * glm::scale(glm::dmat4(1.0), glm::dvec3(0.25, 1, 1));
    LabelMap target = resampleNearest(source, {17, 1, 1}, fine);
    std::vector<std::uint16_t> expected = {0, 0, 5, 5, 5, 5, 6, 6, 6, 6, 7, 7, 7, 7, 0, 0, 0};
    EXPECT_EQ(target.ids, expected);
}

TEST(LabelMap, JhuOnTheCh2GridKeepsEachStructureInPlace) {
    SKIP_WITHOUT_MRICRON("JHU-WhiteMatter-labels-1mm.nii.gz");
    SKIP_WITHOUT_MRICRON("ch2.nii.gz");
    LabelMap jhu = labelMapFromVolume(io::readVolume(kTemplates / "JHU-WhiteMatter-labels-1mm.nii.gz"));
    VolumeData ch2 = io::readVolume(kTemplates / "ch2.nii.gz");
    ASSERT_NE(jhu.dims, ch2.dims);  // a different grid (182 x 218 x 182 against 181 x 217 x 181)
    LabelMap onCh2 = resampleNearest(jhu, ch2.dims, ch2.indexToWorld);
    EXPECT_EQ(onCh2.dims, ch2.dims);
    // Genu, body and splenium of the corpus callosum, the middle cerebellar peduncle, a left/right pair.
    std::set<int> labels = {1, 3, 4, 5, 47, 48};
    std::map<int, glm::dvec3> before = centroids(jhu, labels), after = centroids(onCh2, labels);
    for (int id : labels) {
        ASSERT_TRUE(before.count(id) && after.count(id)) << "label " << id;
        EXPECT_LT(glm::length(after[id] - before[id]), 1.0) << "label " << id;
    }
    std::set<int> idsBefore(jhu.ids.begin(), jhu.ids.end()), idsAfter(onCh2.ids.begin(), onCh2.ids.end());
    EXPECT_TRUE(std::includes(idsBefore.begin(), idsBefore.end(), idsAfter.begin(), idsAfter.end()));  // no new ids
}

}  // namespace
}  // namespace curette
