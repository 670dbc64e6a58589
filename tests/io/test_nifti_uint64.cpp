// 64-bit volumes as NIfTI-1 (io/nifti_uint64.h, the drilled removal's file): every bit of every word reads
// back, the affine within float32, either endianness; anything else is an InputError naming the field.
#include "io/gzip.h"
#include "io/nifti_uint64.h"
#include "io/nifti_writer.h"
#include "base/atomic_file.h"
#include "tests/io/io_test_support.h"

#include <random>

namespace curette {
namespace {

// A folder of its own: other tests read the shared scratch folder as a (DICOM) directory.
std::filesystem::path folder() {
    std::filesystem::path dir = test::scratchDirectory() / "uint64";
    std::filesystem::create_directories(dir);
    return dir;
}

io::Uint64Volume sampleVolume() {
    io::Uint64Volume v;
    v.dims = {5, 4, 3};
    v.indexToWorld = glm::dmat4(glm::dvec4(0.0, 1.2, 0.1, 0.0), glm::dvec4(-0.9, 0.0, 0.0, 0.0), glm::dvec4(0.0, 0.05, 2.0, 0.0),
                                glm::dvec4(10.5, -20.25, 3.0, 1.0));
    std::mt19937_64 random(7);
    for (int i = 0; i < 60; ++i) v.values.push_back(i % 3 == 0 ? 0 : random());
    v.values[1] = ~std::uint64_t(0);   // every bit, the top one too
    v.values[2] = std::uint64_t(1) << 63;
    return v;
}

TEST(NiftiUint64, EveryBitReadsBackCompressedOrNot) {
    for (const char* name : {"bits.nii.gz", "bits.nii"}) {
        std::filesystem::path path = folder() / name;
        io::Uint64Volume v = sampleVolume();
        io::writeNiftiUint64(path, v, "test");
        EXPECT_EQ(io::isGzip(readFileBytes(path)), std::string(name).ends_with(".gz"));
        io::Uint64Volume back = io::readNiftiUint64(path);
        EXPECT_EQ(back.dims, v.dims);
        EXPECT_EQ(back.values, v.values);
        for (int c = 0; c < 4; ++c)
            for (int r = 0; r < 3; ++r) EXPECT_NEAR(back.indexToWorld[c][r], v.indexToWorld[c][r], 1e-5) << c << "," << r;
        std::vector<std::uint8_t> raw = readFileBytes(path);
        std::vector<std::uint8_t> bytes = io::isGzip(raw) ? io::gunzip(raw, name, 1 << 20) : raw;
        std::int16_t datatype;
        std::memcpy(&datatype, bytes.data() + 70, 2);
        EXPECT_EQ(datatype, 1280) << "DT_UINT64";
    }
}

// Words per voxel as a 4-D file (dim[4]), the word slowest.
TEST(NiftiUint64, SeveralWordsPerVoxelReadBackAsA4DFile) {
    std::filesystem::path path = folder() / "words.nii.gz";
    io::Uint64Volume v = sampleVolume();
    v.words = 3;
    std::mt19937_64 random(11);
    for (int i = 0; i < 120; ++i) v.values.push_back(random());
    io::writeNiftiUint64(path, v, "test");
    io::Uint64Volume back = io::readNiftiUint64(path);
    EXPECT_EQ(back.words, 3);
    EXPECT_EQ(back.dims, v.dims);
    EXPECT_EQ(back.values, v.values);
    std::vector<std::uint8_t> bytes = io::gunzip(readFileBytes(path), "words", 1 << 20);
    std::int16_t dim[5];
    std::memcpy(dim, bytes.data() + 40, sizeof dim);
    EXPECT_EQ(dim[0], 4);
    EXPECT_EQ(dim[4], 3);
}

TEST(NiftiUint64, ABigEndianFileReadsTheSame) {
    io::Uint64Volume v = sampleVolume();
    std::filesystem::path little = folder() / "little.nii";
    io::writeNiftiUint64(little, v, "test");
    std::vector<std::uint8_t> b = readFileBytes(little);
    // Swap every header field curette reads and every voxel word.
    auto swap = [&](std::size_t offset, std::size_t size) { std::reverse(b.begin() + static_cast<long>(offset), b.begin() + static_cast<long>(offset + size)); };
    swap(0, 4);
    for (std::size_t i = 0; i < 8; ++i) swap(40 + 2 * i, 2);
    swap(70, 2), swap(72, 2), swap(108, 4), swap(112, 4), swap(116, 4), swap(254, 2);
    for (std::size_t i = 0; i < 12; ++i) swap(280 + 4 * i, 4);
    for (std::size_t n = 0; n < v.values.size(); ++n) swap(352 + 8 * n, 8);
    io::Uint64Volume back = io::readNiftiUint64Bytes(b, "big.nii");
    EXPECT_EQ(back.values, v.values);
    EXPECT_EQ(back.dims, v.dims);
}

TEST(NiftiUint64, OtherFilesAreRefusedNamingTheField) {
    std::filesystem::path dir = folder();
    // A label map (uint8) is not a removal.
    LabelMap labels;
    labels.dims = {2, 2, 2};
    labels.ids.assign(8, 1);
    io::writeNiftiLabelmap(dir / "labels.nii", labels);
    test::expectInputError([&] { io::readNiftiUint64(dir / "labels.nii"); }, (dir / "labels.nii").string(), "datatype");
    io::Uint64Volume v = sampleVolume();
    io::writeNiftiUint64(dir / "ok.nii", v, "test");
    std::vector<std::uint8_t> good = readFileBytes(dir / "ok.nii");
    auto refused = [&](std::vector<std::uint8_t> bytes, const std::string& field) {
        test::expectInputError([&] { io::readNiftiUint64Bytes(bytes, "bad.nii"); }, "bad.nii", field);
    };
    std::vector<std::uint8_t> b = good;
    b.resize(b.size() - 8);
    refused(b, "vox_offset");   // a voxel short
    b = good, b[254] = 0, b[255] = 0;
    refused(b, "sform_code");
    b = good, b[40] = 5;
    refused(b, "dim[0]");
    b = good, b[40] = 4, b[48] = 0;   // 4-D with no words per voxel
    refused(b, "dim[4]");
    b = good, b[72] = 32;
    refused(b, "bitpix");
    b = good, b[344] = 'x';
    refused(b, "magic");
    refused(std::vector<std::uint8_t>(good.begin(), good.begin() + 100), "header");
    // The writer refuses values that do not fill the grid, and leaves no file.
    v.values.pop_back();
    EXPECT_THROW(io::writeNiftiUint64(dir / "short.nii", v, "test"), InputError);
    EXPECT_FALSE(std::filesystem::exists(dir / "short.nii"));
}


// The writers' gzip member fed in parts (a plane at a time) inflates to the parts in order, across empty parts
// and parts larger than zlib's output chunk.
TEST(NiftiUint64, AGzipMemberFedInPartsInflatesToTheirConcatenation) {
    std::mt19937 random(3);
    std::vector<std::uint8_t> whole;
    io::GzipCompressor gz;
    for (std::size_t size : {std::size_t(0), std::size_t(348), std::size_t(200000), std::size_t(0), std::size_t(7), std::size_t(70000)}) {
        std::vector<std::uint8_t> part(size);
        for (std::size_t i = 0; i < size; ++i) part[i] = static_cast<std::uint8_t>(i % 251 < 200 ? 0 : random());
        gz.add(part);
        whole.insert(whole.end(), part.begin(), part.end());
    }
    std::vector<std::uint8_t> member = gz.finish();
    EXPECT_EQ(io::gunzip(member, "parts", 1 << 22), whole);
    EXPECT_EQ(io::gunzip(io::gzipCompress(whole), "whole", 1 << 22), whole);
}

// The reader hands the planes over one at a time, word slowest then z, as written; an inflater read in parts
// of any size gives the stream's bytes. A gzip file too small to hold what its header claims is refused at
// the header (deflate inflates at most 1032-fold), and one cut short names vox_offset when the planes run out.
TEST(NiftiUint64, PlanesAreReadOneAtATimeInTheFilesOrder) {
    std::filesystem::path path = folder() / "planes.nii.gz";
    io::Uint64Volume v = sampleVolume();
    v.words = 2;
    std::mt19937_64 random(5);
    for (int i = 0; i < 60; ++i) v.values.push_back(random());
    io::writeNiftiUint64(path, v, "test");
    io::NiftiUint64Reader reader(path);
    ASSERT_EQ(reader.dims(), v.dims);
    ASSERT_EQ(reader.words(), 2);
    std::vector<std::uint64_t> plane(20);
    int word = -1, z = -1, planes = 0;
    while (reader.next(word, z, plane)) {
        EXPECT_EQ(word, planes / 3);
        EXPECT_EQ(z, planes % 3);
        EXPECT_TRUE(std::equal(plane.begin(), plane.end(), v.values.begin() + 20 * planes)) << "plane " << planes;
        ++planes;
    }
    EXPECT_EQ(planes, 6);

    std::vector<std::uint8_t> stored = readFileBytes(path), whole = io::gunzip(stored, "planes", 1 << 20), parts;
    io::Inflater inflater(stored, "planes", 1 << 20);
    for (std::size_t size = 1;; size = size * 3 + 1) {
        std::vector<std::uint8_t> part(size);
        std::size_t n = inflater.read(part);
        parts.insert(parts.end(), part.begin(), part.begin() + static_cast<long>(n));
        if (n < size) break;
    }
    EXPECT_EQ(parts, whole);

    // A header claiming 2000^3 voxels of 8 words in a file of a few hundred bytes.
    std::vector<std::uint8_t> header = whole;
    header.resize(352);
    std::int16_t big = 2000;
    for (int a = 0; a < 3; ++a) std::memcpy(header.data() + 42 + 2 * a, &big, 2);
    test::expectInputError([&] { io::NiftiUint64Reader(io::gzipCompress(header), "claims.nii.gz"); }, "claims.nii.gz", "vox_offset");
    // The same file cut after its first plane: the header passes, the second plane is refused.
    std::vector<std::uint8_t> cut(whole.begin(), whole.begin() + 352 + 8 * 20 + 8);
    std::vector<std::uint8_t> cutStored = io::gzipCompress(cut);
    io::NiftiUint64Reader shortReader(cutStored, "cut.nii.gz");
    EXPECT_TRUE(shortReader.next(word, z, plane));
    test::expectInputError([&] { shortReader.next(word, z, plane); }, "cut.nii.gz", "vox_offset");
}

}  // namespace
}  // namespace curette
