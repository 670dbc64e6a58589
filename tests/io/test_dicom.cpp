// DICOM import: real files from pydicom's test data (values, shapes and geometry checked against pydicom
// 2.3.1), every transfer syntax of MR_small, and series the tests write with GDCM (shuffled files, oblique
// planes, several series, missing slices, gantry tilt, localizers, rescale, stored bits, enhanced
// multi-frame), and that patient identifiers stay out of everything unless asked for.
#include "io/dicom.h"
#include "io/volume_file.h"
#include "base/error.h"
#include "tests/io/dicom_test_writer.h"
#include "tests/io/io_test_support.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <functional>
#include <iterator>

namespace curette {
namespace {

namespace fs = std::filesystem;
using io::DicomSeries;
using test::DicomImageSpec;

// scripts/setup copies python3-pydicom's test_files here. Missing data is a failure, not a skip.
const fs::path kPydicomData = "/usr/local/share/curette/pydicom-data";

// A fresh folder for the running test (`variant` tells several apart).
fs::path testDirectory(const std::string& variant = "") {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    fs::path dir = test::scratchDirectory() / (std::string(info->test_suite_name()) + "." + info->name() + variant);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

// Integer and short decimal values: "exact" up to the double rounding of the stored texel (any decoding error
// would be at least one unit of the stored value).
::testing::AssertionResult sameValue(double got, double expected) {
    if (std::abs(got - expected) <= 1e-9 * std::max(1.0, std::abs(expected))) return ::testing::AssertionSuccess();
    return ::testing::AssertionFailure() << "got " << got << ", expected " << expected;
}

void expectAffine(const glm::dmat4& got, const double (&expected)[3][4]) {
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 4; ++c) EXPECT_NEAR(got[c][r], expected[r][c], 1e-4) << "affine row " << r << " column " << c;
    EXPECT_EQ(got[0][3], 0.0);
    EXPECT_EQ(got[3][3], 1.0);
}

double sumOf(const VolumeData& v) {
    double sum = 0;
    for (int k = 0; k < v.dims.z; ++k)
        for (int j = 0; j < v.dims.y; ++j)
            for (int i = 0; i < v.dims.x; ++i) sum += v.value(i, j, k);
    return sum;
}

std::string errorOf(const std::function<void()>& f) {
    try {
        f();
    } catch (const InputError& e) {
        return e.what();
    }
    ADD_FAILURE() << "expected an InputError";
    return {};
}

struct Voxel {
    int i, j, k;
    double value;
};

// ---- real files: expected numbers come from pydicom 2.3.1 (pixel_array after apply_modality_lut; the affine
// built from IPP/IOP/PixelSpacing of the slices sorted by IPP . normal, LPS -> RAS) ---------------------------

TEST(DicomReal, PydicomTestFilesAreInstalled) {
    ASSERT_TRUE(fs::is_directory(kPydicomData)) << kPydicomData << " is missing: run scripts/setup";
    for (const char* name : {"CT_small.dcm", "MR_small.dcm", "MR_small_implicit.dcm", "MR_small_bigendian.dcm", "MR_small_RLE.dcm",
                             "MR_small_jp2klossless.dcm", "MR_small_jpeg_ls_lossless.dcm", "rtdose.dcm", "dicomdirtests/98892001/CT5N",
                             "dicomdirtests/77654033/CT2", "dicomdirtests/98892003/MR700"})
        EXPECT_TRUE(fs::exists(kPydicomData / name)) << name;
}

TEST(DicomReal, CtSmallMatchesPydicom) {
    VolumeData v = io::readVolume(kPydicomData / "CT_small.dcm");
    EXPECT_EQ(v.dims, glm::ivec3(128, 128, 1));
    EXPECT_EQ(v.sourceType, ScalarType::Int16);
    // pydicom: IPP -158.135803\-179.035797\-75.699997, IOP 1\0\0\0\1\0, PixelSpacing 0.661468\0.661468,
    // SpacingBetweenSlices 5 (the k step of a single slice).
    const double affine[3][4] = {{-0.661468, 0, 0, 158.135803}, {0, -0.661468, 0, 179.035797}, {0, 0, 5, -75.699997}};
    expectAffine(v.indexToWorld, affine);
    for (Voxel x : {Voxel{0, 0, 0, -849}, Voxel{64, 64, 0, 904}, Voxel{127, 127, 0, -115}, Voxel{3, 5, 0, -801}, Voxel{127, 0, 0, -808}})
        EXPECT_TRUE(sameValue(v.value(x.i, x.j, x.k), x.value)) << x.i << "," << x.j << "," << x.k;
    EXPECT_TRUE(sameValue(v.minValue, -896));
    EXPECT_TRUE(sameValue(v.maxValue, 1167));
    EXPECT_NEAR(sumOf(v), -1950906.0, 1e-3);
    EXPECT_NE(v.description.find("CT"), std::string::npos) << v.description;
}

TEST(DicomReal, MrSmallMatchesPydicom) {
    VolumeData v = io::readVolume(kPydicomData / "MR_small.dcm");
    EXPECT_EQ(v.dims, glm::ivec3(64, 64, 1));
    // pydicom: IPP -83.9063\-91.2000\6.6406, IOP 1\0\0\0\1\0, PixelSpacing 0.3125\0.3125, SliceThickness 0.8.
    const double affine[3][4] = {{-0.3125, 0, 0, 83.9063}, {0, -0.3125, 0, 91.2}, {0, 0, 0.8, 6.6406}};
    expectAffine(v.indexToWorld, affine);
    for (Voxel x : {Voxel{0, 0, 0, 905}, Voxel{32, 32, 0, 182}, Voxel{63, 63, 0, 862}, Voxel{3, 5, 0, 503}, Voxel{63, 0, 0, 328}})
        EXPECT_TRUE(sameValue(v.value(x.i, x.j, x.k), x.value)) << x.i << "," << x.j << "," << x.k;
    EXPECT_TRUE(sameValue(v.minValue, 127));
    EXPECT_TRUE(sameValue(v.maxValue, 2145));
    EXPECT_NEAR(sumOf(v), 2125338.0, 1e-3);
}

TEST(DicomReal, EveryTransferSyntaxOfMrSmallDecodesToTheSameValues) {
    // The nine MR_small files are one SOP instance in several transfer syntaxes; in a folder of their own (the
    // GDCM scan of pydicom's whole folder spends a second on SC_rgb_jpeg.dcm alone).
    fs::path dir = testDirectory();
    for (const auto& entry : fs::directory_iterator(kPydicomData))
        if (entry.path().filename().string().rfind("MR_", 0) == 0) fs::copy_file(entry.path(), dir / entry.path().filename());
    VolumeData reference = io::readVolume(dir / "MR_small.dcm");
    // Implicit VR, explicit big endian, RLE, JPEG 2000 lossless, JPEG-LS lossless. pydicom 2.3.1 decodes the
    // first four to MR_small's array exactly; it has no JPEG-LS decoder here (no CharPyLS), so that one is
    // checked against MR_small alone (it is lossless).
    for (const char* name : {"MR_small_implicit.dcm", "MR_small_bigendian.dcm", "MR_small_RLE.dcm", "MR_small_jp2klossless.dcm",
                             "MR_small_jpeg_ls_lossless.dcm"}) {
        SCOPED_TRACE(name);
        // One SOP instance is one image: the named file is the one that is read.
        std::vector<DicomSeries> series = io::scanDicom(dir / name);
        ASSERT_EQ(series.size(), 1u);
        ASSERT_EQ(series[0].files.size(), 1u);
        EXPECT_EQ(series[0].files[0].filename().string(), name);
        VolumeData v = io::readDicomSeries(series[0], name, io::chooseDicomSeries(series, "", name));
        ASSERT_EQ(v.dims, reference.dims);
        EXPECT_EQ(v.indexToWorld, reference.indexToWorld);
        int differing = 0;
        for (int j = 0; j < v.dims.y; ++j)
            for (int i = 0; i < v.dims.x; ++i) differing += v.value(i, j, 0) != reference.value(i, j, 0) ? 1 : 0;
        EXPECT_EQ(differing, 0);
    }
}

TEST(DicomReal, Ct5nFolderMatchesPydicom) {
    const fs::path folder = kPydicomData / "dicomdirtests/98892001/CT5N";
    std::vector<DicomSeries> series = io::scanDicom(folder);
    ASSERT_EQ(series.size(), 1u);
    EXPECT_EQ(series[0].number, "5");
    EXPECT_EQ(series[0].description, "SmartScore - Gated 0.5 sec");
    EXPECT_EQ(series[0].modality, "CT");
    ASSERT_TRUE(series[0].formsVolume()) << series[0].problem;
    // Sorted by z (pydicom: 3353 at z -1.2375 ... 2062 at 8.7625): against the file names and InstanceNumbers.
    std::vector<std::string> order;
    for (const io::DicomSlice& s : series[0].slices) order.push_back(s.file.filename().string());
    EXPECT_EQ(order, (std::vector<std::string>{"3353", "3023", "2693", "2392", "2062"}));

    VolumeData v = io::readVolume(folder);
    EXPECT_EQ(v.dims, glm::ivec3(16, 16, 5));
    const double affine[3][4] = {{-0.488281, 0, 0, 72.199997}, {0, -0.488281, 0, 143.0}, {0, 0, 2.5, -1.2375}};
    expectAffine(v.indexToWorld, affine);
    for (Voxel x : {Voxel{0, 0, 0, -33}, Voxel{8, 8, 2, 44}, Voxel{15, 15, 4, -729}, Voxel{3, 5, 1, -112}, Voxel{15, 0, 0, -101}})
        EXPECT_TRUE(sameValue(v.value(x.i, x.j, x.k), x.value)) << x.i << "," << x.j << "," << x.k;
    EXPECT_TRUE(sameValue(v.minValue, -888));
    EXPECT_TRUE(sameValue(v.maxValue, 85));
    EXPECT_NEAR(sumOf(v), -177320.0, 1e-3);

    // One file of the folder (no extension; "DICM" at byte 128) opens the whole series.
    VolumeData fromOneFile = io::readVolume(folder / "2693");
    EXPECT_EQ(fromOneFile.dims, v.dims);
    EXPECT_EQ(fromOneFile.voxels, v.voxels);
}

TEST(DicomReal, Ct2WithAGapIsRefused) {
    // pydicom: z -99.48, 103.02, 104.27, 105.52 (InstanceNumbers 18, 180-182): 1.25 mm steps and a 202.5 mm
    // gap, 161 slices missing. Refused: curette does not resample.
    const fs::path folder = kPydicomData / "dicomdirtests/77654033/CT2";
    std::vector<DicomSeries> series = io::scanDicom(folder);
    ASSERT_EQ(series.size(), 1u);
    EXPECT_FALSE(series[0].formsVolume());
    std::string message = errorOf([&] { io::readVolume(folder); });
    EXPECT_NE(message.find("series 2 \"Routine Brain\""), std::string::npos) << message;
    EXPECT_NE(message.find("161 slices missing"), std::string::npos) << message;
    EXPECT_NE(message.find("1.25 mm apart"), std::string::npos) << message;
    EXPECT_NE(message.find("202.5 mm"), std::string::npos) << message;
}

TEST(DicomReal, Mr700WithAnOrientationPerSliceIsRefused) {
    const fs::path folder = kPydicomData / "dicomdirtests/98892003/MR700";
    std::string message = errorOf([&] { io::readVolume(folder); });
    EXPECT_NE(message.find("series 700"), std::string::npos) << message;
    EXPECT_NE(message.find("ANGIO Projected from"), std::string::npos) << message;
    EXPECT_NE(message.find("7 different orientations among 7 images"), std::string::npos) << message;
}

TEST(DicomReal, RtDoseMultiFrameMatchesPydicom) {
    // pydicom: 15 frames of 10 x 10 uint32, IPP 189.43125\199.43125\-761.87, PixelSpacing 10\10,
    // GridFrameOffsetVector 0\5\...\70, DoseGridScaling 1e-6 (dose = raw * scaling).
    VolumeData v = io::readVolume(kPydicomData / "rtdose.dcm");
    EXPECT_EQ(v.dims, glm::ivec3(10, 10, 15));
    const double affine[3][4] = {{-10, 0, 0, -189.43125}, {0, -10, 0, -199.43125}, {0, 0, 5, -761.87}};
    expectAffine(v.indexToWorld, affine);
    for (Voxel x : {Voxel{0, 0, 0, 1249000}, Voxel{5, 5, 7, 975000}, Voxel{9, 9, 14, 799000}, Voxel{3, 5, 1, 981000}, Voxel{9, 0, 0, 1253000}})
        EXPECT_EQ(v.value(x.i, x.j, x.k), x.value * 1e-6) << x.i << "," << x.j << "," << x.k;
    EXPECT_EQ(v.minValue, 795000 * 1e-6);
    EXPECT_EQ(v.maxValue, 1254000 * 1e-6);
    EXPECT_NEAR(sumOf(v), 1519.91, 1e-9);
}

TEST(DicomReal, PhilipsEnhancedMrMatchesPydicom) {
    // nibabel's philips_mprage.dcm.gz: Enhanced MR Image Storage, 176 frames of 256 x 256, every macro in the
    // per-frame groups (none in the shared one). pydicom 2.3.1: frames already in IPP . normal order, 1 mm
    // apart; IOP -0.00220111\0.99788553\-0.064959\-0.03379351\-0.06499629\-0.99731314, PixelSpacing 1\1,
    // RescaleSlope 2.1079..., and every pixel 0 (the test file is blanked).
    const fs::path gz = "/usr/local/share/curette/nibabel-nicom-data/philips_mprage.dcm.gz";
    ASSERT_TRUE(fs::exists(gz)) << gz << " is missing: run scripts/setup";
    fs::path file = testDirectory() / "philips_mprage.dcm";
    {
        gzFile in = gzopen(gz.c_str(), "rb");
        ASSERT_NE(in, nullptr);
        std::ofstream out(file, std::ios::binary);
        char buffer[1 << 16];
        for (int n; (n = gzread(in, buffer, sizeof buffer)) > 0;) out.write(buffer, n);
        gzclose(in);
    }
    VolumeData v = io::readVolume(file);
    EXPECT_EQ(v.dims, glm::ivec3(256, 256, 176));
    const double affine[3][4] = {{0.002201, 0.033794, 0.999428, -92.709042},
                                 {-0.997886, 0.064996, 0.0, 125.12767},
                                 {-0.064959, -0.997313, 0.033865, 136.495257}};
    expectAffine(v.indexToWorld, affine);
    EXPECT_EQ(v.minValue, 0.0);
    EXPECT_EQ(v.maxValue, 0.0);
}

// ---- series written by the tests -------------------------------------------------------------------------

// The stored value of voxel (i,j,k) in the synthetic series.
int storedValue(int i, int j, int k) { return 100 * k + 10 * j + i - 300; }

struct Stack {
    DicomImageSpec spec;                // everything but position, pixels, names
    std::vector<glm::dvec3> positions;  // slice k's ImagePositionPatient
    std::function<int(int, int, int)> value = storedValue;
};

DicomImageSpec baseSpec(const std::string& seriesNumber, const std::string& description) {
    DicomImageSpec spec;
    spec.studyUid = test::newUid();
    spec.seriesUid = test::newUid();
    spec.seriesNumber = seriesNumber;
    spec.seriesDescription = description;
    return spec;
}

// Writes slice k of the stack into `dir`, under a name that sorts in no relation to the positions (k 7919 mod
// 1009: distinct for k < 1009), with InstanceNumbers in yet another order.
std::vector<fs::path> writeStack(const fs::path& dir, const Stack& stack, const std::string& prefix = "img") {
    std::vector<fs::path> files;
    const std::size_t n = stack.positions.size();
    for (std::size_t k = 0; k < n; ++k) {
        DicomImageSpec s = stack.spec;
        s.position = stack.positions[k];
        s.instanceNumber = static_cast<int>((k * 3 + 1) % n) + 1;
        s.pixels.clear();
        for (int j = 0; j < s.rows; ++j)
            for (int i = 0; i < s.columns; ++i) s.pixels.push_back(stack.value(i, j, static_cast<int>(k)));
        fs::path file = dir / (prefix + std::to_string(k * 7919 % 1009));
        test::writeDicom(file, s);
        files.push_back(file);
    }
    return files;
}

std::vector<glm::dvec3> alongZ(std::initializer_list<double> z, glm::dvec3 origin = {10, -20, 30}) {
    std::vector<glm::dvec3> p;
    for (double v : z) p.push_back(origin + glm::dvec3(0, 0, v));
    return p;
}

void expectValues(const VolumeData& v, const std::function<double(int, int, int)>& expected) {
    int wrong = 0;
    for (int k = 0; k < v.dims.z; ++k)
        for (int j = 0; j < v.dims.y; ++j)
            for (int i = 0; i < v.dims.x; ++i)
                if (!sameValue(v.value(i, j, k), expected(i, j, k))) {
                    if (wrong++ < 5) ADD_FAILURE() << "voxel " << i << "," << j << "," << k << ": " << sameValue(v.value(i, j, k), expected(i, j, k)).message();
                }
    EXPECT_EQ(wrong, 0);
}

TEST(DicomSynthetic, ShuffledFilesAreSortedByPositionNotByNameOrInstanceNumber) {
    fs::path dir = testDirectory();
    Stack stack{baseSpec("4", "shuffled"), {}};
    // Written in the order 3, 0, 5, 1, 4, 2 along z.
    stack.positions = alongZ({7.5, 0, 12.5, 2.5, 10, 5});
    stack.value = [](int i, int j, int k) {
        const int along[] = {3, 0, 5, 1, 4, 2};
        return storedValue(i, j, along[k]);
    };
    std::vector<fs::path> files = writeStack(dir, stack);
    // The names, sorted, are not in z order either (else this would prove nothing).
    std::vector<std::size_t> byName{0, 1, 2, 3, 4, 5};
    std::sort(byName.begin(), byName.end(), [&](std::size_t a, std::size_t b) { return files[a] < files[b]; });
    std::vector<double> zByName;
    for (std::size_t k : byName) zByName.push_back(stack.positions[k].z);
    EXPECT_FALSE(std::is_sorted(zByName.begin(), zByName.end()) || std::is_sorted(zByName.rbegin(), zByName.rend()));
    VolumeData v = io::readVolume(dir);
    EXPECT_EQ(v.dims, glm::ivec3(4, 3, 6));
    expectValues(v, [](int i, int j, int k) { return storedValue(i, j, k); });
    const double affine[3][4] = {{-1, 0, 0, -10}, {0, -1, 0, 20}, {0, 0, 2.5, 30}};
    expectAffine(v.indexToWorld, affine);
}

TEST(DicomSynthetic, ObliqueOrientationMapsEveryVoxelToItsPatientPosition) {
    fs::path dir = testDirectory();
    // Row direction X, column direction Y (orthonormal), normal N = X x Y; anisotropic pixels: rows 0.7 mm
    // apart, columns 0.4 mm apart, slices 1.5 mm.
    const glm::dvec3 x(0.8, 0.6, 0), y(-0.36, 0.48, 0.8), n = glm::cross(x, y), p0(10, -20, 30);
    Stack stack{baseSpec("9", "oblique"), {}};
    stack.spec.orientation = {x.x, x.y, x.z, y.x, y.y, y.z};
    stack.spec.pixelSpacing = {0.7, 0.4};
    const int order[] = {2, 0, 3, 1};
    for (int k : order) stack.positions.push_back(p0 + 1.5 * k * n);
    stack.value = [&](int i, int j, int k) { return storedValue(i, j, order[k]); };
    writeStack(dir, stack);
    VolumeData v = io::readVolume(dir);
    ASSERT_EQ(v.dims, glm::ivec3(4, 3, 4));
    expectValues(v, [](int i, int j, int k) { return storedValue(i, j, k); });
    for (int k = 0; k < 4; ++k)
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 4; ++i) {
                glm::dvec3 lps = p0 + i * 0.4 * x + j * 0.7 * y + k * 1.5 * n;  // PS3.3 C.7.6.2.1.1
                glm::dvec3 ras(-lps.x, -lps.y, lps.z);
                glm::dvec3 got(v.indexToWorld * glm::dvec4(i, j, k, 1));
                EXPECT_LT(glm::length(got - ras), 1e-4) << i << "," << j << "," << k;
            }
}

TEST(DicomSynthetic, TwoSeriesInOneFolderAreListedAndPickedByNumberOrUid) {
    fs::path dir = testDirectory();
    Stack big{baseSpec("3", "six slices"), alongZ({0, 1, 2, 3, 4, 5})};
    Stack small{baseSpec("7", "four slices"), alongZ({0, 2, 4, 6})};
    small.spec.studyUid = big.spec.studyUid;
    small.spec.rows = 5;
    small.value = [](int i, int j, int k) { return -storedValue(i, j, k); };
    writeStack(dir, big, "a");
    writeStack(dir, small, "b");

    std::vector<DicomSeries> series = io::scanDicom(dir);
    ASSERT_EQ(series.size(), 2u);
    const DicomSeries& s3 = series[0].number == "3" ? series[0] : series[1];
    const DicomSeries& s7 = series[0].number == "3" ? series[1] : series[0];
    EXPECT_EQ(s3.number, "3");
    EXPECT_EQ(s7.number, "7");
    EXPECT_EQ(s3.uid, big.spec.seriesUid);
    EXPECT_EQ(s7.uid, small.spec.seriesUid);
    EXPECT_EQ(s3.dims, glm::ivec3(4, 3, 6));
    EXPECT_EQ(s7.dims, glm::ivec3(4, 5, 4));
    EXPECT_EQ(s3.description, "six slices");
    EXPECT_EQ(s7.modality, "CT");

    VolumeData byDefault = io::readVolume(dir);
    EXPECT_EQ(byDefault.dims.z, 6);
    EXPECT_NE(byDefault.description.find("series 3 \"six slices\""), std::string::npos) << byDefault.description;
    EXPECT_NE(byDefault.description.find("default"), std::string::npos) << byDefault.description;

    io::VolumeReadOptions options;
    options.series = "7";
    VolumeData byNumber = io::readVolume(dir, options);
    EXPECT_EQ(byNumber.dims, glm::ivec3(4, 5, 4));
    expectValues(byNumber, [](int i, int j, int k) { return -storedValue(i, j, k); });
    EXPECT_NE(byNumber.description.find("series 7"), std::string::npos) << byNumber.description;
    std::vector<fs::path> files = byNumber.files, expected = s7.files;
    std::sort(files.begin(), files.end());
    std::sort(expected.begin(), expected.end());
    EXPECT_EQ(files, expected) << "the files of series 7, not those of series 3 beside them";
    const double affine[3][4] = {{-1, 0, 0, -10}, {0, -1, 0, 20}, {0, 0, 2, 30}};
    expectAffine(byNumber.indexToWorld, affine);

    options.series = big.spec.seriesUid;
    VolumeData byUid = io::readVolume(dir, options);
    EXPECT_EQ(byUid.dims, glm::ivec3(4, 3, 6));
    expectValues(byUid, [](int i, int j, int k) { return storedValue(i, j, k); });

    options.series = std::string("5");  // not `= "5"`: g++ 12 warns falsely on assigning a literal (GCC bug 105329)
    std::string message = errorOf([&] { io::readVolume(dir, options); });
    EXPECT_NE(message.find("series"), std::string::npos) << message;
    EXPECT_NE(message.find("\"5\""), std::string::npos) << message;
    EXPECT_NE(message.find(small.spec.seriesUid), std::string::npos) << message;
}

TEST(DicomSynthetic, SeriesNumberUsedTwiceNeedsTheUid) {
    fs::path dir = testDirectory();
    writeStack(dir, Stack{baseSpec("2", "first"), alongZ({0, 1, 2})}, "a");
    writeStack(dir, Stack{baseSpec("2", "second"), alongZ({0, 1})}, "b");
    io::VolumeReadOptions options;
    options.series = "2";
    std::string message = errorOf([&] { io::readVolume(dir, options); });
    EXPECT_NE(message.find("the number of 2 series"), std::string::npos) << message;
}

TEST(DicomSynthetic, MissingSliceIsRefusedNamingTheSeries) {
    fs::path dir = testDirectory();
    writeStack(dir, Stack{baseSpec("12", "thorax 2 mm"), alongZ({0, 2, 4, 8, 10})});
    std::string message = errorOf([&] { io::readVolume(dir); });
    EXPECT_NE(message.find("series 12 \"thorax 2 mm\""), std::string::npos) << message;
    EXPECT_NE(message.find("1 slice missing"), std::string::npos) << message;
    EXPECT_NE(message.find("2 mm apart, but 4 mm lie between slice 3 and 4 of 5"), std::string::npos) << message;
}

TEST(DicomSynthetic, NonUniformSpacingIsRefused) {
    fs::path dir = testDirectory();
    writeStack(dir, Stack{baseSpec("6", "uneven"), alongZ({0, 2, 4.5, 6, 8})});
    std::string message = errorOf([&] { io::readVolume(dir); });
    EXPECT_NE(message.find("series 6 \"uneven\""), std::string::npos) << message;
    EXPECT_NE(message.find("uniformly spaced slices"), std::string::npos) << message;
    EXPECT_NE(message.find("steps from 1.5 to 2.5 mm"), std::string::npos) << message;
    EXPECT_NE(message.find("resampling"), std::string::npos) << message;

    // Steps within 0.01 mm of each other are one spacing.
    fs::path near = testDirectory("-near");
    writeStack(near, Stack{baseSpec("6", "even enough"), alongZ({0, 2.003, 3.999, 6.002})});
    EXPECT_EQ(io::readVolume(near).dims.z, 4);
}

TEST(DicomSynthetic, GantryTiltIsRefused) {
    fs::path dir = testDirectory();
    // Axial planes, but each 2.5 mm step also moves 2.5 tan(10 deg) mm posterior: a 10 degree tilt.
    Stack stack{baseSpec("2", "tilted head"), {}};
    stack.spec.gantryDetectorTilt = "10";
    for (int k = 0; k < 5; ++k) stack.positions.push_back(glm::dvec3(0, 2.5 * std::tan(10.0 * 3.14159265358979 / 180) * k, 2.5 * k));
    writeStack(dir, stack);
    std::string message = errorOf([&] { io::readVolume(dir); });
    EXPECT_NE(message.find("series 2 \"tilted head\""), std::string::npos) << message;
    EXPECT_NE(message.find("gantry tilt of 10 degrees"), std::string::npos) << message;
    EXPECT_NE(message.find("GantryDetectorTilt (0018,1120) 10"), std::string::npos) << message;
}

TEST(DicomSynthetic, LocalizersBesideTheMainSeriesAreNotTheDefault) {
    fs::path dir = testDirectory();
    // A three-plane scout (mixed orientations: not a volume), a one-slice sagittal localizer (a volume, but a
    // localizer), and the 4-slice axial series.
    Stack scout{baseSpec("1", "3-plane loc"), alongZ({0, 0, 0})};
    scout.spec.imageType = "ORIGINAL\\PRIMARY\\LOCALIZER";
    DicomImageSpec sagittal = scout.spec, coronal = scout.spec, axial = scout.spec;
    sagittal.orientation = {0, 1, 0, 0, 0, -1};
    coronal.orientation = {1, 0, 0, 0, 0, -1};
    for (auto [spec, name] : {std::pair{&axial, "s0"}, std::pair{&sagittal, "s1"}, std::pair{&coronal, "s2"}}) {
        spec->pixels.assign(12, 5);
        test::writeDicom(dir / name, *spec);
    }
    DicomImageSpec single = baseSpec("2", "sagittal loc");
    single.imageType = "ORIGINAL\\PRIMARY\\LOCALIZER";
    single.orientation = {0, 1, 0, 0, 0, -1};
    single.pixels.assign(12, 9);
    test::writeDicom(dir / "loc", single);
    writeStack(dir, Stack{baseSpec("3", "axial"), alongZ({0, 3, 6, 9})});

    std::vector<DicomSeries> series = io::scanDicom(dir);
    ASSERT_EQ(series.size(), 3u);
    io::DicomChoice choice = io::chooseDicomSeries(series, "", dir.string());
    EXPECT_EQ(series[choice.index].number, "3");
    for (const DicomSeries& s : series) {
        if (s.number == "1") {
            EXPECT_NE(s.problem.find("3 different orientations"), std::string::npos) << s.problem;
        }
        if (s.number == "2") {
            EXPECT_TRUE(s.localizer && s.formsVolume());
        }
    }
    VolumeData v = io::readVolume(dir);
    EXPECT_EQ(v.dims.z, 4);
    EXPECT_NE(v.description.find("series 3 \"axial\""), std::string::npos) << v.description;

    // Asked for, the localizer opens.
    io::VolumeReadOptions options;
    options.series = "2";
    EXPECT_EQ(io::readVolume(dir, options).dims, glm::ivec3(4, 3, 1));
}

TEST(DicomSynthetic, ABrokenMainSeriesIsReportedNotReplacedByAScout) {
    fs::path dir = testDirectory();
    DicomImageSpec scout = baseSpec("1", "scout");  // a valid one-slice volume, but a scout
    scout.pixels.assign(12, 1);
    test::writeDicom(dir / "scout", scout);
    writeStack(dir, Stack{baseSpec("2", "main"), alongZ({0, 1, 2, 4, 5})});  // a missing slice
    std::string message = errorOf([&] { io::readVolume(dir); });
    EXPECT_NE(message.find("series 2 \"main\""), std::string::npos) << message;
    EXPECT_NE(message.find("1 slice missing"), std::string::npos) << message;
    io::VolumeReadOptions options;
    options.series = "1";
    EXPECT_EQ(io::readVolume(dir, options).dims.z, 1);
}

TEST(DicomSynthetic, SignedInt16WithInterceptGivesExactHounsfieldUnits) {
    fs::path dir = testDirectory();
    Stack stack{baseSpec("5", "hu"), alongZ({0, 1.25, 2.5, 3.75})};
    stack.spec.rescaleIntercept = "-1024";
    stack.value = [](int i, int j, int k) { return 1500 * k + 37 * j + i - 2000; };
    writeStack(dir, stack);
    VolumeData v = io::readVolume(dir);
    EXPECT_EQ(v.sourceType, ScalarType::Int16);
    expectValues(v, [](int i, int j, int k) { return 1500 * k + 37 * j + i - 2000 - 1024; });
    EXPECT_TRUE(sameValue(v.minValue, -3024));
    EXPECT_TRUE(sameValue(v.maxValue, 1500 * 3 + 37 * 2 + 3 - 2000 - 1024));

    // The same HU from unsigned storage with slope 0.5.
    fs::path unsignedDir = testDirectory("-unsigned");
    stack.spec.isSigned = false;
    stack.spec.rescaleSlope = "0.5";
    stack.value = [](int i, int j, int k) { return 2 * (1500 * k + 37 * j + i + 1000); };
    writeStack(unsignedDir, stack);
    VolumeData u = io::readVolume(unsignedDir);
    EXPECT_EQ(u.sourceType, ScalarType::UInt16);
    expectValues(u, [](int i, int j, int k) { return 1500 * k + 37 * j + i + 1000 - 1024; });
}

TEST(DicomSynthetic, BitsAboveBitsStoredAreNotPartOfTheValue) {
    // 12 stored bits in 16 allocated, garbage in the top 4 (PS3.5 8.1.1): signed values are sign-extended
    // from bit 11, unsigned ones masked.
    for (bool isSigned : {true, false}) {
        SCOPED_TRACE(isSigned ? "signed" : "unsigned");
        fs::path dir = testDirectory();
        Stack stack{baseSpec("8", "12 bits"), alongZ({0, 1, 2})};
        stack.spec.bitsStored = 12;
        stack.spec.isSigned = isSigned;
        auto twelveBit = [isSigned](int i, int j, int k) { return isSigned ? 300 * k + 10 * j + i - 2048 : 300 * k + 10 * j + i + 3000; };
        stack.value = [&](int i, int j, int k) { return (twelveBit(i, j, k) & 0x0fff) | 0xa000; };
        writeStack(dir, stack);
        VolumeData v = io::readVolume(dir);
        expectValues(v, twelveBit);
    }
}

TEST(DicomSynthetic, EnhancedMultiFrameIsPlacedByItsPerFramePositions) {
    fs::path dir = testDirectory();
    DicomImageSpec spec = baseSpec("301", "enhanced");
    spec.rows = 3, spec.columns = 4;
    spec.pixelSpacing = {0.6, 0.9};
    spec.rescaleIntercept = "-1024";
    const int along[] = {2, 0, 4, 1, 3};  // frame f lies at slice along[f]
    for (int f = 0; f < 5; ++f) {
        spec.framePositions.push_back(glm::dvec3(-5, 7, 20 + 3.0 * along[f]));
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 4; ++i) spec.pixels.push_back(storedValue(i, j, along[f]));
    }
    test::writeDicom(dir / "enhanced.dcm", spec);
    VolumeData v = io::readVolume(dir / "enhanced.dcm");
    ASSERT_EQ(v.dims, glm::ivec3(4, 3, 5));
    expectValues(v, [](int i, int j, int k) { return storedValue(i, j, k) - 1024; });
    const double affine[3][4] = {{-0.9, 0, 0, 5}, {0, -0.6, 0, -7}, {0, 0, 3, 20}};
    expectAffine(v.indexToWorld, affine);
}

