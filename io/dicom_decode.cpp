// DICOM decoding (gdcm::ImageReader, gdcm::Image::GetBuffer): every transfer syntax GDCM decodes, checked
// before it allocates; stored bits, sample types, and the rescale to physical values.
#include "io/dicom.h"

#include "io/dicom_values.h"
#include "base/error.h"

#include <gdcmImage.h>
#include <gdcmImageReader.h>
#include <gdcmSequenceOfFragments.h>

#include <algorithm>
#include <cstring>
#include <map>
#include <optional>

namespace curette::io {

namespace {

namespace fs = std::filesystem;
using dicom_detail::fmt;
using dicom_detail::forgetGdcmMessages;
using dicom_detail::gdcmMessages;
using dicom_detail::kAlwaysAcceptedBytes;

// Compressed pixel data may decode to at most this many times its size (or to 64 MiB, whatever is larger), so
// a corrupt header cannot make curette allocate gigabytes for a few bytes of file.
constexpr double kMaxCompressionRatio = 1000.0;

// Every JPEG-LS frame header (SOF55: FF F7, length, P, Y, X, Nf; T.87 C.2.2) in the fragments must give this
// image's rows, columns and samples, at most `bitsAllocated` bits, and there must be one per frame.
void checkJpegLsFrames(const gdcm::DataElement& pixelData, unsigned columns, unsigned rows, unsigned frames, unsigned samples,
                       unsigned bitsAllocated, const std::string& name) {
    const gdcm::SequenceOfFragments* fragments = pixelData.GetSequenceOfFragments();
    unsigned headers = 0;
    for (unsigned f = 0; fragments && f < fragments->GetNumberOfFragments(); ++f) {
        const gdcm::ByteValue* value = fragments->GetFragment(f).GetByteValue();
        if (!value) continue;
        const auto* p = reinterpret_cast<const std::uint8_t*>(value->GetPointer());
        const std::size_t n = static_cast<std::uint32_t>(value->GetLength());
        for (std::size_t i = 0; i + 10 <= n; ++i) {
            if (p[i] != 0xFF || p[i + 1] != 0xF7) continue;  // in JPEG-LS scan data FF is never followed by a byte >= 0x80
            unsigned precision = p[i + 4], y = (p[i + 5] << 8) | p[i + 6], x = (p[i + 7] << 8) | p[i + 8], components = p[i + 9];
            if (x != columns || y != rows || components != samples || precision < 2 || precision > bitsAllocated)
                throw InputError(name, "PixelData", "JPEG-LS frames of " + std::to_string(columns) + " x " + std::to_string(rows) + " x " +
                                                        std::to_string(samples) + " samples of at most " + std::to_string(bitsAllocated) + " bits",
                                 "a frame header of " + std::to_string(x) + " x " + std::to_string(y) + " x " + std::to_string(components) +
                                     " samples of " + std::to_string(precision) + " bits");
            ++headers;
        }
    }
    if (headers != frames)
        throw InputError(name, "PixelData", std::to_string(frames) + " JPEG-LS frame headers (one per frame)", std::to_string(headers));
}

// ---- decoding -----------------------------------------------------------------------------------------------

struct DecodedImage {
    ScalarType type = ScalarType::UInt8;
    std::vector<std::uint8_t> samples;  // frames x rows x columns, native endian, of scalarTypeSize(type)
};

// Keeps the BitsStored low bits of each integer sample and extends their sign: the bits above are not part
// of the value (PS3.5 8.1.1; old files keep overlays there).
template <typename T>
void keepStoredBits(std::vector<std::uint8_t>& samples, unsigned bitsStored, bool isSigned) {
    using Unsigned = std::make_unsigned_t<T>;
    if (bitsStored == 0 || bitsStored >= 8 * sizeof(T)) return;
    const Unsigned mask = static_cast<Unsigned>((Unsigned{1} << bitsStored) - 1);
    const Unsigned sign = static_cast<Unsigned>(Unsigned{1} << (bitsStored - 1));
    for (std::size_t i = 0; i + sizeof(T) <= samples.size(); i += sizeof(T)) {
        Unsigned v;
        std::memcpy(&v, samples.data() + i, sizeof v);
        v = static_cast<Unsigned>(v & mask);
        if (isSigned && (v & sign)) v = static_cast<Unsigned>(v | static_cast<Unsigned>(~mask));
        std::memcpy(samples.data() + i, &v, sizeof v);
    }
}

// Converts samples of type From to To (the types buildVolume takes).
template <typename From, typename To>
std::vector<std::uint8_t> widen(const std::vector<std::uint8_t>& samples) {
    std::size_t count = samples.size() / sizeof(From);
    std::vector<std::uint8_t> out(count * sizeof(To));
    for (std::size_t i = 0; i < count; ++i) {
        From v;
        std::memcpy(&v, samples.data() + i * sizeof(From), sizeof v);
        To w = static_cast<To>(v);
        std::memcpy(out.data() + i * sizeof(To), &w, sizeof w);
    }
    return out;
}

// The sample type curette stores a GDCM pixel format in (INT8 is widened and UINT32 converted later).
ScalarType storedType(const gdcm::PixelFormat& format, const std::string& name) {
    switch (format.GetScalarType()) {
        case gdcm::PixelFormat::UINT8: return ScalarType::UInt8;
        case gdcm::PixelFormat::INT8: return ScalarType::UInt8;  // widened to int16 below
        case gdcm::PixelFormat::UINT12:
        case gdcm::PixelFormat::UINT16: return ScalarType::UInt16;
        case gdcm::PixelFormat::INT12:
        case gdcm::PixelFormat::INT16: return ScalarType::Int16;
        case gdcm::PixelFormat::UINT32: return ScalarType::Int32;  // converted to float32 below
        case gdcm::PixelFormat::INT32: return ScalarType::Int32;
        case gdcm::PixelFormat::FLOAT32: return ScalarType::Float32;
        case gdcm::PixelFormat::FLOAT64: return ScalarType::Float64;
        default:
            throw InputError(name, "BitsAllocated", "8, 16 or 32-bit integer or float samples",
                             std::to_string(format.GetBitsAllocated()) + " bits (" + format.GetScalarTypeAsString() + ")");
    }
}

// What the file holds must be able to give `bytes`, before they are allocated: the whole native pixel data,
// or compressed data within kMaxCompressionRatio of it.
void checkPixelDataCanHold(const gdcm::Image& image, std::uint64_t bytes, int columns, int rows, unsigned frames, const std::string& name) {
    const gdcm::DataElement& pixelData = image.GetDataElement();
    if (!image.GetTransferSyntax().IsEncapsulated()) {
        const gdcm::ByteValue* value = pixelData.GetByteValue();
        std::uint64_t have = value ? static_cast<std::uint64_t>(static_cast<std::uint32_t>(value->GetLength())) : 0;
        if (have < bytes)
            throw InputError(name, "PixelData", std::to_string(bytes) + " bytes (" + std::to_string(columns) + " x " + std::to_string(rows) +
                                                    " x " + std::to_string(frames) + " samples)",
                             std::to_string(have) + " bytes");
    } else {
        const gdcm::SequenceOfFragments* fragments = pixelData.GetSequenceOfFragments();
        double have = fragments ? static_cast<double>(fragments->ComputeByteLength()) : 0.0;
        if (bytes > kAlwaysAcceptedBytes && static_cast<double>(bytes) > kMaxCompressionRatio * have)
            throw InputError(name, "PixelData", "compressed data that can hold " + std::to_string(bytes) + " bytes",
                             fmt(have) + " bytes (a ratio above " + fmt(kMaxCompressionRatio) + ")");
    }
}

// Keeps the value bits of the decoded samples and brings them to the type curette stores; returns that type.
ScalarType keepValueBits(std::vector<std::uint8_t>& samples, const gdcm::PixelFormat& format, ScalarType type) {
    const unsigned bitsStored = format.GetBitsStored();
    const bool isSigned = format.GetPixelRepresentation() == 1;
    switch (format.GetScalarType()) {
        case gdcm::PixelFormat::UINT8:
            keepStoredBits<std::uint8_t>(samples, bitsStored, false);
            break;
        case gdcm::PixelFormat::INT8:
            keepStoredBits<std::int8_t>(samples, bitsStored, true);
            samples = widen<std::int8_t, std::int16_t>(samples);
            return ScalarType::Int16;
        case gdcm::PixelFormat::UINT12:
        case gdcm::PixelFormat::UINT16:
        case gdcm::PixelFormat::INT12:
        case gdcm::PixelFormat::INT16:
            keepStoredBits<std::int16_t>(samples, bitsStored, isSigned);
            break;
        case gdcm::PixelFormat::UINT32:
            keepStoredBits<std::uint32_t>(samples, bitsStored, false);
            // Exact up to 2^24, like every value curette stores as float32.
            samples = widen<std::uint32_t, float>(samples);
            return ScalarType::Float32;
        case gdcm::PixelFormat::INT32:
            keepStoredBits<std::int32_t>(samples, bitsStored, true);
            break;
        default: break;
    }
    return type;
}

DecodedImage decodeFile(const fs::path& file, int columns, int rows, unsigned framesNeeded) {
    const std::string name = file.string();
    gdcm::ImageReader reader;
    reader.SetFileName(name.c_str());
    forgetGdcmMessages();
    if (!reader.Read()) throw InputError(name, "PixelData", "an image GDCM can read", "none GDCM can read (no PixelData, or an encoding it does not know)");
    if (gdcmMessages().str().find("Incomplete Pixel Data") != std::string::npos)
        throw InputError(name, "PixelData", "the whole pixel data", "a file that ends inside it (truncated)");
    const gdcm::Image& image = reader.GetImage();
    const unsigned frames = image.GetNumberOfDimensions() >= 3 ? image.GetDimension(2) : 1;
    if (image.GetDimension(0) != static_cast<unsigned>(columns) || image.GetDimension(1) != static_cast<unsigned>(rows) || frames < framesNeeded)
        throw InputError(name, "Columns/Rows/NumberOfFrames",
                         std::to_string(columns) + " x " + std::to_string(rows) + " x " + std::to_string(framesNeeded) + " (as scanned)",
                         std::to_string(image.GetDimension(0)) + " x " + std::to_string(image.GetDimension(1)) + " x " + std::to_string(frames));
    const gdcm::PixelFormat& format = image.GetPixelFormat();
    if (format.GetSamplesPerPixel() != 1)
        throw InputError(name, "SamplesPerPixel", "1 (grey-scale images)", std::to_string(format.GetSamplesPerPixel()));
    const gdcm::PhotometricInterpretation photometric = image.GetPhotometricInterpretation();
    if (photometric != gdcm::PhotometricInterpretation::MONOCHROME1 && photometric != gdcm::PhotometricInterpretation::MONOCHROME2)
        throw InputError(name, "PhotometricInterpretation", "MONOCHROME1 or MONOCHROME2 (grey values)",
                         photometric.GetString() ? photometric.GetString() : "unknown");

    const std::uint64_t pixels = static_cast<std::uint64_t>(columns) * static_cast<std::uint64_t>(rows) * frames;
    const std::uint64_t bytes = image.GetBufferLength();
    std::uint64_t sampleBytes = pixels ? bytes / pixels : 0;
    const ScalarType type = storedType(format, name);
    if (sampleBytes != scalarTypeSize(type) || bytes != pixels * sampleBytes)
        throw InputError(name, "PixelData", std::to_string(pixels) + " samples of " + std::to_string(scalarTypeSize(type)) + " bytes",
                         std::to_string(bytes) + " bytes");
    checkPixelDataCanHold(image, bytes, columns, rows, frames, name);

    // JPEG-LS: GDCM 3.0.21's codec asserts (aborts the process) when a stream's own frame header (SOF55, ITU-T
    // T.87 C.2.2) promises more samples than Rows x Columns. Every frame's header must describe this image.
    const gdcm::TransferSyntax& syntax = image.GetTransferSyntax();
    if (syntax == gdcm::TransferSyntax::JPEGLSLossless || syntax == gdcm::TransferSyntax::JPEGLSNearLossless)
        checkJpegLsFrames(image.GetDataElement(), columns, rows, frames, format.GetSamplesPerPixel(), format.GetBitsAllocated(), name);

    DecodedImage decoded;
    decoded.samples.resize(bytes);
    if (!image.GetBuffer(reinterpret_cast<char*>(decoded.samples.data())))
        throw InputError(name, "PixelData", "pixel data GDCM can decode",
                         std::string("decoding failed (transfer syntax ") + (syntax.GetString() ? syntax.GetString() : "unknown") + ")");
    decoded.type = keepValueBits(decoded.samples, format, type);
    return decoded;
}

double sampleAt(const std::uint8_t* p, ScalarType type) {
    switch (type) {
        case ScalarType::UInt8: return *p;
        case ScalarType::Int16: { std::int16_t v; std::memcpy(&v, p, 2); return v; }
        case ScalarType::UInt16: { std::uint16_t v; std::memcpy(&v, p, 2); return v; }
        case ScalarType::Int32: { std::int32_t v; std::memcpy(&v, p, 4); return v; }
        case ScalarType::Float32: { float v; std::memcpy(&v, p, 4); return v; }
        case ScalarType::Float64: { double v; std::memcpy(&v, p, 8); return v; }
    }
    return 0;
}

}  // namespace

VolumeData readDicomSeries(const DicomSeries& series, const std::string& source, const DicomChoice& choice, bool showIdentifiers) {
    forgetGdcmMessages();
    if (!series.formsVolume()) throw InputError(source, series.label(), series.problemExpected, series.problem);
    const std::size_t pixelsPerSlice = static_cast<std::size_t>(series.dims.x) * static_cast<std::size_t>(series.dims.y);
    const std::size_t sliceCount = series.slices.size();

    // Each file is decoded once, however many of its frames the volume takes.
    std::vector<fs::path> fileOrder;
    std::map<fs::path, std::vector<std::pair<unsigned, std::size_t>>> framesOfFile;  // file -> (frame, slice k)
    for (std::size_t k = 0; k < sliceCount; ++k) {
        auto& frames = framesOfFile[series.slices[k].file];
        if (frames.empty()) fileOrder.push_back(series.slices[k].file);
        frames.emplace_back(series.slices[k].frame, k);
    }
    std::optional<ScalarType> type;
    std::vector<std::uint8_t> samples;
    std::size_t sliceBytes = 0;
    for (const fs::path& file : fileOrder) {
        const auto& frames = framesOfFile[file];
        unsigned framesNeeded = 0;
        for (auto [frame, k] : frames) framesNeeded = std::max(framesNeeded, frame + 1);
        DecodedImage image;
        try {
            image = decodeFile(file, series.dims.x, series.dims.y, framesNeeded);
        } catch (const InputError&) {
            throw;
        } catch (const std::exception& e) {
            throw InputError(file.string(), "PixelData", "pixel data GDCM can decode", e.what());
        }
        if (!type) {
            type = image.type;
            sliceBytes = pixelsPerSlice * scalarTypeSize(*type);
            samples.resize(sliceBytes * sliceCount);
        } else if (image.type != *type) {
            throw InputError(file.string(), "BitsAllocated/PixelRepresentation", std::string("the pixel type of the series' other images (") +
                                                                                      scalarTypeName(*type) + ")",
                             scalarTypeName(image.type));
        }
        for (auto [frame, k] : frames)
            std::memcpy(samples.data() + k * sliceBytes, image.samples.data() + frame * sliceBytes, sliceBytes);
    }

    // One rescale for every slice keeps the stored samples; slices with their own (PET, some MR) are
    // converted to their physical values in float32.
    const DicomSlice& first = series.slices.front();
    bool oneRescale = std::all_of(series.slices.begin(), series.slices.end(), [&](const DicomSlice& s) {
        return s.rescaleSlope == first.rescaleSlope && s.rescaleIntercept == first.rescaleIntercept;
    });
    VolumeData volume;
    if (oneRescale) {
        volume = buildVolume(source, series.dims, *type, samples.data(), false, first.rescaleSlope, first.rescaleIntercept, series.indexToWorld);
    } else {
        std::vector<std::uint8_t> physical(pixelsPerSlice * sliceCount * sizeof(float));
        const std::size_t size = scalarTypeSize(*type);
        for (std::size_t k = 0; k < sliceCount; ++k)
            for (std::size_t p = 0; p < pixelsPerSlice; ++p) {
                std::size_t index = k * pixelsPerSlice + p;
                float v = static_cast<float>(series.slices[k].rescaleSlope * sampleAt(samples.data() + index * size, *type) +
                                             series.slices[k].rescaleIntercept);
                std::memcpy(physical.data() + index * sizeof(float), &v, sizeof v);
            }
        volume = buildVolume(source, series.dims, ScalarType::Float32, physical.data(), false, 1.0, 0.0, series.indexToWorld);
    }
    volume.description = "DICOM " + (series.modality.empty() ? std::string("image") : series.modality) + " " + series.label() + ", " +
                         std::to_string(sliceCount) + (sliceCount == 1 ? " slice" : " slices") +
                         (series.uid.empty() ? std::string() : ", SeriesInstanceUID " + series.uid) + "; opened as " + choice.reason;
    if (showIdentifiers)
        volume.description += "; patient \"" + series.patientName + "\", PatientID \"" + series.patientId + "\"";
    volume.files = fileOrder;
    return volume;
}

}  // namespace curette::io
