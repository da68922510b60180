// Counting the C++ allocations of a stretch of code. allocation_counter.cpp replaces every
// global operator new and delete (forwarding to malloc and free) with versions that count while
// an `AllocationCounter` is alive. A replacement holds for a whole binary, so it is linked into
// one of its own (shadow_alloc_tests, tests/CMakeLists.txt) with the *_alloc_test.cpp files.
//
// What it counts: operator new on any thread, called by our code or by the standard library on
// its behalf (containers, strings, std::function, shared_ptr). What it does not: malloc called
// directly, as C libraries do (Mesa's driver among them); that memory is not the engine's.
#pragma once

namespace shadow::test {

/// Whether this binary's operator new is the counting one: false if another replacement won
/// (a sanitizer runtime may bring its own).
[[nodiscard]] bool allocationCountingWorks();

/// Counts allocations from construction to destruction. One at a time.
class AllocationCounter {
public:
    /// `traceFirst`: how many of the allocations counted get their call stack printed to stderr,
    /// to find where they come from.
    explicit AllocationCounter(int traceFirst = 0);
    ~AllocationCounter();
    AllocationCounter(const AllocationCounter&) = delete;
    AllocationCounter& operator=(const AllocationCounter&) = delete;

    /// Allocations counted so far.
    [[nodiscard]] long count() const;
};

}  // namespace shadow::test
