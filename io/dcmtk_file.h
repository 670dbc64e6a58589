#pragma once
// Saving a DCMTK file format object atomically (base/atomic_file.h): DCMTK writes a scratch file, whose
// bytes then replace the target in one rename. DCMTK types only in io/*.cpp that include DCMTK already.

#include <dcmtk/config/osconfig.h>
#include <dcmtk/dcmdata/dcfilefo.h>

#include <filesystem>

namespace curette::io {

// Throws SystemError naming `path` when DCMTK cannot write it.
void saveDicomAtomically(DcmFileFormat& file, const std::filesystem::path& path);

}  // namespace curette::io
