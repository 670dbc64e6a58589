#pragma once
// Whether a file is a well-formed DICOM stream, checked before GDCM reads it.
//
// GDCM 3.0 is made to read broken files: when a data element does not parse it tries other readings (an
// unknown VR as implicit, 16-bit lengths), it allocates and zero-fills the length an element declares before
// reading it, and Debian builds it with its assert()s on. A few corrupt bytes can so make it ask for 4 GB or
// abort the process (both found by tests/fuzz/fuzz_dicom.cpp). This walk checks the structure PS3.5 defines
// (7.1 data elements and their VRs, 7.5 sequences, items and delimiters, A.4 encapsulated fragments, 6.2.2 UN
// of undefined length), each public element's VR against PS3.6 (GDCM's dictionary), and every declared
// length against what is left, so that only a file that passes goes to GDCM. Deflated data sets (their
// elements are inside the deflate stream) are not walked.

#include <cstdint>
#include <filesystem>
#include <string>

namespace curette::io {

struct DicomStructure {
    std::string problem;  // "" when the file is well formed, else what is wrong and where (tag, byte offset)
    // The one problem is native pixel data longer than the rest of the file, by at most the tolerated
    // shortfall: a file cut short, whose header GDCM can still read (it allocates the declared pixel data and
    // pads what is missing). Cut-short encapsulated pixel data makes GDCM assert, so it is never this.
    bool onlyTruncatedPixelData = false;
};

DicomStructure checkDicomStructure(const std::filesystem::path& file, std::uint64_t toleratedPixelDataShortfall);

}  // namespace curette::io
