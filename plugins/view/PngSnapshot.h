#pragma once
#include "Display.h"
#include "SceneRenderer.h"

#include "fascia/sim/Mechanics.h"

#include <memory>

namespace fascia::view {

/// Pictures of a run without the viewer: the bodies' surfaces coloured by a field, the tools and the
/// constrained nodes, drawn offscreen by fascia-view's renderer (SceneRenderer.h) from a camera
/// given here or fitted to the bodies. With every="N" it writes <filename>_<step>.png every N steps
/// (the initial state too), and always <filename>.png of the final state at the end of the run.
/// Each file is written under a temporary name and renamed. VTK renders through an X display: where
/// none opens it starts its own Xvfb at init (and stops it at the end), and where Xvfb is not
/// installed init fails with an output error (exit 1), before any step.
class PngSnapshot : public core::BaseObserver {
public:
    PngSnapshot();
    ~PngSnapshot() override;
    void init() override;
    void observe(double t, long step) override;
    bool records(long step) const override { return m_every.get() > 0 && step % m_every.get() == 0; }
    void observeFinal(double t, long step) override;
    void cleanup() override;

    core::Param<std::string> m_filename{this, core::ParamSpec("filename").help("base name of the pictures, relative to the output folder (default: the component's name); a trailing .png is dropped")};
    core::Param<int> m_every{this, core::ParamSpec("every").min(0).help("write a picture every N steps as <filename>_<step>.png (0: only the final one, <filename>.png)"), 0};
    core::Param<std::string> m_field{this, core::ParamSpec("field").choices({"displacement", "vonMises", "J", "none"}).help("the field the surface is coloured by: displacement (mm), vonMises (kPa, averaged over the elements around each node), J or none"), "displacement"};
    core::Param<std::string> m_camera{this, core::ParamSpec("camera").help("iso, x, -x, y, -y, z, -z (looking along that axis), or \"PX PY PZ FX FY FZ\": the camera's position and focal point (m)"), "iso"};
    core::Param<int> m_width{this, core::ParamSpec("width").min(64).max(8192).unit("px").help("picture width"), 1024};
    core::Param<int> m_height{this, core::ParamSpec("height").min(64).max(8192).unit("px").help("picture height"), 768};
    core::Param<double> m_rangeMin{this, core::ParamSpec("rangeMin").help("the colour range's low end, in the field's unit (with rangeMax; default: the range follows the data)"), 0.0};
    core::Param<double> m_rangeMax{this, core::ParamSpec("rangeMax").help("the colour range's high end (a fixed range when above rangeMin)"), 0.0};
    core::Param<std::string> m_surface{this, core::ParamSpec("surface").help("the only surface to draw: a mechanical state or a visual surface, by name or path (default: every body's)")};
    core::Param<bool> m_text{this, core::ParamSpec("text").help("draw the time, the step and the colour bar"), true};

    /// The files written so far (output-folder paths), for fascia-run's closing lines.
    const std::vector<std::string>& written() const { return m_written; }

private:
    void write(double t, long step, const std::string& path);
    std::string m_base;
    long m_lastStep = -1;
    std::unique_ptr<PrivateDisplay> m_display;
    std::unique_ptr<FrameSource> m_source;
    std::unique_ptr<SceneRenderer> m_renderer;
    Frame m_frame;
    std::vector<std::string> m_written;
};

} // namespace fascia::view
