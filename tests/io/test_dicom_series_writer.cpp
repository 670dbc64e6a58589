// io/dicom_series_writer.h read back by curette's GDCM reader (io/dicom.h, separate code on another library):
// an oblique, anisotropic volume keeps its affine and its values; non-integer values go through the rescale;
// a sheared affine is refused. And io/dicom_reference.h finds the written series slice by slice, or says why not.
#include "io/dicom_reference.h"
#include "io/dicom_series_writer.h"
#include "io/volume_file.h"
#include "base/error.h"

#include <glm/gtc/matrix_transform.hpp>
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <unistd.h>

namespace curette {
namespace {

namespace fs = std::filesystem;

// Outside test::scratchDirectory(), whose root other tests read as a folder holding no DICOM.
fs::path freshDirectory(const std::string& name) {
    fs::path dir = fs::temp_directory_path() / ("curette-series-writer-" + std::to_string(::getpid())) / name;
    fs::remove_all(dir);
    return dir;
}

// 7 x 5 x 4 voxels of 0.8 x 0.9 x 1.7 mm, turned 30 degrees about (1, 2, 3), values i + 10 j + 100 k - 250.
VolumeData obliqueVolume(bool fractional) {
    glm::dmat4 rotation = glm::rotate(glm::dmat4(1.0), glm::radians(30.0), glm::normalize(glm::dvec3(1, 2, 3)));
    glm::dmat4 affine = glm::translate(glm::dmat4(1.0), glm::dvec3(-20, 14, 3)) * rotation * glm::scale(glm::dmat4(1.0), glm::dvec3(0.8, 0.9, 1.7));
    glm::ivec3 dims(7, 5, 4);
    std::vector<float> values;
    for (int k = 0; k < dims.z; ++k)
        for (int j = 0; j < dims.y; ++j)
            for (int i = 0; i < dims.x; ++i) values.push_back(float(i + 10 * j + 100 * k - 250) + (fractional ? 0.37f * float(i) : 0.0f));
    std::vector<std::uint8_t> bytes(values.size() * 4);
    std::memcpy(bytes.data(), values.data(), bytes.size());
    return buildVolume("oblique", dims, ScalarType::Float32, bytes.data(), false, 1.0, 0.0, affine);
}

void expectReadsBack(const VolumeData& written, const fs::path& dir, double tolerance) {
    VolumeData back = io::readVolume(dir);
    ASSERT_EQ(back.dims, written.dims);
    for (int c = 0; c < 4; ++c)
        for (int r = 0; r < 3; ++r) EXPECT_NEAR(back.indexToWorld[c][r], written.indexToWorld[c][r], 1e-4) << "affine column " << c << " row " << r;
    for (int k = 0; k < written.dims.z; ++k)
        for (int j = 0; j < written.dims.y; ++j)
            for (int i = 0; i < written.dims.x; ++i) ASSERT_NEAR(back.value(i, j, k), written.value(i, j, k), tolerance) << i << "," << j << "," << k;
}

TEST(DicomSeriesWriter, AnObliqueVolumeKeepsItsAffineAndValues) {
    VolumeData volume = obliqueVolume(false);
    fs::path dir = freshDirectory("oblique");
    io::DicomReferencedSeries series = io::writeDicomSeries(dir, volume, {}, {"CT", "test", 7, "test"});
    ASSERT_EQ(series.images.size(), 4u);
    EXPECT_EQ(io::guessModality(volume), "CT");
    expectReadsBack(volume, dir, 1e-6);

    // The source reading of the written files finds the same series, image by image.
    VolumeData read = io::readVolume(dir);
    io::DicomSourceReading reading = io::readDicomSourceSeries(read);
    ASSERT_TRUE(reading.series) << reading.problem;
    EXPECT_EQ(reading.series->seriesInstanceUid, series.seriesInstanceUid);
    EXPECT_EQ(reading.series->frameOfReferenceUid, series.frameOfReferenceUid);
    EXPECT_EQ(reading.series->patientStudy.studyInstanceUid, series.patientStudy.studyInstanceUid);
    for (std::size_t k = 0; k < 4; ++k) {
        EXPECT_EQ(reading.series->images[k].sopInstanceUid, series.images[k].sopInstanceUid);
        EXPECT_LT(glm::length(reading.series->images[k].positionLps - series.images[k].positionLps), 1e-4);
    }
}

TEST(DicomSeriesWriter, FractionalValuesGoThroughTheRescale) {
    VolumeData volume = obliqueVolume(true);
    fs::path dir = freshDirectory("fractional");
    io::writeDicomSeries(dir, volume, {}, {"MR", "test", 1, "test"});
    // 16 bits over the range: a step of (max - min) / 65535.
    expectReadsBack(volume, dir, 0.5 * (volume.maxValue - volume.minValue) / 65535.0 + 1e-6);
}

TEST(DicomSeriesWriter, AShearedAffineIsRefused) {
    VolumeData volume = obliqueVolume(false);
    volume.indexToWorld[1][0] += 0.3;   // the j axis leans towards i
    EXPECT_THROW(io::writeDicomSeries(freshDirectory("sheared"), volume, {}, {"CT", "test", 1, "test"}), InputError);
}

TEST(DicomReference, ASeriesThatIsNotOneFilePerSliceIsNotReferenced) {
    VolumeData volume = obliqueVolume(false);
    fs::path dir = freshDirectory("reference");
    io::writeDicomSeries(dir, volume, {}, {"CT", "test", 1, "test"});
    VolumeData read = io::readVolume(dir);
    read.files.pop_back();
    io::DicomSourceReading reading = io::readDicomSourceSeries(read);
    EXPECT_FALSE(reading.series);
    EXPECT_NE(reading.problem.find("3 file(s) for 4 slices"), std::string::npos) << reading.problem;
    read = io::readVolume(dir);
    std::swap(read.files[1], read.files[2]);
    reading = io::readDicomSourceSeries(read);
    EXPECT_FALSE(reading.series);
    EXPECT_NE(reading.problem.find("not where the volume places slice 1"), std::string::npos) << reading.problem;
}

}  // namespace
}  // namespace curette