TEST(DicomSynthetic, SlicesWithTheirOwnRescaleKeepTheirPhysicalValues) {
    fs::path dir = testDirectory();
    const char* slopes[] = {"0.5", "2", "0.25"};
    const char* intercepts[] = {"10", "-3", "0"};
    const char* names[] = {"p0.dcm", "p1.dcm", "p2.dcm"};
    const std::string series = test::newUid();
    for (int k = 0; k < 3; ++k) {
        DicomImageSpec spec = baseSpec("11", "pet");
        spec.seriesUid = series;
        spec.position = {0, 0, 4.0 * k};
        spec.rescaleSlope = slopes[k];
        spec.rescaleIntercept = intercepts[k];
        for (int j = 0; j < 3; ++j)
            for (int i = 0; i < 4; ++i) spec.pixels.push_back(storedValue(i, j, k));
        test::writeDicom(dir / names[k], spec);
    }
    VolumeData v = io::readVolume(dir);
    EXPECT_EQ(v.format, StorageFormat::Float32);
    expectValues(v, [&](int i, int j, int k) { return std::stod(slopes[k]) * storedValue(i, j, k) + std::stod(intercepts[k]); });
}

TEST(DicomSynthetic, SeveralImagesAtOnePositionAreRefused) {
    fs::path dir = testDirectory();
    writeStack(dir, Stack{baseSpec("14", "two echoes"), alongZ({0, 0, 3, 3, 6, 6})});
    std::string message = errorOf([&] { io::readVolume(dir); });
    EXPECT_NE(message.find("series 14 \"two echoes\""), std::string::npos) << message;
    EXPECT_NE(message.find("6 images at 3 positions"), std::string::npos) << message;
}

