// libFuzzer target: a DICOM file from arbitrary bytes, through GDCM's scanner and image reader and curette's
// series placement and decoding. Input errors are expected; anything else (a crash, a sanitizer report, an
// uncaught exception) is a bug.
#include "io/dicom.h"
#include "base/error.h"

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

// GDCM 3.0.21 leaks buffers that gdcm::JPEGLSCodec::Decode and ::GetHeaderInfo allocate when the JPEG-LS data
// is corrupt (found by this driver). The library's leak, not curette's: suppressed for that codec only.
extern "C" const char* __lsan_default_suppressions() { return "leak:JPEGLSCodec\n"; }

namespace {

// GDCM reads files, not memory. The file lies alone in a folder of its own, because one named file opens the
// files of its series beside it; the folder goes when the fuzzer exits.
std::filesystem::path folder;

void removeFolder() {
    std::error_code ec;
    std::filesystem::remove_all(folder, ec);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    static const bool ready = [] {
        folder = std::filesystem::temp_directory_path() / ("curette-fuzz-dicom-" + std::to_string(::getpid()));
        std::filesystem::create_directories(folder);
        std::atexit(removeFolder);
        return true;
    }();
    (void)ready;
    const std::filesystem::path file = folder / "input.dcm";
    {
        std::ofstream out(file, std::ios::binary | std::ios::trunc);
        out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(size));
    }
    try {
        curette::io::readDicomSeries(file, curette::io::VolumeReadOptions{});
    } catch (const curette::InputError&) {
    }
    return 0;
}
