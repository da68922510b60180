// The viewer's Dear ImGui panels: the scene (camera, animation, exposure, debug views), a panel
// per light (its settings from viewer_settings.h's table, applied live, and what the shadow system
// did for it), the frame (timing graphs, counters, warnings) and a shadow-map layer.
#pragma once

#include "viewer_app.h"

#include <optional>

namespace shadow::viewer {

/// What the user asked for in the UI, for the loop to do after the frame.
struct UiRequests {
    bool screenshot = false;
    std::optional<int> sceneCamera;  ///< look through the scene's camera N again
    bool reload = false;             ///< load the scene again (the default rig was turned on or off)
};

/// Draws the last frame behind everything, and with `state.showUi` the panels, between
/// `ImGui::NewFrame` and `ImGui::Render`. Edits go into `state` and the scene's components.
void drawUi(ViewerState& state, UiRequests& requests);

}  // namespace shadow::viewer
