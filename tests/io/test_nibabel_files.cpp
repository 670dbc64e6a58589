// Every NIfTI file of nibabel's test data (python3-nibabel 5.0.0's nibabel/tests/data, unpacked by
// scripts/setup into /usr/local/share/curette/nibabel-data) either reads with the shape, affine and values
// nibabel gives, or is refused with a clear message for a reason stated below.
//
// Expected numbers: nibabel 5.0.0 (Debian 12's python3-nibabel 5.0.0-2, numpy 1.24.2), computed once with
//   img = nibabel.load(f); img.shape; img.affine; d = numpy.asanyarray(img.dataobj).astype(numpy.float64)
//   d[..., t][i, j, k]; numpy.nanmin / nanmax / nansum of d[..., t]; numpy.isnan(d).sum()
// nibabel is not a test dependency: the numbers are constants here. Affines are compared to 1e-4 mm; values of
// unscaled files exactly (curette's value() of an integer or float voxel is exact), values of the one scaled
// file (functional.nii, scl_slope 0.0754...) to 1e-9 relative, because curette folds the scaling into its
// storage map in another order than nibabel's raw * slope + inter; sums of float data to 1e-12 relative
// (numpy sums pairwise).
#include "io/nifti.h"
#include "io/volume_file.h"
#include "base/error.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <set>

