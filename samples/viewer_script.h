// The viewer's script language: one command a line, run in order without any input, so that CI
// can drive the viewer under Xvfb (docs/viewer.md has the grammar and an example).
//
//   # a comment            blank lines and lines starting with # are skipped
//   time T                 sets the animation time (s) and pauses the clock
//   dt S                   the step between the frames of `frames` (s, > 0; default 1/30)
//   frames N               renders N frames, the clock advancing by dt between them
//   set LIGHT KEY VALUE    a light setting (viewer_settings.h's keys); LIGHT: index or `all`
//   debug VIEW [LIGHT]     none|cascade|blocker|penumbra|visibility|steps|closest
//   shadowmap LIGHT LAYER  shows that shadow-map layer in the UI; `shadowmap off` hides it
//   camera N               looks through the scene's camera N
//   exposure E|auto        exposure of screenshots and the window (auto: as shadow_render)
//   screenshot PATH        writes the rendered scene (no UI) as PNG
//   screenshot-ui PATH     writes the window, UI included, as PNG
//   quit                   ends the run (exit 0); so does the end of the script
//
// The whole script is parsed and checked against the scene before the first frame: a bad line
// is one error naming the file and line, and nothing is written. A script is a regular file of
// at most 1 MiB (kMaxScriptBytes) with lines of at most 4096 bytes.
#pragma once

#include <shadow/renderer.h>
#include <shadow/result.h>

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace shadow::viewer {

/// One checked command of a script.
struct ScriptCommand {
    enum class Verb { Time, Dt, Frames, Set, Debug, ShadowMap, Camera, Exposure, Screenshot, ScreenshotUi, Quit };
    Verb verb = Verb::Quit;
    int line = 0;  ///< 1-based line of the script, for messages
    /// Set, Debug, ShadowMap, Camera: the light or camera index; absent for `all` (Set), for a
    /// debug view without a light (the current one kept), for `shadowmap off` and `exposure auto`.
    std::optional<int> index;
    double number = 0.0;  ///< Time, Dt, Exposure: the value; Frames: N; Set: the parsed value; ShadowMap: the layer
    std::string key;      ///< Set: the setting's key
    std::string path;     ///< Screenshot, ScreenshotUi
    DebugView view = DebugView::None;
};

/// Largest script file read (bytes): some fifty thousand commands.
inline constexpr std::size_t kMaxScriptBytes = std::size_t{1} << 20U;
/// Longest line of a script (bytes); a longer one is an error that does not quote it.
inline constexpr std::size_t kMaxScriptLine = 4096;
/// Longest error message about a script (bytes): the quoted line and words are cut to fit.
inline constexpr std::size_t kMaxScriptMessage = 1024;

/// The text of the script file `path`: a regular file (a FIFO, device or folder is refused
/// without being opened, so nothing blocks) of at most `kMaxScriptBytes`. The error names the
/// file as `--script PATH: ...`.
[[nodiscard]] Result<std::string> readScriptFile(const std::string& path);

/// What a script is checked against.
struct ScriptContext {
    int lights = 0;   ///< `Scene::lights.size()`
    int cameras = 0;  ///< `Scene::cameras.size()`
};

/// Parses and checks the script `text`, read from `fileName` (named in messages as
/// `FILE:LINE: ...`; a message is at most `kMaxScriptMessage` bytes and quotes at most 80 of
/// the line).
[[nodiscard]] Result<std::vector<ScriptCommand>> parseScript(const std::string& text, const std::string& fileName,
                                                             const ScriptContext& context);

/// A debug view by the name `--debug` and `debug` use ("none", "cascade", ...), or an error
/// listing the names.
[[nodiscard]] Result<DebugView> parseDebugView(const std::string& name);
/// The name of `view`.
[[nodiscard]] const char* debugViewName(DebugView view);
/// Every debug view, in menu order.
[[nodiscard]] const std::vector<DebugView>& debugViews();

}  // namespace shadow::viewer
