// libFuzzer target: label tables (io/label_table.h): mricron names, plain colour tables, 3D Slicer's
// table and CSV forms. The first byte picks the file name the detection sees (.txt or .ctbl).
#include "io/label_table.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    if (size == 0) return 0;
    std::string source = (data[0] & 1) ? "fuzz.ctbl" : "fuzz.txt";
    try {
        curette::io::readLabelTableText(std::string_view(reinterpret_cast<const char*>(data + 1), size - 1), source);
    } catch (const curette::InputError&) {
    }
    return 0;
}