TEST(DicomSynthetic, OneFileOpensItsOwnSeriesFromItsFolder) {
    fs::path dir = testDirectory();
    std::vector<fs::path> small = writeStack(dir, Stack{baseSpec("7", "small"), alongZ({0, 1})}, "a");
    writeStack(dir, Stack{baseSpec("3", "large"), alongZ({0, 1, 2, 3, 4})}, "b");
    std::vector<DicomSeries> series = io::scanDicom(small[0]);
    ASSERT_EQ(series.size(), 1u);
    EXPECT_EQ(series[0].number, "7");
    EXPECT_EQ(series[0].slices.size(), 2u);
    EXPECT_EQ(io::readVolume(small[1]).dims.z, 2);
}

TEST(DicomSynthetic, FilesThatAreNotDicomImagesAreErrors) {
    fs::path dir = testDirectory();
    test::writeBytes(dir / "notes.txt", {'h', 'i'});
    std::string message = errorOf([&] { io::readVolume(dir); });
    EXPECT_NE(message.find("none of its 1 files is a DICOM image"), std::string::npos) << message;

    test::writeBytes(dir / "broken.dcm", std::vector<std::uint8_t>(200, 7));
    message = errorOf([&] { io::readVolume(dir / "broken.dcm"); });
    EXPECT_NE(message.find("broken.dcm"), std::string::npos) << message;
    EXPECT_NE(message.find("a well-formed DICOM image file"), std::string::npos) << message;

    // Truncated pixel data: the series is found, its pixels are refused.
    fs::path truncated = testDirectory("-truncated");
    std::vector<fs::path> files = writeStack(truncated, Stack{baseSpec("1", "cut"), alongZ({0, 1})});
    std::ifstream in(files[0], std::ios::binary);
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    bytes.resize(bytes.size() - 10);
    in.close();
    test::writeBytes(files[0], bytes);
    message = errorOf([&] { io::readVolume(truncated); });
    EXPECT_NE(message.find(files[0].filename().string()), std::string::npos) << message;
}

