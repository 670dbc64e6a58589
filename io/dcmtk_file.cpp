#include "io/dcmtk_file.h"

#include "io/dcmtk_support.h"
#include "base/atomic_file.h"
#include "base/error.h"

#include <unistd.h>

namespace curette::io {

void saveDicomAtomically(DcmFileFormat& file, const std::filesystem::path& path) {
    std::filesystem::path scratch = std::filesystem::temp_directory_path() /
                                    ("curette-dicom-" + std::to_string(::getpid()) + "-" + newDicomUid() + ".dcm");
    OFCondition status = file.saveFile(scratch.c_str(), EXS_LittleEndianExplicit);
    if (status.bad()) {
        std::filesystem::remove(scratch);
        throw SystemError(path.string() + ": DCMTK cannot write the object (" + status.text() + ")");
    }
    std::vector<std::uint8_t> bytes = readFileBytes(scratch);
    std::filesystem::remove(scratch);
    writeFileAtomically(path, bytes);
}

}  // namespace curette::io
