// Error values for bad input.
//
// Bad *input* (files, arguments, settings) is reported through `Result<T>`, whose error
// names the element at fault (`scene.gltf: nodes[3].rotation: not finite`). Broken
// *internal* invariants assert instead. The library never aborts on user input.
#pragma once

#include <cassert>
#include <cstdint>
#include <string>
#include <utility>
#include <variant>

namespace shadow {

/// What kind of failure an `Error` is, for a program that reacts to it (tests assert codes,
/// not message text). Names the cause, not the module that found it.
enum class ErrorCode : std::uint8_t {
    FileUnreadable,    ///< a file or folder cannot be opened, read or listed, or is not a regular file
    FileUnwritable,    ///< an output file or folder cannot be created or written
    MalformedFile,     ///< a file's syntax or structure is broken (JSON, glTF, GLB, OBJ, EXR, too deep)
    InvalidValue,      ///< an element holds a bad value: not finite, out of range, wrong type, a
                       ///< dangling index, an unknown name
    Unsupported,       ///< valid input outside what the module handles (an orthographic camera, ...)
    InvalidArgument,   ///< a command-line option or API argument out of its documented range
    LimitExceeded,     ///< over a size or count limit (render size, nodes, a dense accessor, ...)
    MismatchedInputs,  ///< inputs that do not belong together: sizes, channels, the lights of two
                       ///< runs, a file older than its run
    GlUnavailable,     ///< no usable OpenGL (context, version, entry points) or ray tracer: the
                       ///< platform, not the input
    Internal,          ///< an exception where none was expected (out of memory, a bug)
};

/// The code's name (`"InvalidValue"`); "Unknown" for a value outside the enum.
[[nodiscard]] constexpr const char* errorCodeName(ErrorCode code) {
    switch (code) {
        case ErrorCode::FileUnreadable: return "FileUnreadable";
        case ErrorCode::FileUnwritable: return "FileUnwritable";
        case ErrorCode::MalformedFile: return "MalformedFile";
        case ErrorCode::InvalidValue: return "InvalidValue";
        case ErrorCode::Unsupported: return "Unsupported";
        case ErrorCode::InvalidArgument: return "InvalidArgument";
        case ErrorCode::LimitExceeded: return "LimitExceeded";
        case ErrorCode::MismatchedInputs: return "MismatchedInputs";
        case ErrorCode::GlUnavailable: return "GlUnavailable";
        case ErrorCode::Internal: return "Internal";
    }
    return "Unknown";
}

/// A failure caused by input: a code, the element at fault where there is one
/// (`nodes[3].rotation`; empty otherwise) and a message that names the file and element.
struct Error {
    Error() = default;
    Error(ErrorCode c, std::string text, std::string at = {})
        : code(c), element(std::move(at)), message(std::move(text)) {}

    /// The same error with `prefix` ahead of its message (`"scene.gltf: " + message`): a caller
    /// that adds where it was adds no new cause.
    [[nodiscard]] Error within(const std::string& prefix) const { return {code, prefix + message, element}; }

    ErrorCode code = ErrorCode::Internal;
    std::string element;
    std::string message;
};

/// Either a value or an `Error`. A small stand-in for C++23 `std::expected`.
template <typename T>
class [[nodiscard]] Result {
public:
    Result(T value) : state_(std::move(value)) {}      // NOLINT: implicit by design
    Result(Error error) : state_(std::move(error)) {}  // NOLINT: implicit by design

    [[nodiscard]] bool ok() const { return state_.index() == 0; }
    explicit operator bool() const { return ok(); }

    [[nodiscard]] T& value() & {
        assert(ok());
        return std::get<0>(state_);
    }
    [[nodiscard]] const T& value() const& {
        assert(ok());
        return std::get<0>(state_);
    }
    [[nodiscard]] T&& value() && {
        assert(ok());
        return std::get<0>(std::move(state_));
    }
    T* operator->() { return &value(); }
    const T* operator->() const { return &value(); }
    T& operator*() & { return value(); }
    const T& operator*() const& { return value(); }

    [[nodiscard]] const Error& error() const {
        assert(!ok());
        return std::get<1>(state_);
    }

private:
    std::variant<T, Error> state_;
};

/// `Result` for operations that produce nothing but may fail.
struct Ok {};
using Status = Result<Ok>;

}  // namespace shadow
