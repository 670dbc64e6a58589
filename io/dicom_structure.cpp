// The structure of a DICOM file (PS3.5), checked before GDCM reads it; see io/dicom_structure.h.
#include "io/dicom_structure.h"

#include "io/gzip.h"
#include "base/error.h"
#include "base/text.h"

#include <gdcmDict.h>
#include <gdcmDicts.h>
#include <gdcmGlobal.h>
#include <gdcmTag.h>
#include <gdcmVR.h>

#include <algorithm>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>
#include <memory>
#include <sstream>
#include <optional>
#include <utility>

namespace curette::io {

namespace {

namespace fs = std::filesystem;

// PS3.5 6.2: a UI is padded with a NUL, other values with a space.
constexpr std::string_view kPadding{" \0", 2};

// One walk over one file: the meta group (explicit VR little endian), then the data set in its transfer
// syntax (or, without one, in each encoding GDCM could guess).
class FileStructure {
public:
    FileStructure(const fs::path& file, std::uint64_t toleratedShortfall)
        : in_(std::make_unique<std::ifstream>(file, std::ios::binary)), toleratedShortfall_(toleratedShortfall) {
        std::error_code ec;
        size_ = fs::file_size(file, ec);
        if (ec) size_ = 0;
    }

    // "" when the file is well formed, else what is wrong.
    std::string problem() {
        if (!*in_) return "a file that cannot be opened";
        char prefix[4] = {};
        // PS3.10 7.1: a 128-byte preamble and "DICM"; GDCM also reads files without them.
        std::uint64_t pos = size_ >= 132 && seekTo(128) && in_->read(prefix, 4) && std::memcmp(prefix, "DICM", 4) == 0 ? 132 : 0;
        // File meta information: group 0002, explicit VR little endian (PS3.10 7.1).
        std::string syntax;
        while (pos + 8 <= size_) {
            std::uint16_t group = 0;
            if (!seekTo(pos) || !read16(group, false) || group != 0x0002) break;
            std::optional<Element> e = header(pos, true, false);
            if (!e) return problem_.empty() ? "an unreadable data element at byte " + std::to_string(pos) : problem_;
            if (e->undefined) return "an undefined length in the file meta information, " + tagText(*e);
            if (e->length > size_ - e->valueAt) return tooLong(*e, size_);
            if (e->element == 0x0010) syntax = valueText(e->valueAt, e->length);
            pos = e->valueAt + e->length;
        }
        // GDCM's meta reader asserts when the file ends after the meta group, or inside the element after it.
        if (size_ - pos < 8) return "no data set after the file meta information (the file ends at byte " + std::to_string(size_) + ")";
        if (syntax == "1.2.840.10008.1.2.1.99") {
            // Deflated (PS3.5 A.5): the data set is one raw deflate stream of explicit VR little endian. It must
            // inflate, and what it inflates to is walked like any data set: GDCM otherwise read such a file's
            // bytes as they stand and allocated what they declared (1.3 GB for 2.8 kB, found by the fuzz run).
            std::vector<std::uint8_t> rest(size_ - pos);
            if (!seekTo(pos) || !in_->read(reinterpret_cast<char*>(rest.data()), static_cast<std::streamsize>(rest.size())))
                return "an unreadable deflated data set at byte " + std::to_string(pos);
            std::vector<std::uint8_t> inflated;
            try {
                // Deflate cannot expand by more than 1032 to 1; beyond that the stream is not deflate.
                inflated = inflateRaw(rest, "", 1100 * std::uint64_t(rest.size()) + 4096);
            } catch (const InputError& e) {
                return "a deflated data set (transfer syntax 1.2.840.10008.1.2.1.99) that does not inflate: " + e.got();
            }
            std::string bytes(pos, '\0');
            bytes.append(inflated.begin(), inflated.end());
            in_ = std::make_unique<std::istringstream>(std::move(bytes));
            size_ = pos + inflated.size();
            walk(pos, size_, false, Contents::DataSet, 0);
            return problem_;
        }
        if (!syntax.empty()) {
            explicitVr_ = syntax != "1.2.840.10008.1.2";
            bigEndian_ = syntax == "1.2.840.10008.1.2.2";
            walk(pos, size_, false, Contents::DataSet, 0);
            return problem_;
        }
        // No transfer syntax: GDCM guesses the encoding from the first element, and only that reading is
        // checked (a file well formed in another encoding than GDCM's guess made GDCM assert).
        std::string guessProblem;
        std::optional<std::pair<bool, bool>> encoding = guessedEncoding(pos, guessProblem);
        if (!encoding) return guessProblem;
        explicitVr_ = encoding->first, bigEndian_ = encoding->second;
        walk(pos, size_, false, Contents::DataSet, 0);
        if (!problem_.empty()) pixelDataTooLong_ = false;  // the guess may be wrong: nothing of the file is trusted
        return problem_;
    }

