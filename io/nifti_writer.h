#pragma once
// Label volumes as NIfTI-1 single files (nifti1.h, https://nifti.nimh.nih.gov/nifti-1): `.nii`, or
// gzip-compressed when the name ends in `.gz`. Header as written:
//   sizeof_hdr 348, magic "n+1", vox_offset 352 (header + the 4-byte extension flag, all zero), dim 3,
//   datatype 2 (uint8, bitpix 8) when every id is <= 255 else 512 (uint16, bitpix 16), little-endian,
//   intent_code 1002 (NIFTI_INTENT_LABEL), scl_slope 1 and scl_inter 0 (ids are the stored values),
//   cal_min 0 / cal_max the largest id, xyzt_units 2 (mm),
//   sform_code 2 (NIFTI_XFORM_ALIGNED_ANAT): srow_x/y/z = rows of the index-to-world affine (RAS mm), as is
//   (NIfTI-1 stores them as float32, so coefficients are rounded to the nearest float),
//   pixdim[1..3] = the affine's column norms,
//   qform_code 2 with the quaternion of the rotation part when the affine is a rotation times a diagonal
//   (columns orthogonal within 1e-6 relative), qfac = pixdim[0] = -1 when the affine mirrors (det < 0) and
//   the third column is negated for the quaternion (nifti1.h METHOD 2); qform_code 0 for a sheared affine.

#include "base/label_map.h"

#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

namespace curette::io {

// What varies between the NIfTI-1 files curette writes; the rest of the header is as described above.
struct NiftiLayout {
    glm::ivec3 dims{0};
    glm::dmat4 indexToWorld{1.0};
    std::int16_t datatype = 2, bitpix = 8, intentCode = 0;
    double calMax = 0;
    std::string description, intentName;   // at most 79 and 15 characters are kept
};
inline constexpr std::size_t kNiftiVoxOffset = 352;
// The header (and the 4-byte extension flag) of such a file, followed by `dataBytes` zero bytes for the voxels.
std::vector<std::uint8_t> niftiHeaderBytes(const NiftiLayout& layout, std::size_t dataBytes, const std::string& source);

// Atomic (base/atomic_file.h): no partial file remains on failure.
void writeNiftiLabelmap(const std::filesystem::path& path, const LabelMap& labels);

}  // namespace curette::io