namespace curette {
namespace {

const std::filesystem::path kFolder = "/usr/local/share/curette/nibabel-data";

struct Voxel {
    glm::ivec3 index;
    double value;  // NaN: no data
};

struct VolumeExpectation {
    int index;
    double min, max, sum;
    std::vector<Voxel> voxels;
};

struct FileExpectation {
    const char* name;
    glm::ivec3 dims;
    int volumeCount;
    ScalarType type;
    double affine[3][4];
    bool scaled;
    std::uint64_t noData;
    std::vector<VolumeExpectation> volumes;
};

// The oblique affine of example4d.nii.gz and example_nifti2.nii.gz (the same acquisition; qform = sform).
#define EXAMPLE4D_AFFINE                                                                              \
    {{-2.0, 6.714715653593746e-19, 9.081024511081715e-18, 117.8551025390625},                         \
     {-6.714715653593746e-19, 1.9737114906311035, -0.35552823543548584, -35.72294235229492},          \
     {8.25548088896093e-18, 0.3232076168060303, 2.171081781387329, -7.248798370361328}}

const std::vector<FileExpectation>& readable() {
    static const std::vector<FileExpectation> files = {
        // Big-endian NIfTI-1, int16, sform = qform (code 2), 3-D.
        {"anatomical.nii", {33, 41, 25}, 1, ScalarType::Int16, {{-2, 0, 0, 32}, {0, 2, 0, -40}, {0, 0, 2, -16}}, false, 0,
         {{0, -610.0, 30393.0, 284166082.0, {{{0, 0, 0}, 10712.0}, {{32, 40, 24}, 2971.0}, {{16, 20, 12}, 11881.0}, {{1, 2, 24}, 9315.0}}}}},
        // NIfTI-1, 4-D (two volumes), gzipped, an extension before the data (vox_offset 416).
        {"example4d.nii.gz", {128, 96, 24}, 2, ScalarType::Int16, EXAMPLE4D_AFFINE, false, 0,
         {{0, 0.0, 1162.0, 50994397.0, {{{0, 0, 0}, 0.0}, {{127, 95, 23}, 0.0}, {{64, 48, 12}, 265.0}, {{1, 2, 23}, 0.0}}},
          {1, 0.0, 1140.0, 50990959.0, {{{0, 0, 0}, 0.0}, {{127, 95, 23}, 0.0}, {{64, 48, 12}, 266.0}, {{1, 2, 23}, 0.0}}}}},
        // NIfTI-2 ("n+2"), 4-D, gzipped, vox_offset 608.
        {"example_nifti2.nii.gz", {32, 20, 12}, 2, ScalarType::Int16, EXAMPLE4D_AFFINE, false, 0,
         {{0, 49.0, 742.0, 3461748.0, {{{0, 0, 0}, 424.0}, {{31, 19, 11}, 484.0}, {{16, 10, 6}, 265.0}, {{1, 2, 11}, 546.0}}},
          {1, 46.0, 757.0, 3465054.0, {{{0, 0, 0}, 439.0}, {{31, 19, 11}, 457.0}, {{16, 10, 6}, 266.0}, {{1, 2, 11}, 549.0}}}}},
        // NIfTI-1, 4-D (20 volumes), int16 with scl_slope 0.07540696859359741, scl_inter 3100.76171875.
        {"functional.nii", {17, 21, 3}, 20, ScalarType::Int16, {{-4, 0, 0, 32}, {0, 4, 0, -40}, {0, 0, 8, 0}}, true, 0,
         {{0, 762.5424365997314, 5538.065757632256, 3883746.552329719,
           {{{0, 0, 0}, 4004.137202501297}, {{16, 20, 2}, 3142.8388072252274}, {{8, 10, 1}, 3865.7654151320457}, {{1, 2, 2}, 3704.5453162789345}}},
          {1, 736.8286603093147, 5466.730765342712, 3884191.0010026097,
           {{{0, 0, 0}, 4039.729291677475}, {{16, 20, 2}, 3128.0590413808823}, {{8, 10, 1}, 3880.2435531020164}, {{1, 2, 2}, 3642.5607880949974}}},
          {19, 829.7300456166267, 5541.082036375999, 3888072.273083091,
           {{{0, 0, 0}, 3971.1089502573013}, {{16, 20, 2}, 3129.3409598469734}, {{8, 10, 1}, 3910.858782351017}, {{1, 2, 2}, 3626.5745107531548}}}}},
        // Big-endian float32, 3-D.
        {"reoriented_anat_moved.nii", {21, 26, 22}, 1, ScalarType::Float32,
         {{4, 0, 0, -35.29789733886719}, {0, 4, 0, -47.97758483886719}, {0, 0, 4, -27.599409103393555}}, false, 0,
         {{0, 0.0, 21199.935546875, 32739769.449157715, {{{0, 0, 0}, 0.0}, {{20, 25, 21}, 0.0}, {{10, 13, 11}, 8117.22021484375}, {{1, 2, 21}, 0.0}}}}},
        // Big-endian float32 with 153 NaN voxels outside the resampled field of view: "no data".
        {"resampled_anat_moved.nii", {17, 21, 3}, 1, ScalarType::Float32, {{-4, 0, 0, 32}, {0, 4, 0, -40}, {0, 0, 8, 0}}, false, 153,
         {{0, 409.3004455566406, 13360.9619140625, 7749957.09866333,
           {{{0, 0, 0}, NAN}, {{16, 20, 2}, NAN}, {{8, 10, 1}, 10849.904296875}, {{1, 2, 2}, 9086.7509765625}}}}},
        // uint8, 3-D, gzipped, pixdim-only style affine diag(1, 3, 2).
        {"standard.nii.gz", {4, 5, 7}, 1, ScalarType::UInt8, {{1, 0, 0, 0}, {0, 3, 0, 0}, {0, 0, 2, 0}}, false, 0,
         {{0, 0.0, 255.0, 7650.0, {{{0, 0, 0}, 0.0}, {{3, 4, 6}, 255.0}, {{2, 2, 3}, 0.0}, {{1, 2, 6}, 255.0}}}}},
    };
    return files;
}

// Files curette refuses, and why (each reason is also the field its error names).
struct Refusal {
    const char* name;
    const char* field;
    const char* why;
};
const std::vector<Refusal>& refused() {
    static const std::vector<Refusal> files = {
        // nibabel ships these headers without their .img (nibabel itself raises FileNotFoundError for the data).
        {"nifti1.hdr", "image file", "an \"ni1\" header whose .img is not in the folder"},
        {"nifti2.hdr", "image file", "an \"ni2\" header whose .img is not in the folder"},
        // ANALYZE 7.5 (SPM2 flavour): no NIfTI magic, so no defined orientation; curette reads NIfTI only.
        {"analyze.hdr", "magic", "ANALYZE 7.5, not NIfTI (no \"ni1\" magic)"},
        // CIFTI-2 dense connectivity (NIfTI-2, intent 3001 ConnDense, dims 1 1 1 1 10 10): a matrix over brain
        // surface vertices and voxels, not a volume.
        {"row_major.dconn.nii", "intent_code", "CIFTI-2, a connectivity matrix rather than a volume"},
    };
    return files;
}

bool isNiftiName(const std::string& name) {
    auto ends = [&](const std::string& s) { return name.size() >= s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0; };
    return ends(".nii") || ends(".nii.gz") || ends(".hdr") || ends(".hdr.gz");
}

TEST(NibabelFiles, TheFolderIsThereAndEveryNiftiFileInItIsAccountedFor) {
    // Not a skip: without the folder this suite proves nothing (scripts/setup unpacks it).
    ASSERT_TRUE(std::filesystem::is_directory(kFolder)) << kFolder << " is missing: run scripts/setup (python3-nibabel's test data)";
    std::set<std::string> known;
    for (const FileExpectation& f : readable()) known.insert(f.name);
    for (const Refusal& r : refused()) known.insert(r.name);
    std::set<std::string> found;
    for (const auto& entry : std::filesystem::directory_iterator(kFolder)) {
        std::string name = entry.path().filename().string();
        if (!isNiftiName(name)) continue;
        found.insert(name);
        EXPECT_TRUE(known.count(name)) << name << " is a NIfTI file this test does not know: add its nibabel numbers or its refusal";
    }
    for (const std::string& name : known) EXPECT_TRUE(found.count(name)) << name << " is no longer in " << kFolder;
}

TEST(NibabelFiles, ReadWithNibabelsShapeAffineAndValues) {
    ASSERT_TRUE(std::filesystem::is_directory(kFolder)) << kFolder << " is missing: run scripts/setup";
    for (const FileExpectation& f : readable())
        for (const VolumeExpectation& e : f.volumes) {
            std::string what = std::string(f.name) + " volume " + std::to_string(e.index);
            io::VolumeReadOptions options;
            options.volumeIndex = e.index;
            VolumeData v = io::readVolume(kFolder / f.name, options);
            ASSERT_EQ(v.dims, f.dims) << what;
            EXPECT_EQ(v.volumeCount, f.volumeCount) << what;
            EXPECT_EQ(v.volumeIndex, e.index) << what;
            EXPECT_EQ(v.sourceType, f.type) << what;
            EXPECT_EQ(v.noDataVoxels, f.noData) << what;
            for (int row = 0; row < 3; ++row)
                for (int col = 0; col < 4; ++col)
                    EXPECT_NEAR(v.indexToWorld[col][row], f.affine[row][col], 1e-4) << what << " affine row " << row << " col " << col;
            auto same = [&](double got, double expected, double relative) {
                if (std::isnan(expected)) return std::isnan(got);
                return relative == 0 ? got == expected : std::abs(got - expected) <= relative * std::abs(expected);
            };
            const double valueTolerance = f.scaled ? 1e-9 : 0.0;
            for (const Voxel& x : e.voxels)
                EXPECT_TRUE(same(v.value(x.index.x, x.index.y, x.index.z), x.value, valueTolerance))
                    << what << " voxel " << x.index.x << "," << x.index.y << "," << x.index.z << ": curette "
                    << v.value(x.index.x, x.index.y, x.index.z) << ", nibabel " << x.value;
            double sum = 0, lo = INFINITY, hi = -INFINITY;
            for (int k = 0; k < v.dims.z; ++k)
                for (int j = 0; j < v.dims.y; ++j)
                    for (int i = 0; i < v.dims.x; ++i) {
                        double x = v.value(i, j, k);
                        if (std::isnan(x)) continue;
                        sum += x, lo = std::min(lo, x), hi = std::max(hi, x);
                    }
            EXPECT_TRUE(same(lo, e.min, valueTolerance)) << what << " min " << lo << " vs " << e.min;
            EXPECT_TRUE(same(hi, e.max, valueTolerance)) << what << " max " << hi << " vs " << e.max;
            EXPECT_TRUE(same(v.minValue, e.min, valueTolerance)) << what << " minValue " << v.minValue;
            EXPECT_TRUE(same(v.maxValue, e.max, valueTolerance)) << what << " maxValue " << v.maxValue;
            const bool integral = f.type != ScalarType::Float32 && f.type != ScalarType::Float64 && !f.scaled;
            EXPECT_TRUE(same(sum, e.sum, integral ? 0.0 : 1e-12)) << what << " sum " << sum << " vs " << e.sum;
        }
}

TEST(NibabelFiles, RefusedFilesSayWhy) {
    ASSERT_TRUE(std::filesystem::is_directory(kFolder)) << kFolder << " is missing: run scripts/setup";
    for (const Refusal& r : refused()) {
        try {
            io::readVolume(kFolder / r.name);
            ADD_FAILURE() << r.name << " (" << r.why << ") must be refused";
        } catch (const InputError& e) {
            EXPECT_EQ(e.field(), r.field) << r.name << ": " << e.what();
            EXPECT_EQ(e.file(), (kFolder / r.name).string()) << e.what();
        }
    }
}

TEST(NibabelFiles, Nifti2PairHeaderReadsWithAnImageBesideIt) {
    // nifti2.hdr ("ni2", 91 x 109 x 91 int16, sform code 4) is shipped without its .img; beside a copy of it
    // an .img the test writes must read with nibabel's affine for the header:
    //   [[-2, 0, 0, 90], [0, 2, 0, -126], [0, 0, 2, -72]]   (nibabel 5.0.0, Nifti2Pair.affine)
    ASSERT_TRUE(std::filesystem::is_directory(kFolder)) << kFolder << " is missing: run scripts/setup";
    auto dir = test::scratchDirectory();
    std::filesystem::copy_file(kFolder / "nifti2.hdr", dir / "nifti2.hdr", std::filesystem::copy_options::overwrite_existing);
    const glm::ivec3 dims(91, 109, 91);
    // Its vox_offset is 544: for a pair that is where the voxels start in the .img (nibabel reads from there too).
    std::vector<std::uint8_t> image(544, 0);
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) test::put<std::int16_t>(image, static_cast<std::int16_t>(i - j + 3 * k), false);
    test::writeBytes(dir / "nifti2.img", image);
    VolumeData v = io::readVolume(dir / "nifti2.hdr");
    ASSERT_EQ(v.dims, dims);
    EXPECT_EQ(v.sourceType, ScalarType::Int16);
    const double affine[3][4] = {{-2, 0, 0, 90}, {0, 2, 0, -126}, {0, 0, 2, -72}};
    for (int row = 0; row < 3; ++row)
        for (int col = 0; col < 4; ++col) EXPECT_NEAR(v.indexToWorld[col][row], affine[row][col], 1e-4);
    EXPECT_EQ(v.value(90, 0, 90), 90 + 270);
    EXPECT_EQ(v.value(0, 108, 0), -108);
}

}  // namespace
}  // namespace curette