    bool onlyTruncatedPixelData() const { return pixelDataTooLong_; }

private:
    // The encoding (explicit VR, big endian) GDCM 3.0 reads a data set in that has no transfer syntax
    // (gdcm::FileMetaInformation::ReadCompat, from the first element's tag and the two bytes after it): group
    // 0008 little endian (explicit when those bytes are a VR) or big endian (explicit only: implicit big endian
    // is ACR-NEMA, which GDCM refuses); element 0010 (a private creator), implicit little endian; otherwise a
    // VR there means explicit, big endian when the tag read little endian has a group or element above 00FF.
    // Nothing, with the reason, when GDCM finds no encoding.
    std::optional<std::pair<bool, bool>> guessedEncoding(std::uint64_t pos, std::string& problem) {
        unsigned char b[6] = {};
        if (pos + 6 > size_ || !seekTo(pos) || !in_->read(reinterpret_cast<char*>(b), 6)) {
            problem = "a file that ends inside its first data element (byte " + std::to_string(pos) + ")";
            return std::nullopt;
        }
        const unsigned group = b[0] | (b[1] << 8), element = b[2] | (b[3] << 8);
        const char vrText[3] = {static_cast<char>(b[4]), static_cast<char>(b[5]), '\0'};
        const bool vr = gdcm::VR::GetVRType(vrText) != gdcm::VR::VR_END;
        if (group == 0x0008) return std::pair{vr, false};
        if (group == 0x0800) {
            if (vr) return std::pair{true, true};
            problem = "a data set in implicit VR big endian (ACR-NEMA), which DICOM does not define";
            return std::nullopt;
        }
        if (element == 0x0010) return std::pair{false, false};
        if (vr) return std::pair{true, group > 0xff || element > 0xff};
        problem = "no transfer syntax, and a first data element that is neither explicit nor group 0008 (byte " +
                  std::to_string(pos) + ")";
        return std::nullopt;
    }

    struct Element {
        std::uint16_t group = 0, element = 0;
        char vr[2] = {' ', ' '};
        std::uint64_t at = 0, length = 0, valueAt = 0;
        bool undefined = false;
    };
    enum class Contents { DataSet, Items, Fragments };
    static constexpr std::uint32_t kUndefined = 0xffffffffu;
    // PS3.5 7.1.2: the VRs with a reserved field and a 4-byte length, and those with a 2-byte length.
    static constexpr const char* kLongForm[] = {"OB", "OD", "OF", "OL", "OV", "OW", "SQ", "SV", "UC", "UN", "UR", "UT", "UV"};
    static constexpr const char* kShortForm[] = {"AE", "AS", "AT", "CS", "DA", "DS", "DT", "FL", "FD", "IS", "LO",
                                                 "LT", "PN", "SH", "SL", "SS", "ST", "TM", "UI", "UL", "US"};

    bool seekTo(std::uint64_t pos) {
        in_->clear();
        return static_cast<bool>(in_->seekg(static_cast<std::streamoff>(pos)));
    }
    bool read16(std::uint16_t& v, bool bigEndian) {
        unsigned char b[2];
        if (!in_->read(reinterpret_cast<char*>(b), 2)) return false;
        v = static_cast<std::uint16_t>(bigEndian ? (b[0] << 8) | b[1] : (b[1] << 8) | b[0]);
        return true;
    }
    bool read32(std::uint32_t& v, bool bigEndian) {
        std::uint16_t a = 0, b = 0;
        if (!read16(a, bigEndian) || !read16(b, bigEndian)) return false;
        v = bigEndian ? (std::uint32_t{a} << 16) | b : (std::uint32_t{b} << 16) | a;
        return true;
    }
    std::string valueText(std::uint64_t at, std::uint64_t length) {
        std::string text(static_cast<std::size_t>(std::min<std::uint64_t>(length, 64)), '\0');
        if (!seekTo(at) || !in_->read(text.data(), static_cast<std::streamsize>(text.size()))) return {};
        return std::string(trim(text, kPadding));
    }
    static bool isVr(const char* vr, const char* const* list, std::size_t count) {
        return std::any_of(list, list + count, [&](const char* code) { return vr[0] == code[0] && vr[1] == code[1]; });
    }
    bool is(const Element& e, const char* vr) const { return e.vr[0] == vr[0] && e.vr[1] == vr[1]; }

