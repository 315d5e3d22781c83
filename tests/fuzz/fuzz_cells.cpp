// libFuzzer target: the .cells reader (sim/cells_io/cells_file.cpp). The FNV-1a checksum
// would reject almost every mutation before the structural checks, so each input is
// parsed twice: as given, and with its last 8 bytes replaced by the checksum of the rest.
// A file that parses must survive a write/read round trip unchanged; bad input must end
// in pelage::InputError; any other exception, crash or sanitizer report is a bug.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <vector>

#include "sim/cells_io/cells_file.h"
#include "sim/core/input_error.h"

namespace {

// FNV-1a 64 (Fowler, Noll, Vo), as the .cells format specifies
// (sim/cells_io/cells_file.h).
uint64_t fnv1a(const uint8_t *p, size_t n) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 0x100000001b3ull;
    return h;
}

void parse_and_round_trip(const std::vector<uint8_t> &bytes) {
    try {
        const pelage::sim::CellsData cells =
            pelage::sim::parse_cells(bytes, "fuzz.cells");
        const pelage::sim::CellsData again =
            pelage::sim::parse_cells(pelage::sim::serialize_cells(cells), "again.cells");
        if (!(again == cells)) __builtin_trap();
    } catch (const pelage::InputError &) {
    }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size) {
    std::vector<uint8_t> bytes(data, data + size);
    parse_and_round_trip(bytes);
    if (bytes.size() >= 8) {
        const uint64_t sum = fnv1a(bytes.data(), bytes.size() - 8);  // little-endian host
        std::memcpy(bytes.data() + bytes.size() - 8, &sum, 8);
        parse_and_round_trip(bytes);
    }
    return 0;
}
