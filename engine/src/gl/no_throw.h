// The error-value face of calls that throw, for games built without exceptions: the call runs
// inside the library (built with them) and what it would throw comes back as an `Error`.
#pragma once

#include <shadow/result.h>

#include <exception>
#include <new>
#include <string>
#include <string_view>
#include <utility>

namespace shadow::gpu {

/// Runs `f` and returns its value, or an `Error` naming `call` and what `f` threw.
template <typename T, typename F>
Result<T> noThrow(std::string_view call, F&& f) noexcept {
    try {
        return Result<T>(std::forward<F>(f)());
    } catch (const std::exception& e) {
        try {
            return Error{ErrorCode::Internal, std::string(call) + ": " + e.what()};
        } catch (...) {
            return Error(ErrorCode::Internal, "out of memory");  // no memory left even for the message
        }
    } catch (...) {
        try {
            return Error{ErrorCode::Internal, std::string(call) + ": unknown error"};
        } catch (...) {
            return Error(ErrorCode::Internal, "out of memory");
        }
    }
}

/// `noThrow` for a call that returns nothing.
template <typename F>
Status noThrowStatus(std::string_view call, F&& f) noexcept {
    return noThrow<Ok>(call, [&f] {
        f();
        return Ok{};
    });
}

}  // namespace shadow::gpu