    static std::string tagText(const Element& e) {
        char text[48];
        std::snprintf(text, sizeof text, "(%04X,%04X) at byte %llu", e.group, e.element, static_cast<unsigned long long>(e.at));
        return text;
    }
    std::string tooLong(const Element& e, std::uint64_t end) const {
        std::string text = tagText(e);
        text += " declares " + std::to_string(e.length) + " bytes, but ";
        text += std::to_string(end > e.valueAt ? end - e.valueAt : 0);
        text += end == size_ ? " are left in the file" : " are left in its item or sequence";
        return text;
    }
    std::uint64_t fail(std::string problem) {
        problem_ = std::move(problem);
        return 0;
    }

    // The element header at pos (tag, VR when explicit, length); nothing, with problem_ set, when it cannot be.
    std::optional<Element> header(std::uint64_t pos, bool explicitVr, bool bigEndian) {
        Element e;
        e.at = pos;
        if (pos + 8 > size_ || !seekTo(pos) || !read16(e.group, bigEndian) || !read16(e.element, bigEndian)) {
            fail("a file that ends inside a data element header at byte " + std::to_string(pos));
            return std::nullopt;
        }
        std::uint32_t length = 0;
        if (e.group == 0xfffe || !explicitVr) {  // items and delimiters never have a VR (PS3.5 7.5)
            if (!read32(length, bigEndian)) return std::nullopt;
            e.valueAt = pos + 8;
        } else {
            if (!in_->read(e.vr, 2)) return std::nullopt;
            if (isVr(e.vr, kLongForm, std::size(kLongForm))) {
                if (pos + 12 > size_ || !seekTo(pos + 8) || !read32(length, bigEndian)) {
                    fail("a file that ends inside a data element header at byte " + std::to_string(pos));
                    return std::nullopt;
                }
                e.valueAt = pos + 12;
            } else if (isVr(e.vr, kShortForm, std::size(kShortForm))) {
                std::uint16_t shortLength = 0;
                if (!read16(shortLength, bigEndian)) return std::nullopt;
                length = shortLength;
                e.valueAt = pos + 8;
            } else {
                fail("a data element without a valid VR, " + tagText(e));
                return std::nullopt;
            }
            // A public element's VR is the one PS3.6 gives it (GDCM's gdcm::Attribute asserts so).
            if (e.group % 2 == 0 && e.element != 0x0000) {
                const gdcm::VR expected =
                    gdcm::Global::GetInstance().GetDicts().GetPublicDict().GetDictEntry(gdcm::Tag(e.group, e.element)).GetVR();
                const gdcm::VR found = gdcm::VR::GetVRTypeFromFile(e.vr);
                if (expected != gdcm::VR::INVALID && expected != gdcm::VR::UN && !expected.Compatible(found)) {
                    fail("a data element with the VR " + std::string(e.vr, 2) + " where PS3.6 gives " +
                         (gdcm::VR::GetVRString(expected) ? gdcm::VR::GetVRString(expected) : "another") + ", " + tagText(e));
                    return std::nullopt;
                }
            }
        }
        e.undefined = length == kUndefined;
        e.length = e.undefined ? 0 : length;
        return e;
    }

