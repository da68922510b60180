// The viewer's camera: it looks through a camera of the scene (the first, or the default one
// shadow_render would add) until the user moves it; then a free camera of the viewer's own takes
// over from the same pose, orbiting a pivot (drag to turn, scroll or right-drag to zoom,
// middle-drag to pan) or flying (drag to look, W/A/S/D/Q/E to move, Shift for speed).
#pragma once

#include <shadow/scene.h>

namespace shadow::viewer {

/// What moved the camera this frame.
struct CameraInput {
    double dx = 0.0, dy = 0.0;  ///< cursor motion while a button is held (pixels)
    bool turn = false;          ///< left button: orbit, or look around in fly mode
    bool zoom = false;          ///< right button: dolly by dy
    bool pan = false;           ///< middle button: move the pivot in the view plane
    double scroll = 0.0;        ///< wheel notches, up positive
    glm::dvec3 fly{0.0};        ///< fly mode: right, up, forward in [-1, 1]
    bool fast = false;
    double dt = 0.0;  ///< seconds since the last frame
};

/// The camera the viewer renders through.
class CameraRig {
public:
    enum class Mode { Scene, Orbit, Fly };

    /// Looks through `sceneCamera` of `scene` (a camera entity), forgetting any free camera: call
    /// after a scene is loaded (its transforms updated) or to go back to the scene's view.
    void reset(Scene& scene, Entity sceneCamera);
    /// The camera entity to render through this frame.
    [[nodiscard]] Entity camera() const { return mode_ == Mode::Scene ? sceneCamera_ : free_; }
    [[nodiscard]] Mode mode() const { return mode_; }
    /// Switches mode; leaving Scene starts the free camera at the scene camera's current pose.
    void setMode(World& world, Mode mode);
    /// Applies this frame's input. Any motion in Scene mode switches to Orbit first.
    void update(World& world, const CameraInput& in);
    /// Fly speed (m/s), set from the scene's size; scroll changes it in fly mode.
    [[nodiscard]] double flySpeed() const { return flySpeed_; }

private:
    void takeOverPose(World& world);
    void writePose(World& world) const;

    Entity sceneCamera_;
    Entity free_;
    Mode mode_ = Mode::Scene;
    glm::dvec3 pivot_{0.0};
    glm::dvec3 position_{0.0};
    double yaw_ = 0.0;    ///< about +Y (rad); 0 looks along -Z
    double pitch_ = 0.0;  ///< up from the horizon (rad)
    double distance_ = 1.0;
    double sceneRadius_ = 1.0;
    double flySpeed_ = 1.0;
};

}  // namespace shadow::viewer
