#include "command_line.h"

#include "cli_common.h"

#include <CLI/CLI.hpp>

#include <iostream>
#include <utility>

namespace shadow::samples {

CommandLine::Option& CommandLine::Option::required() {
    option_->required();
    return *this;
}

CommandLine::Option& CommandLine::Option::excludes(const Option& other) {
    option_->excludes(other.option_);
    return *this;
}

CommandLine::Option& CommandLine::Option::range(int low, int high) {
    option_->check(CLI::Range(low, high));
    return *this;
}

CommandLine::Option& CommandLine::Option::delimiter(char separator) {
    option_->delimiter(separator);
    return *this;
}

bool CommandLine::Option::given() const { return option_->count() > 0; }

CommandLine::CommandLine(const std::string& description) : app_(std::make_unique<CLI::App>(description)) {}

CommandLine::~CommandLine() = default;

CommandLine::Option CommandLine::add(const std::string& name, std::string& into, const std::string& help) {
    return Option(app_->add_option(name, into, help));
}
CommandLine::Option CommandLine::add(const std::string& name, int& into, const std::string& help) {
    return Option(app_->add_option(name, into, help));
}
CommandLine::Option CommandLine::add(const std::string& name, std::uint32_t& into, const std::string& help) {
    return Option(app_->add_option(name, into, help));
}
CommandLine::Option CommandLine::add(const std::string& name, double& into, const std::string& help) {
    return Option(app_->add_option(name, into, help));
}
CommandLine::Option CommandLine::add(const std::string& name, std::vector<std::string>& into, const std::string& help) {
    return Option(app_->add_option(name, into, help));
}
CommandLine::Option CommandLine::add(const std::string& name, std::optional<std::string>& into,
                                     const std::string& help) {
    return Option(app_->add_option(name, into, help));
}
CommandLine::Option CommandLine::add(const std::string& name, std::optional<int>& into, const std::string& help) {
    return Option(app_->add_option(name, into, help));
}
CommandLine::Option CommandLine::add(const std::string& name, std::optional<float>& into, const std::string& help) {
    return Option(app_->add_option(name, into, help));
}
CommandLine::Option CommandLine::add(const std::string& name, std::optional<double>& into, const std::string& help) {
    return Option(app_->add_option(name, into, help));
}

CommandLine::Option CommandLine::flag(const std::string& name, bool& into, const std::string& help) {
    return Option(app_->add_flag(name, into, help));
}

CommandLine::Option CommandLine::flag(const std::string& name, std::function<void()> onGiven, const std::string& help) {
    return Option(app_->add_flag_callback(name, std::move(onGiven), help));
}

std::optional<int> CommandLine::parse(int argc, char** argv, const char* program) {
    try {
        app_->parse(argc, argv);
    } catch (const CLI::CallForHelp& e) {
        return app_->exit(e);
    } catch (const CLI::ParseError& e) {
        std::cerr << program << ": " << e.what() << "\n(see " << program << " --help)\n";
        return kExitBadInput;
    }
    return std::nullopt;
}

}  // namespace shadow::samples
