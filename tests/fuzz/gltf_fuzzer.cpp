// libFuzzer target over the glTF loading path: the importer from memory, the CPU frame on what
// loads, and the extras.shadow parsers (see gltf_fuzz_target.h). Built with -DSHADOW_FUZZ=ON
// and clang; run by tests/fuzz/run_fuzz.sh. Crashing inputs go to tests/fuzz/regressions/,
// which the ordinary test suite replays.
#include <cstddef>
#include <cstdint>

#include "fuzz/gltf_fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    shadow::fuzz::runOneInput(data, size);
    return 0;
}