// Each of these made GDCM allocate gigabytes or abort on an assert() (found by tests/fuzz/fuzz_dicom.cpp); the
// structure check refuses them before GDCM reads them, with the tag and the byte offset.
TEST(DicomSynthetic, MalformedFilesAreRefusedBeforeGdcmReadsThem) {
    fs::path dir = testDirectory();
    std::vector<fs::path> files = writeStack(dir, Stack{baseSpec("1", "one"), alongZ({0})});
    std::ifstream in(files[0], std::ios::binary);
    const std::vector<std::uint8_t> good((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto find = [&](std::initializer_list<std::uint8_t> pattern) {
        auto at = std::search(good.begin(), good.end(), pattern.begin(), pattern.end());
        EXPECT_NE(at, good.end());
        return static_cast<std::size_t>(at - good.begin());
    };
    auto refusal = [&](const std::vector<std::uint8_t>& bytes) {
        fs::path file = testDirectory("-bad") / "bad.dcm";
        test::writeBytes(file, bytes);
        return errorOf([&] { io::readVolume(file); });
    };

    std::vector<std::uint8_t> huge = good;  // PixelData (7FE0,0010) OW declaring 0xF0000000 bytes
    test::set<std::uint32_t>(huge, find({0xe0, 0x7f, 0x10, 0x00, 'O', 'W'}) + 8, 0xf0000000u, false);
    std::string message = refusal(huge);
    EXPECT_NE(message.find("a well-formed DICOM image file"), std::string::npos) << message;
    EXPECT_NE(message.find("(7FE0,0010) at byte"), std::string::npos) << message;
    EXPECT_NE(message.find("declares 4026531840 bytes"), std::string::npos) << message;

    std::vector<std::uint8_t> delimiter = good;  // a sequence delimiter after the pixel data
    delimiter.insert(delimiter.end(), {0xfe, 0xff, 0xdd, 0xe0, 0, 0, 0, 0});
    message = refusal(delimiter);
    EXPECT_NE(message.find("a sequence delimiter where none belongs"), std::string::npos) << message;

    std::vector<std::uint8_t> wrongVr = good;  // InstanceNumber (0020,0013) IS written as US
    std::size_t instance = find({0x20, 0x00, 0x13, 0x00, 'I', 'S'});
    wrongVr[instance + 4] = 'U', wrongVr[instance + 5] = 'S';
    message = refusal(wrongVr);
    EXPECT_NE(message.find("the VR US where PS3.6 gives IS, (0020,0013)"), std::string::npos) << message;

    std::vector<std::uint8_t> noSamples = good;  // SamplesPerPixel (0028,0002) 0
    test::set<std::uint16_t>(noSamples, find({0x28, 0x00, 0x02, 0x00, 'U', 'S'}) + 8, 0, false);
    message = refusal(noSamples);
    EXPECT_NE(message.find("SamplesPerPixel 0"), std::string::npos) << message;

    std::vector<std::uint8_t> metaOnly(good.begin(), good.begin() + static_cast<std::ptrdiff_t>(find({0x08, 0x00, 0x08, 0x00})));
    message = refusal(metaOnly);
    EXPECT_NE(message.find("no data set after the file meta information"), std::string::npos) << message;
}

// A data set without file meta information is read in the one encoding GDCM guesses from its first element, not
// in any encoding it would be well formed in. These 12 bytes (found by the 30-minute fuzz run) are a short
// element whose length runs past the end when read little endian, GDCM's guess, and well formed only when read
// big endian: GDCM asserted (the process aborted) reading them in a folder beside a good series.
TEST(DicomSynthetic, AFileWithoutMetaIsCheckedInTheEncodingGdcmGuesses) {
    fs::path dir = testDirectory();
    std::vector<fs::path> files = writeStack(dir, Stack{baseSpec("1", "one"), alongZ({0, 1, 2})});
    const std::vector<std::uint8_t> bytes = {0x04, 0x00, 0x00, 0x00, 'S', 'H', 0x00, 0x03, 0x00, 'S', 0x7f, 0x00};
    test::writeBytes(dir / "stray.dcm", bytes);
    VolumeData v = io::readVolume(dir);  // the good series still opens
    EXPECT_EQ(v.dims, glm::ivec3(4, 3, 3));
    fs::path alone = testDirectory("-alone") / "stray.dcm";
    test::writeBytes(alone, bytes);
    std::string message = errorOf([&] { io::readVolume(alone); });
    EXPECT_NE(message.find("(0004,0000) at byte 0 declares 768 bytes, but 4 are left"), std::string::npos) << message;
}

// ---- identifiers ---------------------------------------------------------------------------------------------

TEST(DicomIdentifiers, PatientNameAndIdsAppearOnlyWhenAsked) {
    fs::path dir = testDirectory();
    Stack stack{baseSpec("4", "head"), alongZ({0, 1, 2})};
    stack.spec.patientName = "Doe^Jane";
    stack.spec.patientId = "ID-4711";
    stack.spec.patientBirthDate = "19700101";
    stack.spec.accessionNumber = "ACC-99";
    writeStack(dir, stack);
    auto hasIdentifier = [](const std::string& text) {
        for (const char* id : {"Doe", "ID-4711", "19700101", "ACC-99"})
            if (text.find(id) != std::string::npos) return true;
        return false;
    };

    std::vector<DicomSeries> series = io::scanDicom(dir);
    ASSERT_EQ(series.size(), 1u);
    EXPECT_TRUE(series[0].patientName.empty() && series[0].patientId.empty() && series[0].patientBirthDate.empty() &&
                series[0].accessionNumber.empty());
    VolumeData v = io::readVolume(dir);
    EXPECT_FALSE(hasIdentifier(v.description)) << v.description;

    // A refused series and a wrong --series do not name the patient either.
    fs::path broken = testDirectory("-broken");
    stack.positions = alongZ({0, 1, 3});
    stack.spec.seriesUid = test::newUid();
    writeStack(broken, stack);
    std::string message = errorOf([&] { io::readVolume(broken); });
    EXPECT_NE(message.find("missing"), std::string::npos) << message;
    EXPECT_FALSE(hasIdentifier(message)) << message;
    io::VolumeReadOptions wrong;
    wrong.series = "99";
    message = errorOf([&] { io::readVolume(dir, wrong); });
    EXPECT_FALSE(hasIdentifier(message)) << message;

    io::VolumeReadOptions show;
    show.showIdentifiers = true;
    VolumeData shown = io::readVolume(dir, show);
    EXPECT_NE(shown.description.find("Doe^Jane"), std::string::npos) << shown.description;
    EXPECT_NE(shown.description.find("ID-4711"), std::string::npos) << shown.description;
    std::vector<DicomSeries> withIds = io::scanDicom(dir, true);
    EXPECT_EQ(withIds[0].patientName, "Doe^Jane");
    EXPECT_EQ(withIds[0].patientId, "ID-4711");
    EXPECT_EQ(withIds[0].patientBirthDate, "19700101");
    EXPECT_EQ(withIds[0].accessionNumber, "ACC-99");
}

TEST(DicomDispatch, FoldersDcmNamesAndTheDicmPrefixAreDicom) {
    EXPECT_TRUE(io::looksLikeDicom(kPydicomData / "dicomdirtests/98892001/CT5N"));
    EXPECT_TRUE(io::looksLikeDicom(kPydicomData / "dicomdirtests/98892001/CT5N/2062"));  // no extension: DICM
    EXPECT_TRUE(io::looksLikeDicom("/nonexistent/x.DCM"));
    EXPECT_FALSE(io::looksLikeDicom(kPydicomData / "README.txt"));
}

}  // namespace
}  // namespace curette

