#pragma once
// NIfTI-1 (https://nifti.nimh.nih.gov/nifti-1, the nifti1.h header): single-file .nii and .nii.gz, and the
// .hdr/.img pair. Scalar types uint8, int16, uint16, int32, float32, float64; scl_slope/scl_inter; the
// index-to-world affine from the sform (sform_code > 0), else the qform (qform_code > 0), else pixdim.

#include "base/volume.h"

#include <filesystem>
#include <span>

namespace curette::io {

VolumeData readNifti(const std::filesystem::path& path);
// A whole single-file NIfTI (already decompressed) from memory: the fuzzing entry point.
VolumeData readNiftiBytes(std::span<const std::uint8_t> bytes, const std::string& source);

// The index-to-world affine of a NIfTI qform (quaternion b, c, d; qfac = pixdim[0]; offsets), nifti1.h
// "METHOD 2"; exposed for tests.
glm::dmat4 niftiQformAffine(double b, double c, double d, double qfac, glm::dvec3 pixdim, glm::dvec3 offset);

}  // namespace curette::io
