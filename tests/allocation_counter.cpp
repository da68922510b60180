// The counting replacement of the global operator new and delete (see allocation_counter.h).
#include "allocation_counter.h"

#include <algorithm>
#include <atomic>
#include <cassert>
#include <cstddef>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <cxxabi.h>
#include <execinfo.h>
#include <new>

namespace shadow::test {
namespace {

std::atomic<bool> counting{false};
std::atomic<long> allocations{0};
std::atomic<int> tracesLeft{0};
/// Set while this thread prints a call stack: the printing's own allocations are not counted.
thread_local bool tracing = false;

/// Prints one frame of `backtrace_symbols` ("file(mangled+0x1f) [0x...]"), its name demangled.
void printFrame(int index, const char* symbol) {
    const char* open = std::strchr(symbol, '(');
    const char* plus = open != nullptr ? std::strchr(open, '+') : nullptr;
    if (open == nullptr || plus == nullptr || plus == open + 1) {
        std::fprintf(stderr, "  #%d %s\n", index, symbol);
        return;
    }
    char mangled[512];
    const std::size_t length = std::min(static_cast<std::size_t>(plus - open - 1), sizeof(mangled) - 1);
    std::memcpy(mangled, open + 1, length);
    mangled[length] = '\0';
    int status = 0;
    char* name = abi::__cxa_demangle(mangled, nullptr, nullptr, &status);  // malloc: not counted
    std::fprintf(stderr, "  #%d %s\n", index, status == 0 && name != nullptr ? name : mangled);
    std::free(name);
}

[[gnu::noinline]] void printCallStack(std::size_t bytes) {
    void* frames[32];
    const int depth = backtrace(frames, 32);
    char** symbols = backtrace_symbols(frames, depth);
    std::fprintf(stderr, "allocation of %zu bytes while counting, from:\n", bytes);
    // Frame 0 is this function; the next few are this file's and operator new. The stack ends
    // where GoogleTest's own frames begin.
    for (int i = 1; i < depth; ++i) {
        const char* symbol = symbols != nullptr ? symbols[i] : "?";
        if (std::strstr(symbol, "testing8internal") != nullptr) break;
        printFrame(i, symbol);
    }
    std::free(symbols);
}

void noteAllocation(std::size_t bytes) {
    if (!counting.load(std::memory_order_relaxed) || tracing) return;
    allocations.fetch_add(1, std::memory_order_relaxed);
    if (tracesLeft.load(std::memory_order_relaxed) <= 0 || tracesLeft.fetch_sub(1) <= 0) return;
    tracing = true;
    printCallStack(bytes);
    tracing = false;
}

void* allocate(std::size_t bytes, std::size_t alignment) {
    noteAllocation(bytes);
    if (bytes == 0) bytes = 1;
    if (alignment <= alignof(std::max_align_t)) return std::malloc(bytes);
    // aligned_alloc wants a multiple of the alignment (a power of two).
    return std::aligned_alloc(alignment, (bytes + alignment - 1) & ~(alignment - 1));
}

void* allocateOrThrow(std::size_t bytes, std::size_t alignment) {
    void* p = allocate(bytes, alignment);
    if (p == nullptr) throw std::bad_alloc();
    return p;
}

}  // namespace

bool allocationCountingWorks() {
    const AllocationCounter counter;
    // A direct call to operator new, which the compiler may not leave out as it may a new-expression.
    ::operator delete(::operator new(16));
    return counter.count() == 1;
}

AllocationCounter::AllocationCounter(int traceFirst) {
    assert(!counting.load());
    allocations.store(0);
    tracesLeft.store(traceFirst);
    counting.store(true);
}

AllocationCounter::~AllocationCounter() { counting.store(false); }

long AllocationCounter::count() const { return allocations.load(); }

}  // namespace shadow::test

using shadow::test::allocateOrThrow;

namespace {
// Every deallocation form ends here. Not inlined: where GCC 12 sees operator new and std::free
// together it warns of a mismatch (-Wmismatched-new-delete), though both forms are this file's.
[[gnu::noinline]] void release(void* p) noexcept { std::free(p); }
}  // namespace

// The replaceable allocation functions ([new.delete]): every form forwards to allocateOrThrow,
// every deallocation to release (std::free). The nothrow forms return null instead of throwing.
void* operator new(std::size_t bytes) { return allocateOrThrow(bytes, 0); }
void* operator new[](std::size_t bytes) { return allocateOrThrow(bytes, 0); }
void* operator new(std::size_t bytes, std::align_val_t a) {
    return allocateOrThrow(bytes, static_cast<std::size_t>(a));
}
void* operator new[](std::size_t bytes, std::align_val_t a) {
    return allocateOrThrow(bytes, static_cast<std::size_t>(a));
}
void* operator new(std::size_t bytes, const std::nothrow_t&) noexcept {
    try {
        return allocateOrThrow(bytes, 0);
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t bytes, const std::nothrow_t& tag) noexcept { return operator new(bytes, tag); }
void* operator new(std::size_t bytes, std::align_val_t a, const std::nothrow_t&) noexcept {
    try {
        return allocateOrThrow(bytes, static_cast<std::size_t>(a));
    } catch (...) {
        return nullptr;
    }
}
void* operator new[](std::size_t bytes, std::align_val_t a, const std::nothrow_t& tag) noexcept {
    return operator new(bytes, a, tag);
}

void operator delete(void* p) noexcept { release(p); }
void operator delete[](void* p) noexcept { release(p); }
void operator delete(void* p, std::size_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t) noexcept { release(p); }
void operator delete(void* p, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete[](void* p, std::size_t, std::align_val_t) noexcept { release(p); }
void operator delete(void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, const std::nothrow_t&) noexcept { release(p); }
void operator delete(void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
void operator delete[](void* p, std::align_val_t, const std::nothrow_t&) noexcept { release(p); }