    // Walks [pos, end) holding data elements, the items of a sequence or the fragments of encapsulated pixel
    // data; `delimited`: an undefined length, closed by its delimiter. Returns the position after it, or 0
    // with problem_ set.
    std::uint64_t walk(std::uint64_t pos, std::uint64_t end, bool delimited, Contents contents, int depth) {
        if (depth > 32) return fail("sequences nested deeper than 32 levels");
        while (true) {
            // Up to 3 trailing bytes are tolerated (GDCM stops at the end of the file inside a tag, but asserts
            // inside a VR or length).
            if (pos == end || (!delimited && depth == 0 && end - pos < 4)) break;
            std::optional<Element> e = header(pos, explicitVr_, bigEndian_);
            if (!e) return problem_.empty() ? fail("an unreadable data element at byte " + std::to_string(pos)) : 0;
            const bool item = e->group == 0xfffe && e->element == 0xe000;
            const bool itemEnd = e->group == 0xfffe && e->element == 0xe00d;
            const bool sequenceEnd = e->group == 0xfffe && e->element == 0xe0dd;
            if (itemEnd || sequenceEnd) {
                // PS3.5 7.5: a delimiter's length is zero (GDCM reads a sequence delimiter among fragments as a
                // fragment and allocates what its length says: 1.3 GB for 12 bytes, found by the fuzz run).
                if (e->length != 0 || e->undefined)
                    return fail(std::string(itemEnd ? "an item" : "a sequence") + " delimiter with a length of " +
                                (e->undefined ? std::string("0xFFFFFFFF") : std::to_string(e->length)) + " (PS3.5 7.5: 0), " + tagText(*e));
                if (delimited && (itemEnd ? contents == Contents::DataSet : contents != Contents::DataSet)) return e->valueAt;
                return fail(std::string(itemEnd ? "an item" : "a sequence") + " delimiter where none belongs, " + tagText(*e));
            }
            if (contents == Contents::DataSet ? item || e->group == 0xfffe : !item)
                return fail((contents == Contents::DataSet ? "an item among data elements, " : "a data element among items, ") + tagText(*e));
            const bool pixelData = depth == 0 && e->group == 0x7fe0 && e->element == 0x0010;
            if (!e->undefined && e->length > end - e->valueAt) {
                pixelDataTooLong_ = pixelData && end == size_ && e->length - (end - e->valueAt) <= toleratedShortfall_;
                return fail(tooLong(*e, end));
            }
            // What the value holds, when it holds more structure.
            std::optional<Contents> inner;
            bool innerImplicit = !explicitVr_;
            if (contents == Contents::Items) {
                inner = Contents::DataSet;
            } else if (contents == Contents::DataSet && explicitVr_ && is(*e, "SQ")) {
                inner = Contents::Items;
            } else if (contents == Contents::DataSet && e->undefined) {
                // Undefined lengths: encapsulated pixel data (A.4), a UN sequence in implicit little endian
                // (6.2.2), or in implicit VR any sequence.
                if (e->group == 0x7fe0 && e->element == 0x0010 && (!explicitVr_ || is(*e, "OB") || is(*e, "OW"))) inner = Contents::Fragments;
                else if (!explicitVr_ || is(*e, "UN")) inner = Contents::Items, innerImplicit = true;
            }
            if (e->undefined && !inner) return fail("an undefined length where none may be, " + tagText(*e));
            if (inner) {
                const bool explicitOuter = explicitVr_, bigEndianOuter = bigEndian_;
                if (innerImplicit && explicitVr_) explicitVr_ = false, bigEndian_ = false;
                std::uint64_t after = e->undefined ? walk(e->valueAt, end, true, *inner, depth + 1)
                                                   : walk(e->valueAt, e->valueAt + e->length, false, *inner, depth + 1);
                explicitVr_ = explicitOuter, bigEndian_ = bigEndianOuter;
                if (after == 0) return 0;
                pos = e->undefined ? after : e->valueAt + e->length;
            } else {
                pos = e->valueAt + e->length;
            }
        }
        if (delimited) return fail("a file that ends inside a sequence or item of undefined length (no delimiter)");
        return pos;
    }

    std::unique_ptr<std::istream> in_;   // the file, or the meta group and the inflated data set of a deflated one
    std::uint64_t toleratedShortfall_ = 0;
    std::uint64_t size_ = 0;
    bool explicitVr_ = true, bigEndian_ = false;
    std::string problem_;
    bool pixelDataTooLong_ = false;
};


}  // namespace

DicomStructure checkDicomStructure(const fs::path& file, std::uint64_t toleratedPixelDataShortfall) {
    FileStructure structure(file, toleratedPixelDataShortfall);
    DicomStructure result;
    result.problem = structure.problem();
    result.onlyTruncatedPixelData = !result.problem.empty() && structure.onlyTruncatedPixelData();
    return result;
}

}  // namespace curette::io
