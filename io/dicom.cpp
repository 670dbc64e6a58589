// DICOM import: the value text and GDCM's message sink the io/dicom_*.cpp files share, and choosing the
// series to open. Scanning a folder into series is io/dicom_scan.cpp, placing their images in space
// io/dicom_geometry.cpp, decoding the pixels io/dicom_decode.cpp.
#include "io/dicom.h"

#include "io/dicom_values.h"
#include "base/error.h"
#include "base/text.h"

#include <gdcmTrace.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <optional>
#include <tuple>

namespace curette::io {

namespace dicom_detail {

// GDCM writes its warnings and errors to std::cerr; curette reports problems itself, as one line. They go to
// this sink instead, which decodeFile reads for the one warning that changes the result: GDCM pads truncated
// pixel data and goes on, saying only "Incomplete Pixel Data found" (gdcmExplicitDataElement.txx).
std::ostringstream& gdcmMessages() {
    static std::ostringstream sink;
    static const bool redirected = [] {
        gdcm::Trace::SetStream(sink);
        gdcm::Trace::DebugOff();
        gdcm::Trace::WarningOn();
        gdcm::Trace::ErrorOn();
        return true;
    }();
    (void)redirected;
    return sink;
}

void forgetGdcmMessages() { gdcmMessages().str({}); }

// Values are padded to even length with a space (or a NUL for UIs), PS3.5 6.2; some writers leave tabs and line ends.
constexpr std::string_view kPadding{" \0\t\r\n", 5};

std::string trim(std::string_view text) { return std::string(curette::trim(text, kPadding)); }

std::string fmt(double value) {
    char text[32];
    std::snprintf(text, sizeof text, "%.6g", value);
    return text;
}

// The numbers of a multi-valued DS or IS ("a\b\c", PS3.5 6.2), or nothing when any value is not a number.
std::optional<std::vector<double>> numbers(const std::string& text) {
    if (text.empty()) return std::nullopt;
    std::vector<double> values;
    std::size_t start = 0;
    while (true) {
        std::size_t end = text.find('\\', start);
        std::string item(trim(std::string_view(text).substr(start, end == std::string::npos ? std::string::npos : end - start)));
        const char* first = item.data();
        const char* last = item.data() + item.size();
        if (first != last && *first == '+') ++first;
        double value = 0;
        auto [ptr, ec] = std::from_chars(first, last, value);
        if (ec != std::errc() || ptr != last || !std::isfinite(value)) return std::nullopt;
        values.push_back(value);
        if (end == std::string::npos) break;
        start = end + 1;
    }
    return values;
}

std::optional<double> number(const std::string& text) {
    auto values = numbers(text);
    if (!values || values->size() != 1) return std::nullopt;
    return values->front();
}

}  // namespace dicom_detail

namespace {

namespace fs = std::filesystem;
using dicom_detail::number;

std::string seriesList(const std::vector<DicomSeries>& series) {
    std::string list;
    for (const DicomSeries& s : series) {
        if (!list.empty()) list += ", ";
        list += (s.number.empty() ? "(no number)" : s.number) + " (" + s.modality + ", " + std::to_string(s.slices.size()) +
                " images" + (s.description.empty() ? "" : ", \"" + s.description + "\"") + ", " + s.uid + ")";
    }
    return list;
}

}  // namespace

std::string DicomSeries::label() const {
    std::string text = !number.empty() ? "series " + number
                       : !uid.empty()  ? "series with SeriesInstanceUID " + uid
                       : files.empty() ? std::string("a series without number or UID")
                                       : "the series of " + files.front().filename().string();
    if (!description.empty()) text += " \"" + description + "\"";
    return text;
}

DicomChoice chooseDicomSeries(const std::vector<DicomSeries>& series, const std::string& wanted, const std::string& source) {
    if (series.empty()) throw InputError(source, "", "at least one DICOM series", "none");
    if (!wanted.empty()) {
        for (std::size_t i = 0; i < series.size(); ++i)
            if (series[i].uid == wanted) return {i, "asked for by its SeriesInstanceUID"};
        std::vector<std::size_t> matches;
        std::optional<double> wantedNumber = number(wanted);
        for (std::size_t i = 0; i < series.size(); ++i) {
            std::optional<double> n = number(series[i].number);
            if (series[i].number == wanted || (wantedNumber && n && *n == *wantedNumber)) matches.push_back(i);
        }
        if (matches.size() == 1) return {matches.front(), "asked for by its number"};
        if (matches.size() > 1) {
            std::string uids;
            for (std::size_t i : matches) uids += (uids.empty() ? "" : ", ") + series[i].uid;
            throw InputError(source, "series", "a number only one series has, or a SeriesInstanceUID",
                             "\"" + wanted + "\", the number of " + std::to_string(matches.size()) + " series (" + uids + ")");
        }
        throw InputError(source, "series", "the number or SeriesInstanceUID of one of the series: " + seriesList(series),
                         "\"" + wanted + "\"");
    }
    if (series.size() == 1) return {0, "the only series"};
    // The one to plan on: anything before a scout (ImageType LOCALIZER, or at most 3 images), then a volume
    // before what is not one, then the most slices; ties keep the scan order. A scout never opens by default,
    // not even when the main series does not form a volume: then that series opens, and its error says why.
    auto scout = [](const DicomSeries& s) { return s.localizer || s.slices.size() <= 3; };
    auto rank = [&](const DicomSeries& s) { return std::make_tuple(!scout(s), s.formsVolume(), s.slices.size()); };
    std::size_t best = 0;
    for (std::size_t i = 1; i < series.size(); ++i)
        if (rank(series[i]) > rank(series[best])) best = i;
    auto count = [&](auto predicate) { return static_cast<std::size_t>(std::count_if(series.begin(), series.end(), predicate)); };
    const std::size_t candidates = count([&](const DicomSeries& s) { return !scout(s); });
    const std::size_t volumes = count([&](const DicomSeries& s) { return !scout(s) && s.formsVolume(); });
    if (candidates == 0) return {best, "the default: the most slices; all " + std::to_string(series.size()) + " series are scouts of 1-3 images or localizers"};
    if (volumes == 0) return {best, "the default: the most images; none of the " + std::to_string(candidates) + " series that are not scouts forms a volume"};
    return {best, "the default: the most slices of the " + std::to_string(volumes) + " series that form a volume" +
                      (candidates < series.size() ? std::string(" (scouts and localizers aside)") : std::string())};
}

VolumeData readDicomSeries(const fs::path& path, const VolumeReadOptions& options) {
    const std::string source = path.string();
    if (options.volumeIndex != 0)
        throw InputError(source, "volume", "0 for a DICOM series (choose the series by its number or UID instead)",
                         std::to_string(options.volumeIndex));
    std::vector<DicomSeries> series = scanDicom(path, options.showIdentifiers);
    DicomChoice choice = chooseDicomSeries(series, options.series, source);
    return readDicomSeries(series[choice.index], source, choice, options.showIdentifiers);
}

}  // namespace curette::io
