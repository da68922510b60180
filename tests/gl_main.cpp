// main() of the test programs that render (shadow_gl_tests, shadow_alloc_tests). Before any GL
// context exists (Mesa reads both variables when it makes one), and unless the caller set them:
// - GALLIVM_PERF=nopt: llvmpipe compiles each shader without LLVM's optimisation passes. On a fresh
//   machine the suite's GL time is mostly shader compilation (each test file is a process of its
//   own and builds the variants its lights need), and the tests' small images render about as fast
//   unoptimised: measured on two cores, the fast tier took 124 s instead of 169 with an empty
//   shader cache, 76 s instead of 73 with a full one. The programs the tests run (shadow_render and
//   the other command-line tools) inherit it. Compile-time tests keep the optimisation
//   (compile_main.cpp): they measure what a user's first run costs.
// - MESA_SHADER_CACHE_DIR: a cache of the tests' own in the build folder, so that unoptimised
//   shaders never reach the cache the renderer and the benchmarks use.
// And for the process itself: glibc's malloc keeps what is freed below 1 GiB for the next
// allocation instead of giving it back to the system (M_MMAP_THRESHOLD, M_TRIM_THRESHOLD). The
// tests allocate and free the same large buffers over and over (llvmpipe's textures and render
// targets, shadow maps read back, images), which by default are mapped afresh each time: the
// kernel clears every page again. Measured on two cores, the stability, cascade and
// scale-invariance tests in one process, runs taken in turn: 47 s of CPU -> 45 (of it in the
// kernel 4.4 s -> 1.9), the whole GL suite at the same peak memory (1.5 GB). A sanitizer build's
// allocator ignores it.
#include <gtest/gtest.h>
#include <malloc.h>

#include <cstdlib>

#ifndef SHADOW_TEST_SHADER_CACHE
#error "SHADOW_TEST_SHADER_CACHE (the tests' shader cache folder) is set by tests/CMakeLists.txt"
#endif

int main(int argc, char** argv) {
    mallopt(M_MMAP_THRESHOLD, 1 << 30);
    mallopt(M_TRIM_THRESHOLD, 1 << 30);
    setenv("GALLIVM_PERF", "nopt", 0);
    setenv("MESA_SHADER_CACHE_DIR", SHADOW_TEST_SHADER_CACHE, 0);
    ::testing::InitGoogleTest(&argc, argv);
    return RUN_ALL_TESTS();
}
