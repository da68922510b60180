// The error-value face of calls that throw, for games built without exceptions: the call runs
// inside the library (built with them) and what it would throw comes back as an `Error`.
#pragma once

#include <shadow/context.h>
#include <shadow/result.h>

#include <exception>
#include <new>
#include <string>
#include <string_view>
#include <utility>

namespace shadow::gpu {

/// `what` prefixed with `call` (once: a message that already starts with it keeps its own).
inline std::string namedByCall(std::string_view call, std::string_view what) {
    if (what.substr(0, call.size()) == call) return std::string(what);
    return std::string(call) + ": " + std::string(what);
}

/// Runs `f` and returns its value, or an `Error` naming `call` and what `f` threw: a call made
/// before `loadGl` (`GlNotLoaded`) as `GlUnavailable`, anything else as `Internal`.
template <typename T, typename F>
Result<T> noThrow(std::string_view call, F&& f) noexcept {
    try {
        return Result<T>(std::forward<F>(f)());
    } catch (const GlNotLoaded& e) {
        try {
            return Error{ErrorCode::GlUnavailable, namedByCall(call, e.what())};
        } catch (...) {
            return Error(ErrorCode::Internal, "out of memory");
        }
    } catch (const std::exception& e) {
        try {
            return Error{ErrorCode::Internal, namedByCall(call, e.what())};
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
