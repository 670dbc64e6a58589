// curette info FILE: what a volume file holds, before rendering it.
#include "tools/command_line.h"
#include "tools/commands/commands.h"
#include "io/dicom.h"
#include "io/dicom_plan_reader.h"
#include "io/volume_file.h"
#include "scene/volume_statistics.h"
#include "base/error.h"
#include "render/model/volume_geometry.h"
#include "render/model/volume_layout.h"

#include <algorithm>
#include <cstdio>
#include <optional>

namespace curette::commands {

namespace {

ScalarType parseType(const std::string& text) {
    const std::pair<const char*, ScalarType> names[] = {{"uint8", ScalarType::UInt8},     {"int16", ScalarType::Int16},
                                                        {"uint16", ScalarType::UInt16},   {"int32", ScalarType::Int32},
                                                        {"float32", ScalarType::Float32}, {"float64", ScalarType::Float64}};
    for (auto [name, type] : names)
        if (text == name) return type;
    throw InputError("<command line>", "--raw-type", "one of uint8, int16, uint16, int32, float32, float64", "\"" + text + "\"");
}

// DICOM: the table of the series found and which one opens, then that series as a volume. Patient name and
// ids are read, and printed, only with --show-identifiers.
VolumeData listAndReadDicom(const std::string& path, const io::VolumeReadOptions& options) {
    std::vector<io::DicomSeries> series = io::scanDicom(path, options.showIdentifiers);
    io::DicomChoice choice = io::chooseDicomSeries(series, options.series, path);
    std::printf("DICOM        %zu series\n", series.size());
    std::printf("     %-8s %-32s %-8s %7s  %-19s %s\n", "series", "description", "modality", "slices", "dimensions", "SeriesInstanceUID");
    for (std::size_t i = 0; i < series.size(); ++i) {
        const io::DicomSeries& s = series[i];
        std::string dims = std::to_string(s.dims.x) + " x " + std::to_string(s.dims.y) + " x " + std::to_string(s.dims.z);
        std::printf("  %-2s %-8s %-32s %-8s %7zu  %-19s %s%s\n", i == choice.index ? "->" : "", s.number.c_str(), s.description.c_str(),
                    s.modality.c_str(), s.slices.size(), dims.c_str(), s.uid.c_str(), s.localizer ? "  (localizer)" : "");
        if (!s.formsVolume()) std::printf("        not a volume: %s\n", s.problem.c_str());
        if (options.showIdentifiers)
            std::printf("        patient \"%s\", PatientID \"%s\", birth date \"%s\", accession \"%s\"\n", s.patientName.c_str(),
                        s.patientId.c_str(), s.patientBirthDate.c_str(), s.accessionNumber.c_str());
    }
    std::printf("opens        %s: %s\n", series[choice.index].label().c_str(), choice.reason.c_str());
    std::fflush(stdout);  // the table stays above an error line about the series that opens
    return io::readDicomSeries(series[choice.index], path, choice, options.showIdentifiers);
}

// A DICOM Segmentation (its segments, then it as a label volume: ids are segment numbers) or an RT Structure
// Set (its ROIs); no patient identifier is read. Empty for any other file, and after an RT Structure Set.
std::optional<VolumeData> describeDicomPlanObject(const std::string& path, bool& described) {
    described = false;
    if (!std::filesystem::is_regular_file(path)) return std::nullopt;
    std::string sopClass = io::dicomSopClassOf(path);
    if (sopClass == io::kRtStructureSetStorage) {
        std::vector<io::DicomRoiSummary> rois = io::readRtStructRois(path);
        std::printf("file         %s\n", path.c_str());
        std::printf("DICOM RTSTRUCT  %zu ROIs\n", rois.size());
        std::printf("  %-6s %-32s %-12s %-14s %-13s %8s %8s %8s\n", "number", "name", "type", "algorithm", "colour", "contours", "points", "slices");
        for (const io::DicomRoiSummary& r : rois) {
            std::string colour = std::to_string(r.color.r) + " " + std::to_string(r.color.g) + " " + std::to_string(r.color.b);
            std::printf("  %-6d %-32s %-12s %-14s %-13s %8zu %8zu %8zu\n", r.number, r.name.c_str(), r.interpretedType.c_str(),
                        r.generationAlgorithm.c_str(), colour.c_str(), r.contours, r.points, r.slices);
        }
        described = true;
        return std::nullopt;
    }
    if (sopClass != io::kSegmentationStorage) return std::nullopt;
    io::DicomSegmentationVolume seg = io::readDicomSegmentation(path);
    std::printf("DICOM SEG    %zu segments, %zu frames, series \"%s\"\n", seg.segments.size(), seg.frames, seg.seriesDescription.c_str());
    std::printf("  %-7s %-32s %-14s %-15s %7s %10s\n", "segment", "label", "algorithm", "colour (sRGB)", "frames", "voxels");
    for (const io::DicomSegmentSummary& s : seg.segments) {
        char colour[32];
        std::snprintf(colour, sizeof colour, "%.2f %.2f %.2f", s.color.r, s.color.g, s.color.b);
        std::printf("  %-7d %-32s %-14s %-15s %7zu %10llu\n", s.number, s.label.c_str(), s.algorithmType.c_str(), colour, s.frames,
                    static_cast<unsigned long long>(s.voxels));
    }
    std::printf("label volume each voxel the lowest segment number covering it (0: none)\n");
    described = true;
    return buildVolume(path, seg.labels.dims, ScalarType::UInt16, reinterpret_cast<const std::uint8_t*>(seg.labels.ids.data()), false, 1.0, 0.0,
                       seg.labels.indexToWorld);
}

// --gl: the EGL platforms and devices found, and the context a headless command would use (--gpu).
int describeGl(const CommandLine& cl) {
    gl::GpuChoice choice = gpuChoice(cl);   // a bad --gpu is an error before anything is listed
    gl::EglPlatforms platforms = gl::queryEglPlatforms();
    auto yesNo = [](bool b) { return b ? "yes" : "no"; };
    std::printf("EGL platforms\n");
    std::printf("  device (EGL_EXT_device_enumeration + EGL_EXT_platform_device)  %s\n",
                yesNo(platforms.deviceEnumeration && platforms.platformDevice));
    std::printf("  surfaceless (EGL_MESA_platform_surfaceless)                    %s\n", yesNo(platforms.surfaceless));
    std::printf("EGL devices  %zu\n", platforms.devices.size());
    // The device extensions that decide how curette uses a device.
    const char* telling[] = {"EGL_MESA_device_software", "EGL_EXT_device_drm", "EGL_EXT_device_drm_render_node", "EGL_NV_device_cuda",
                             "EGL_EXT_device_persistent_id"};
    for (const gl::EglDevice& d : platforms.devices) {
        std::printf("  %s\n", d.describe().c_str());
        std::string found;
        for (const char* e : telling)
            if (d.hasExtension(e)) found += std::string(found.empty() ? "" : " ") + e;
        std::printf("     extensions %s\n", found.empty() ? "(none of the ones curette looks at)" : found.c_str());
        if (!d.problem.empty()) continue;
        try {
            auto probe = gl::createHeadlessContext({gl::GpuChoice::Kind::Device, d.index});
            std::printf("     GL         %s | %s | %s\n", probe->info().vendor.c_str(), probe->info().renderer.c_str(), probe->info().version.c_str());
        } catch (const SystemError& e) {
            std::printf("     GL         none: %s\n", e.what());
        }
    }
    std::string asked = cl.valueOr("gpu", "automatic");
    std::vector<gl::HeadlessTarget> targets = gl::headlessTargets(platforms, choice);
    std::printf("--gpu %s tries  ", asked.c_str());
    for (std::size_t i = 0; i < targets.size(); ++i) std::printf("%s%s", i ? ", then " : "", targets[i].describe().c_str());
    std::printf("\n");
    std::fflush(stdout);
    auto context = gl::createHeadlessContext(choice);
    const gl::ContextInfo& i = context->info();
    std::printf("context      %s\n", i.platform.c_str());
    std::printf("GL_VENDOR    %s\nGL_RENDERER  %s\nGL_VERSION   %s\nGLSL         %s\n", i.vendor.c_str(), i.renderer.c_str(), i.version.c_str(),
                i.glslVersion.c_str());
    std::printf("limits       3D textures %d, 2D textures %d, compute groups %d x %d x %d\n", i.max3DTextureSize, i.maxTextureSize,
                i.maxComputeWorkGroupCount[0], i.maxComputeWorkGroupCount[1], i.maxComputeWorkGroupCount[2]);
    std::printf("timing       %s\n", i.softwareRenderer ? "software renderer: benches time with the wall clock"
                                                         : (i.timerQueries ? "GPU timer queries" : "no timer queries: the wall clock"));
    return 0;
}

int info(const CommandLine& cl) {
    if (cl.flag("gl")) {
        if (!cl.positional().empty()) throw InputError("<command line>", cl.positional()[0], "no FILE with --gl (curette info --gl [--gpu N])");
        return describeGl(cl);
    }
    if (cl.value("gpu")) throw InputError("<command line>", "--gpu", "together with --gl (a volume file needs no GL)");
    if (cl.positional().size() != 1)
        throw InputError("<command line>", "FILE", "exactly one volume file or DICOM folder: curette info FILE [options], or curette info --gl",
                         std::to_string(cl.positional().size()) + " arguments");
    io::VolumeReadOptions options;
    if (auto v = cl.value("volume")) options.volumeIndex = CommandLine::parseInt("volume", *v, 0, 1 << 20);
    if (auto s = cl.value("series")) options.series = *s;
    options.showIdentifiers = cl.flag("show-identifiers");
    if (auto dims = cl.value("raw-dims")) {
        io::RawLayout layout;
        std::string text = *dims;
        std::replace(text.begin(), text.end(), 'x', ',');
        auto d = CommandLine::parseIntList("raw-dims", text, 1, 1 << 20);
        if (d.size() != 3) throw InputError("<command line>", "--raw-dims", "XxYxZ, e.g. 64x64x32", "\"" + *dims + "\"");
        layout.dims = {d[0], d[1], d[2]};
        layout.type = parseType(cl.required("raw-type"));
        if (auto s = cl.value("raw-spacing")) {
            std::string t = *s;
            std::vector<double> v;
            std::size_t start = 0;
            while (true) {
                std::size_t comma = t.find(',', start);
                v.push_back(CommandLine::parseDouble("raw-spacing", t.substr(start, comma - start), 1e-9, 1e9));
                if (comma == std::string::npos) break;
                start = comma + 1;
            }
            if (v.size() != 3) throw InputError("<command line>", "--raw-spacing", "three numbers, e.g. 1,1,2", "\"" + t + "\"");
            layout.spacing = {v[0], v[1], v[2]};
        }
        layout.bigEndian = cl.flag("raw-big-endian");
        if (auto h = cl.value("raw-header-bytes")) layout.headerBytes = static_cast<std::uint64_t>(CommandLine::parseDouble("raw-header-bytes", *h, 0, 1e15));
        layout.gzip = cl.flag("raw-gzip");
        options.format = io::VolumeFormat::Raw;
        options.raw = layout;
    }
    const std::string& path = cl.positional()[0];
    const bool dicom = options.format == io::VolumeFormat::Auto && std::filesystem::exists(path) && io::looksLikeDicom(path);
    bool planObject = false;
    std::optional<VolumeData> segmentation = dicom ? describeDicomPlanObject(path, planObject) : std::nullopt;
    if (planObject && !segmentation) return 0;   // an RT Structure Set: its ROIs are all there is
    VolumeData volume = segmentation ? std::move(*segmentation) : dicom ? listAndReadDicom(path, options) : io::readVolume(path, options);
    VolumeGeometry g{volume.dims, volume.indexToWorld};
    VolumeStatistics s = computeStatistics(volume);

    const char* storage = volume.format == StorageFormat::UNorm8 ? "R8" : volume.format == StorageFormat::UNorm16 ? "R16" : "R32F";
    glm::dvec3 sp = g.spacing();
    std::printf("file         %s\n", path.c_str());
    if (!volume.description.empty()) std::printf("description  %s\n", volume.description.c_str());
    std::printf("type         %s (GPU texture %s, %zu bytes)\n", scalarTypeName(volume.sourceType), storage, volume.voxels.size());
    std::printf("dimensions   %d x %d x %d (%zu voxels)\n", volume.dims.x, volume.dims.y, volume.dims.z, volume.voxelCount());
    {
        // How the renderer will store it: GL-free, so for a stated limit (llvmpipe's by default; `info --gl` prints
        // the context's GL_MAX_3D_TEXTURE_SIZE).
        int limit = 2048;
        if (auto t = cl.value("texture-limit")) limit = static_cast<int>(CommandLine::parseDouble("texture-limit", *t, 2, 1 << 20));
        try {
            VolumeLayout l = VolumeLayout::forLimit(volume.dims, limit, path);
            std::printf("GPU layout   %s (3D texture limit %d)\n", l.describe().c_str(), limit);
            std::printf("GPU V        %.3f bytes per voxel\n",
                        static_cast<double>(l.texelCount() * (volume.voxels.size() / volume.voxelCount())) / static_cast<double>(volume.voxelCount()));
        } catch (const InputError& e) {
            std::printf("GPU layout   none fits the 3D texture limit %d: %s\n", limit, e.what());
        }
    }
    if (volume.volumeCount > 1)
        std::printf("volumes      %d (showing index %d, --volume N)\n", volume.volumeCount, volume.volumeIndex);
    std::printf("spacing      %g x %g x %g mm\n", sp.x, sp.y, sp.z);
    std::printf("affine       index (i,j,k) -> world mm (RAS)\n");
    for (int r = 0; r < 3; ++r)
        std::printf("             [ %9.4f %9.4f %9.4f %10.4f ]\n", volume.indexToWorld[0][r], volume.indexToWorld[1][r],
                    volume.indexToWorld[2][r], volume.indexToWorld[3][r]);
    glm::dvec3 lo(1e300), hi(-1e300);
    for (const glm::dvec3& c : g.worldCorners()) lo = glm::min(lo, c), hi = glm::max(hi, c);
    std::printf("world box    x [%.2f, %.2f]  y [%.2f, %.2f]  z [%.2f, %.2f] mm\n", lo.x, hi.x, lo.y, hi.y, lo.z, hi.z);
    std::printf("values       min %g  max %g  mean %.4g  std %.4g  non-zero %.1f %%\n", s.min, s.max, s.mean,
                s.standardDeviation, 100.0 * s.nonZeroFraction);
    if (volume.noDataVoxels > 0)
        std::printf("no data      %llu voxels (NaN/Inf): transparent\n", static_cast<unsigned long long>(volume.noDataVoxels));
    std::printf("percentiles  1%%: %.4g  25%%: %.4g  50%%: %.4g  75%%: %.4g  99%%: %.4g\n", s.percentiles[0],
                s.percentiles[1], s.percentiles[2], s.percentiles[3], s.percentiles[4]);
    std::printf("histogram    (%zu bins over [min, max], bar length ~ log count)\n", s.histogram.size());
    std::uint64_t top = *std::max_element(s.histogram.begin(), s.histogram.end());
    double width = s.histogram.empty() ? 0 : (s.max - s.min) / static_cast<double>(s.histogram.size());
    for (std::size_t b = 0; b < s.histogram.size(); ++b) {
        std::uint64_t count = s.histogram[b];
        int bar = count == 0 ? 0 : 1 + static_cast<int>(39.0 * std::log1p(static_cast<double>(count)) / std::log1p(static_cast<double>(top)));
        std::printf("  %10.4g .. %-10.4g %10llu %s\n", s.min + width * static_cast<double>(b),
                    s.min + width * static_cast<double>(b + 1), static_cast<unsigned long long>(count),
                    std::string(static_cast<std::size_t>(bar), '#').c_str());
    }
    return 0;
}

}  // namespace

Command infoCommand() {
    return {{"info", "FILE | --gl", "what a volume file (or DICOM folder) holds: dimensions, spacing, affine, type, value range, histogram; with --gl the EGL devices and platforms and the GL context headless commands get",
             {{"gl", false, "instead of a file: the EGL devices and platforms, and the GL context headless commands get"},
              gpuOption(),
              {"texture-limit", true, "the GPU's GL_MAX_3D_TEXTURE_SIZE the layout line assumes (default 2048, llvmpipe's; info --gl prints it)"},
              {"raw-dims", true, "raw file: dimensions XxYxZ"},
              {"raw-type", true, "raw file: uint8|int16|uint16|int32|float32|float64"},
              {"raw-spacing", true, "raw file: spacing in mm, e.g. 1,1,2 (default 1,1,1)"},
              {"raw-big-endian", false, "raw file: samples are big-endian"},
              {"raw-header-bytes", true, "raw file: bytes to skip first"},
              {"raw-gzip", false, "raw file: the file is gzip-compressed"},
              {"volume", true, "4-D/5-D files: the volume to describe (0-based, default 0)"},
              {"series", true, "DICOM: the series to describe, by number or SeriesInstanceUID"},
              {"show-identifiers", false, "DICOM: print patient name and ids (never printed otherwise)"}}},
            &info};
}

}  // namespace curette::commands
