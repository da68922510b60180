// libFuzzer target over the image decoding path: each input is the one image of a small GLB,
// loaded as a file's textures are (see image_fuzz_target.h). Built with -DSHADOW_FUZZ=ON and
// clang; run by tests/fuzz/run_fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "fuzz/image_fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    (void)shadow::fuzz::runImageInput(data, size);
    return 0;
}
