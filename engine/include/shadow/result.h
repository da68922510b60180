// Error values for bad input.
//
// Bad *input* (files, arguments, settings) is reported through `Result<T>`, whose error
// names the element at fault (`scene.gltf: nodes[3].rotation: not finite`). Broken
// *internal* invariants assert instead. The library never aborts on user input.
#pragma once

#include <cassert>
#include <string>
#include <utility>
#include <variant>

namespace shadow {

/// A failure caused by input, with a message that names the file and element at fault.
struct Error {
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
