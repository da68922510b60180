#include "viewer_script.h"

#include "viewer_settings.h"

#include <shadow/image_io.h>

#include <charconv>
#include <filesystem>
#include <fstream>
#include <cmath>
#include <sstream>

namespace shadow::viewer {
namespace {

using Verb = ScriptCommand::Verb;

const char* const kVerbs = "time, dt, frames, set, debug, shadowmap, camera, exposure, screenshot, screenshot-ui, quit";

/// `text` cut to at most `limit` bytes on a UTF-8 boundary, with "..." when cut.
std::string clipped(const std::string& text, std::size_t limit) {
    if (text.size() <= limit) return text;
    std::size_t cut = limit;
    while (cut > 0 && (static_cast<unsigned char>(text[cut]) & 0xC0U) == 0x80U) --cut;
    return text.substr(0, cut) + "...";
}

/// The words of one line.
std::vector<std::string> words(const std::string& line) {
    std::istringstream in(line);
    std::vector<std::string> out;
    for (std::string w; in >> w;) out.push_back(w);
    return out;
}

std::optional<double> number(const std::string& text) {
    double v = 0.0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || end != text.data() + text.size() || !std::isfinite(v)) return std::nullopt;
    return v;
}

std::optional<int> integer(const std::string& text) {
    int v = 0;
    const auto [end, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
    if (ec != std::errc{} || end != text.data() + text.size()) return std::nullopt;
    return v;
}

/// Parses one line's words into `cmd`; the error is the message without the file and line.
Status parseCommand(const std::vector<std::string>& w, const ScriptContext& ctx, ScriptCommand& cmd) {
    auto fail = [](const std::string& message) -> Status { return Error{ErrorCode::InvalidValue, message}; };
    const std::string& verb = w[0];
    auto expectArgs = [&](std::size_t least, std::size_t most, const char* usage) -> Status {
        if (w.size() - 1 < least || w.size() - 1 > most) return fail("'" + verb + "' expects: " + usage);
        return Ok{};
    };
    auto lightIndex = [&](const std::string& text, bool allowAll) -> Result<std::optional<int>> {
        if (allowAll && text == "all") return std::optional<int>{};
        const std::optional<int> i = integer(text);
        if (!i || *i < 0 || *i >= ctx.lights) {
            return Error{ErrorCode::InvalidValue, "light '" + text + "': the scene has " + std::to_string(ctx.lights) +
                                                      " lights (0 to " + std::to_string(ctx.lights - 1) + ")" +
                                                      (allowAll ? " or all" : "")};
        }
        return std::optional<int>{*i};
    };

    if (verb == "time" || verb == "dt" || verb == "exposure") {
        cmd.verb = verb == "time" ? Verb::Time : verb == "dt" ? Verb::Dt : Verb::Exposure;
        if (Status s = expectArgs(1, 1, verb == "exposure" ? "exposure E|auto" : (verb + " SECONDS").c_str()); !s)
            return s;
        if (cmd.verb == Verb::Exposure && w[1] == "auto") return Ok{};
        const std::optional<double> v = number(w[1]);
        const bool positive = cmd.verb != Verb::Time;
        if (!v || (positive ? *v <= 0.0 : *v < 0.0)) {
            return fail(verb + " '" + w[1] + "': expected a finite number " + (positive ? "> 0" : ">= 0"));
        }
        cmd.number = *v;
        cmd.index = 0;  // a value was given (exposure: not auto)
        return Ok{};
    }
    if (verb == "frames") {
        cmd.verb = Verb::Frames;
        if (Status s = expectArgs(1, 1, "frames N"); !s) return s;
        const std::optional<int> n = integer(w[1]);
        if (!n || *n < 1 || *n > 100000) return fail("frames '" + w[1] + "': expected an integer in [1, 100000]");
        cmd.number = *n;
        return Ok{};
    }
    if (verb == "set") {
        cmd.verb = Verb::Set;
        if (Status s = expectArgs(3, 3, "set LIGHT|all KEY VALUE"); !s) return s;
        auto light = lightIndex(w[1], true);
        if (!light) return light.error();
        cmd.index = *light;
        const LightSetting* setting = findLightSetting(w[2]);
        if (setting == nullptr) return fail("unknown setting '" + w[2] + "' (known: " + lightSettingKeys() + ")");
        auto value = parseSettingValue(*setting, w[3]);
        if (!value) return value.error();
        cmd.key = w[2];
        cmd.number = *value;
        return Ok{};
    }
    if (verb == "debug") {
        cmd.verb = Verb::Debug;
        if (Status s = expectArgs(1, 2, "debug VIEW [LIGHT]"); !s) return s;
        auto view = parseDebugView(w[1]);
        if (!view) return view.error();
        cmd.view = *view;
        if (w.size() == 3) {
            auto light = lightIndex(w[2], false);
            if (!light) return light.error();
            cmd.index = *light;
        }
        return Ok{};
    }
    if (verb == "shadowmap") {
        cmd.verb = Verb::ShadowMap;
        if (w.size() == 2 && w[1] == "off") return Ok{};
        if (Status s = expectArgs(2, 2, "shadowmap LIGHT LAYER, or shadowmap off"); !s) return s;
        auto light = lightIndex(w[1], false);
        if (!light) return light.error();
        const std::optional<int> layer = integer(w[2]);
        if (!layer || *layer < 0 || *layer > 5) return fail("layer '" + w[2] + "': expected an integer in [0, 5]");
        cmd.index = *light;
        cmd.number = *layer;
        return Ok{};
    }
    if (verb == "camera") {
        cmd.verb = Verb::Camera;
        if (Status s = expectArgs(1, 1, "camera N"); !s) return s;
        const std::optional<int> i = integer(w[1]);
        if (!i || *i < 0 || *i >= ctx.cameras) {
            return fail("camera '" + w[1] + "': the scene has " + std::to_string(ctx.cameras) + " cameras");
        }
        cmd.index = *i;
        return Ok{};
    }
    if (verb == "screenshot" || verb == "screenshot-ui") {
        cmd.verb = verb == "screenshot" ? Verb::Screenshot : Verb::ScreenshotUi;
        if (Status s = expectArgs(1, 1, (verb + " PATH.png").c_str()); !s) return s;
        if (w[1].size() < 5 || w[1].substr(w[1].size() - 4) != ".png") {
            return fail(verb + " '" + w[1] + "': the path must end in .png");
        }
        cmd.path = w[1];
        return Ok{};
    }
    if (verb == "quit") {
        cmd.verb = Verb::Quit;
        return expectArgs(0, 0, "quit");
    }
    return fail("unknown command '" + verb + "' (known: " + kVerbs + ")");
}

}  // namespace

Result<std::string> readScriptFile(const std::string& path) {
    const std::string where = "--script " + clipped(path, 256) + ": ";
    if (std::optional<std::string> what = notRegularFile(path)) return Error{ErrorCode::FileUnreadable, where + *what};
    std::error_code ec;
    const std::uintmax_t size = std::filesystem::file_size(path, ec);
    if (ec) return Error{ErrorCode::FileUnreadable, where + "cannot be read (" + ec.message() + ")"};
    if (size > kMaxScriptBytes) {
        return Error{ErrorCode::LimitExceeded, where + std::to_string(size) + " bytes; a script holds at most " +
                                                   std::to_string(kMaxScriptBytes) + " (1 MiB)"};
    }
    std::ifstream in(path, std::ios::binary);
    std::string text(kMaxScriptBytes + 1, '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    if (in.bad()) return Error{ErrorCode::FileUnreadable, where + "cannot be read"};
    text.resize(static_cast<std::size_t>(in.gcount()));
    // It may have grown since it was measured: the limit holds for what was read.
    if (text.size() > kMaxScriptBytes) return Error{ErrorCode::LimitExceeded, where + "grew beyond 1 MiB while read"};
    return text;
}

Result<std::vector<ScriptCommand>> parseScript(const std::string& text, const std::string& fileName,
                                               const ScriptContext& context) {
    std::vector<ScriptCommand> commands;
    std::istringstream in(text);
    int lineNumber = 0;
    const auto failure = [&](const std::string& message) {
        return Error{ErrorCode::InvalidValue,
                     clipped(fileName + ":" + std::to_string(lineNumber) + ": " + message, kMaxScriptMessage)};
    };
    for (std::string line; std::getline(in, line);) {
        ++lineNumber;
        if (line.size() > kMaxScriptLine) {
            return failure("a line of " + std::to_string(line.size()) + " bytes; a line holds at most " +
                           std::to_string(kMaxScriptLine));
        }
        const std::vector<std::string> w = words(line);
        if (w.empty() || w[0][0] == '#') continue;
        ScriptCommand cmd;
        cmd.line = lineNumber;
        if (Status s = parseCommand(w, context, cmd); !s) {
            // The line last, so that the cut falls on the quote rather than on the cause.
            const std::string quote = " (in '" + clipped(line, 80) + "')";
            return failure(clipped(s.error().message, kMaxScriptMessage - quote.size() - 64) + quote);
        }
        commands.push_back(std::move(cmd));
    }
    return commands;
}

const std::vector<DebugView>& debugViews() {
    static const std::vector<DebugView> kViews = {DebugView::None,     DebugView::Cascade,    DebugView::BlockerDepth,
                                                  DebugView::Penumbra, DebugView::Visibility, DebugView::MarchSteps,
                                                  DebugView::Closest};
    return kViews;
}

const char* debugViewName(DebugView view) {
    switch (view) {
        case DebugView::None: return "none";
        case DebugView::Cascade: return "cascade";
        case DebugView::BlockerDepth: return "blocker";
        case DebugView::Penumbra: return "penumbra";
        case DebugView::Visibility: return "visibility";
        case DebugView::MarchSteps: return "steps";
        case DebugView::Closest: return "closest";
    }
    return "none";
}

Result<DebugView> parseDebugView(const std::string& name) {
    for (DebugView v : debugViews()) {
        if (name == debugViewName(v)) return v;
    }
    return Error{
        ErrorCode::InvalidValue,
        "unknown debug view '" + name + "' (known: none, cascade, blocker, penumbra, visibility, steps, closest)"};
}

}  // namespace shadow::viewer
