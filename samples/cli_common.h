// What the sample CLIs share: the exit codes of the CLI contract (docs/output_contract.md), the
// one-line failure message, and parsing a command line into them. Header-only, so that
// shadow_compare, which links no sample library, shares it too.
#pragma once

#include <CLI/CLI.hpp>

#include <iostream>
#include <optional>
#include <string>

namespace shadow::samples {

inline constexpr int kExitFailure = 1;   ///< the program failed (OpenGL, the disk, ...)
inline constexpr int kExitBadInput = 2;  ///< bad arguments, files or settings: nothing written

/// Prints `program: message` on stderr and returns `code`.
inline int failAs(const char* program, int code, const std::string& message) {
    std::cerr << program << ": " << message << "\n";
    return code;
}

/// Parses the command line into `app`'s options: nullopt when the program is to run, else the
/// exit code to return (0 after --help; kExitBadInput after one message naming the problem).
inline std::optional<int> parseCommandLine(CLI::App& app, int argc, char** argv, const char* program) {
    try {
        app.parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app.exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << program << ": " << e.what() << "\n(see " << program << " --help)\n";
        return kExitBadInput;
    }
    return std::nullopt;
}

}  // namespace shadow::samples
