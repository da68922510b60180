// The command lines of the sample programs and the benchmarks: options declared into variables,
// parsed into the exit codes of the CLI contract (docs/output_contract.md). A thin face over
// CLI11, whose templates are compiled once, in command_line.cpp, instead of once per program
// (measured: a translation unit that declares a few options costs 6 s of CPU at -O1, 11 s at
// -O3). Messages and --help are CLI11's.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace CLI {
class App;
class Option;
}  // namespace CLI

namespace shadow::samples {

class CommandLine {
public:
    /// One declared option: a handle into its command line, valid while that lives.
    class Option {
    public:
        Option& required();                     ///< parsing fails without it
        Option& excludes(const Option& other);  ///< parsing fails when both are given
        Option& range(int low, int high);       ///< a number within [low, high]
        Option& delimiter(char separator);      ///< a list given as one separated word too
        [[nodiscard]] bool given() const;       ///< it was on the command line

    private:
        friend class CommandLine;
        explicit Option(CLI::Option* option) : option_(option) {}
        CLI::Option* option_;
    };

    explicit CommandLine(const std::string& description);
    ~CommandLine();
    CommandLine(const CommandLine&) = delete;
    CommandLine& operator=(const CommandLine&) = delete;

    /// An option parsed into `into`. A `name` without leading dashes is positional.
    Option add(const std::string& name, std::string& into, const std::string& help);
    Option add(const std::string& name, int& into, const std::string& help);
    Option add(const std::string& name, std::uint32_t& into, const std::string& help);
    Option add(const std::string& name, double& into, const std::string& help);
    Option add(const std::string& name, std::vector<std::string>& into, const std::string& help);
    Option add(const std::string& name, std::optional<std::string>& into, const std::string& help);
    Option add(const std::string& name, std::optional<int>& into, const std::string& help);
    Option add(const std::string& name, std::optional<float>& into, const std::string& help);
    Option add(const std::string& name, std::optional<double>& into, const std::string& help);
    /// A flag: `into` becomes true when it is given.
    Option flag(const std::string& name, bool& into, const std::string& help);
    /// A flag that calls `onGiven` when it is given.
    Option flag(const std::string& name, std::function<void()> onGiven, const std::string& help);

    /// Parses the command line into the declared variables: nullopt when the program is to run,
    /// else the exit code to return (0 after --help; kExitBadInput after one message naming the
    /// problem, `program: ...` on stderr).
    std::optional<int> parse(int argc, char** argv, const char* program);

private:
    std::unique_ptr<CLI::App> app_;
};

}  // namespace shadow::samples