namespace curette {
namespace {

// GDCM's JPEG-LS codec asserts (the process aborts) when a stream's frame header promises more samples than
// Rows x Columns; the fuzz target found it in CI. Such a file is now an InputError naming the mismatch.
TEST(DicomSynthetic, AJpegLsFrameLargerThanTheImageIsRefusedBeforeGdcmDecodesIt) {
    std::ifstream in(std::filesystem::path(CURETTE_SOURCE_DIR) / "tests/fuzz/corpus/dicom/ct5n_jpegls.dcm", std::ios::binary);
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    ASSERT_GT(bytes.size(), 200u);
    std::filesystem::path good = test::scratchDirectory() / "jpegls-good.dcm";
    test::writeBytes(good, bytes);
    EXPECT_NO_THROW(io::readVolume(good)) << "the seed itself reads";
    const std::uint8_t marker[2] = {0xFF, 0xF7};
    auto sof = std::search(bytes.begin(), bytes.end(), std::begin(marker), std::end(marker));
    ASSERT_NE(sof, bytes.end()) << "the seed is JPEG-LS";
    sof[7] = 0x01;  // X (columns) high byte: 16 -> 272 columns in the stream, 16 in the DICOM header
    std::filesystem::path bad = test::scratchDirectory() / "jpegls-too-wide.dcm";
    test::writeBytes(bad, bytes);
    std::string message = errorOf([&] { io::readVolume(bad); });
    EXPECT_NE(message.find("JPEG-LS frames of 16 x 16"), std::string::npos) << message;
}

// A delimiter's length is zero (PS3.5 7.5). GDCM reads a sequence delimiter among encapsulated fragments as
// one more fragment and allocates and zero-fills the length it declares: a 3.8 kB file whose delimiter said
// 1358954496 bytes took 1.3 GB and 8-50 s to scan (found by the 30-minute fuzz run as a slow unit).
TEST(DicomSynthetic, ADelimiterWithALengthIsRefusedBeforeGdcmAllocatesIt) {
    std::ifstream in(std::filesystem::path(CURETTE_SOURCE_DIR) / "tests/fuzz/corpus/dicom/ct5n_jpegls.dcm", std::ios::binary);
    std::vector<std::uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const std::uint8_t sequenceEnd[8] = {0xfe, 0xff, 0xdd, 0xe0, 0, 0, 0, 0};
    auto end = std::find_end(bytes.begin(), bytes.end(), std::begin(sequenceEnd), std::end(sequenceEnd));
    ASSERT_NE(end, bytes.end()) << "the seed's fragments end with a sequence delimiter";
    test::set<std::uint32_t>(bytes, static_cast<std::size_t>(end - bytes.begin()) + 4, 1358954496u, false);
    std::filesystem::path bad = test::scratchDirectory() / "jpegls-long-delimiter.dcm";
    test::writeBytes(bad, bytes);
    std::string message = errorOf([&] { io::readVolume(bad); });
    EXPECT_NE(message.find("a sequence delimiter with a length of 1358954496 (PS3.5 7.5: 0), (FFFE,E0DD)"), std::string::npos)
        << message;
}

// A file that names the deflated transfer syntax but whose data set is not a deflate stream: GDCM read its bytes
// as they stand and allocated and zero-filled the 1.3 GB an element declared (2.8 kB found by the fuzz run, an
// out-of-memory only when libFuzzer's RSS check caught it). Its data set must inflate now, or it is refused
// before GDCM reads it.
TEST(DicomSynthetic, ADeflatedDataSetThatDoesNotInflateIsRefusedBeforeGdcmReadsIt) {
    fs::path bad = fs::path(CURETTE_SOURCE_DIR) / "tests/fuzz/corpus/dicom/deflated-syntax-raw-data-set.dcm";
    std::string message = errorOf([&] { io::readVolume(bad); });
    EXPECT_NE(message.find("a deflated data set (transfer syntax 1.2.840.10008.1.2.1.99) that does not inflate"), std::string::npos)
        << message;
}

// pydicom's deflated file inflates, and its data set is walked and read.
TEST(DicomReal, TheDeflatedFileIsInflatedWalkedAndRead) {
    std::vector<DicomSeries> series = io::scanDicom(kPydicomData / "image_dfl.dcm");
    ASSERT_EQ(series.size(), 1u);
    EXPECT_EQ(series[0].dims, glm::ivec3(512, 512, 1));
}

}  // namespace
}  // namespace curette
