// libFuzzer target over the viewer's script language: each input is a script, parsed against
// builtin:default, its settings written into the lights and planned (see script_fuzz_target.h).
// Built with -DSHADOW_FUZZ=ON and clang; run by tests/fuzz/run_fuzz.sh.
#include <cstddef>
#include <cstdint>

#include "fuzz/script_fuzz_target.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    (void)shadow::fuzz::runScriptInput(data, size);
    return 0;
}
