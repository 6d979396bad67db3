#pragma once
/// Draws a Frame with VTK: the bodies' surfaces coloured by their field with a colour bar, the
/// constrained nodes as dots, the tools as grey shapes, the grab spring, a status text. The same
/// renderer makes fascia-view's window and the offscreen pictures (fascia-view --screenshot,
/// PngSnapshot). VTK stays inside the .cpp: its types are only forward-declared here.
#include "Frame.h"

#include <memory>
#include <string>

class vtkRenderWindow;
class vtkRenderer;

namespace fascia::view {

struct RenderOptions {
    int width = 1024, height = 768;
    bool offscreen = false;
    bool scalarBar = true;       ///< the colour bar of the field
    bool text = true;            ///< the status text (top left) and the key help (bottom left)
    bool markConstrained = true; ///< the constrained surface nodes as dots
    bool drawTools = true;
    bool gradient = true;        ///< a graded background (false: a plain one, for tests)
    /// The colour range of the field: fixed when min < max, else it follows the data (the range of
    /// the frame, never shrinking below [0, 1e-9]).
    double rangeMin = 0, rangeMax = 0;
    /// The view direction: "iso" (from the front, right and above: -y, +x, +z), "x", "-x", "y", "-y", "z", "-z"
    /// (looking along that axis), or "px py pz fx fy fz" (the camera position and focal point, m).
    std::string camera = "iso";
    std::string help;            ///< the key help (bottom left)
};

/// Throws an input error for a camera text that is none of the forms above.
void checkCamera(const std::string& camera);

class SceneRenderer {
public:
    explicit SceneRenderer(const RenderOptions& options);
    ~SceneRenderer();
    SceneRenderer(const SceneRenderer&) = delete;
    SceneRenderer& operator=(const SceneRenderer&) = delete;

    /// Shows `frame`: the first call builds the actors and fits the camera to the bodies, later
    /// ones move the points and recolour. Does not render.
    void show(const Frame& frame);
    /// Sets the status text (top left).
    void setStatus(const std::string& text);
    /// Renders into the window.
    void render();
    /// Renders and writes the picture to `path` as PNG, through a temporary file in its folder and a
    /// rename (an output error when it cannot be written).
    void writePng(const std::string& path);
    /// Fits the camera to the bodies, along the options' view direction.
    void fitCamera();

    /// The body and surface point nearest to where the display point (x, y) (pixels, origin bottom
    /// left) hits a body's surface; false when it hits none. `world` gets the hit point.
    bool pick(int x, int y, int& body, int& point, Vec3& world);
    /// The world point under the display point (x, y) at the depth of `depth` (a point in the
    /// scene): where a dragged point goes.
    Vec3 displayToWorld(int x, int y, const Vec3& depth);
    /// The display point (x, y, depth) of a world point.
    Vec3 worldToDisplay(const Vec3& world);

    vtkRenderWindow* window();
    vtkRenderer* renderer();
    /// The colour range of the last frame drawn.
    double rangeMin() const;
    double rangeMax() const;

private:
    struct Impl;
    std::unique_ptr<Impl> m_impl;
};

} // namespace fascia::view
