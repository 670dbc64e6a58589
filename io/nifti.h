#pragma once
// NIfTI-1 (https://nifti.nimh.nih.gov/nifti-1, the nifti1.h header) and NIfTI-2 (nifti2.h: the same fields,
// 64-bit dims and offsets, double pixdim/quatern/srow): single-file .nii and .nii.gz, and the .hdr/.img pair,
// either endianness. Scalar types uint8, int16, uint16, int32, float32, float64; scl_slope/scl_inter; the
// index-to-world affine from the sform (sform_code > 0), else the qform (qform_code > 0), else pixdim.
// 4-D and 5-D files (dim[0] 4 or 5) hold dim[4] * dim[5] 3-D volumes; one of them is read (0-based index,
// counted with dim[4] varying fastest, as the voxels are stored).

#include "base/volume.h"

#include <filesystem>
#include <span>

namespace curette::io {

// volumeIndex: which 3-D volume of a 4-D/5-D file; out of range is an InputError naming --volume/volume.index.
VolumeData readNifti(const std::filesystem::path& path, int volumeIndex = 0);
// A whole single-file NIfTI (already decompressed) from memory: the fuzzing entry point.
VolumeData readNiftiBytes(std::span<const std::uint8_t> bytes, const std::string& source, int volumeIndex = 0);

// The index-to-world affine of a NIfTI qform (quaternion b, c, d; qfac = pixdim[0], any negative value
// mirroring; offsets), nifti1.h "METHOD 2"; exposed for tests.
glm::dmat4 niftiQformAffine(double b, double c, double d, double qfac, glm::dvec3 pixdim, glm::dvec3 offset);

}  // namespace curette::io
