#pragma once
// MetaImage (ITK/VTK MetaIO, https://paraview.org/Wiki/MetaIO/Documentation; Kitware/MetaIO metaImage.cxx):
// `.mha` (text header and data in one file, ElementDataFile = LOCAL) and `.mhd` (header; data in the file
// ElementDataFile names, relative to the header's folder). NDims 3, or 4 (the fourth axis counts volumes; one
// is read). ElementType MET_UCHAR, CHAR, USHORT, SHORT, UINT, INT, ULONG, LONG (4 bytes each, metaTypes.h),
// ULONG_LONG, LONG_LONG, FLOAT, DOUBLE; ElementSpacing (ElementSize as fallback), Offset/Position/Origin,
// TransformMatrix/Rotation/Orientation, all in LPS and converted to RAS; BinaryDataByteOrderMSB (or its synonym
// ElementByteOrderMSB); CompressedData (zlib or gzip) with or without CompressedDataSize; HeaderSize (bytes
// before the data, -1: the data end the file). Refused with an InputError naming the key: vector pixels
// (ElementNumberOfChannels > 1), ASCII data (BinaryData = False), ElementDataFile LIST and %d patterns.

#include "base/volume.h"

#include <filesystem>
#include <span>
#include <string>

namespace curette::io {

// volumeIndex: which 3-D volume of an NDims = 4 image (0-based); out of range names --volume/volume.index.
VolumeData readMetaImage(const std::filesystem::path& path, int volumeIndex = 0);
// A header (and LOCAL data) from memory; `baseDirectory` resolves a separate data file: the fuzzing entry point.
VolumeData readMetaImageBytes(std::span<const std::uint8_t> bytes, const std::string& source,
                              const std::filesystem::path& baseDirectory, int volumeIndex = 0);

}  // namespace curette::io
