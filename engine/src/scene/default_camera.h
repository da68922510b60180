// Where the cameras the engine adds to a scene without one look from: `addDefaultCamera` and the
// default rig's camera (default_rig.cpp) stand in the same direction from what they frame.
#pragma once

#include <glm/glm.hpp>

namespace shadow {

/// From the framed point towards the eye (not unit): above, to the front (+Z) and the right (+X),
/// 25 degrees above the horizon.
inline glm::dvec3 defaultCameraOffset() { return {1.0, 0.8, 1.4}; }

}  // namespace shadow
