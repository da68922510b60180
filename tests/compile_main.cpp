// main() of shadow_compile_tests: the driver's shader cache is turned off before any GL context
// exists (Mesa reads MESA_SHADER_CACHE_DISABLE when it makes one), so every program a test
// builds is compiled as on a fresh machine's first run, and its compile time is measured.
#include <gtest/gtest.h>

#include <cstdlib>

int main(int argc, char** argv) {
    setenv("MESA_SHADER_CACHE_DISABLE", "true", 1);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
