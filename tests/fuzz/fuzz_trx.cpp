// libFuzzer target: TRX zip archives (libzip directory, entry data, header.json, positions, offsets) from
// arbitrary bytes.
#include "io/trx.h"
#include "base/error.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    try {
        curette::io::readTrxZipBytes(std::span(data, size), "fuzz.trx");
    } catch (const curette::InputError&) {
    }
    return 0;
}
