#include "PngSnapshot.h"

#include "fascia/base/Error.h"
#include "fascia/scene/Node.h"

#include <cstdio>
#include <filesystem>

namespace fascia::view {

namespace fs = std::filesystem;

PngSnapshot::PngSnapshot() = default;
PngSnapshot::~PngSnapshot() = default;

void PngSnapshot::init() {
    try {
        checkCamera(m_camera.get());
    } catch (const core::Error& e) {
        throw core::Error(e.kind(), m_camera.loc().empty() ? loc() : m_camera.loc(), e.message(), e.notes());
    }
    std::string file = m_filename.get().empty() ? name() : m_filename.get();
    if (file.size() > 4 && file.compare(file.size() - 4, 4, ".png") == 0) file.resize(file.size() - 4);
    m_base = (fs::path(node()->context().outputDir) / file).string();
    node()->context().claimOutput(m_base + ".png", *this);
    try {
        m_display = std::make_unique<PrivateDisplay>(true);
    } catch (const NoDisplayError& e) {
        core::throwOutputError(loc(), std::string("PngSnapshot cannot render: ") + e.what());
    }
}

void PngSnapshot::write(double t, long step, const std::string& path) {
    if (!m_renderer) {
        RenderOptions o;
        o.offscreen = true;
        o.width = m_width.get(), o.height = m_height.get();
        o.camera = m_camera.get();
        o.rangeMin = m_rangeMin.get(), o.rangeMax = m_rangeMax.get();
        o.text = o.scalarBar = m_text.get();
        m_source = std::make_unique<FrameSource>(*node()->root(), parseField(m_field.get()), m_surface.get());
        m_renderer = std::make_unique<SceneRenderer>(o);
    }
    m_source->capture(m_frame, t, step);
    m_renderer->show(m_frame);
    char text[200];
    std::snprintf(text, sizeof text, "t = %.4f s   step %ld", t, step);
    m_renderer->setStatus(text);
    m_renderer->writePng(path);
    m_written.push_back(path);
    m_lastStep = step;
}

void PngSnapshot::observe(double t, long step) {
    if (!records(step)) return;
    char suffix[32];
    std::snprintf(suffix, sizeof suffix, "_%06ld.png", step);
    write(t, step, m_base + suffix);
}

void PngSnapshot::observeFinal(double t, long step) { write(t, step, m_base + ".png"); }

void PngSnapshot::cleanup() {
    m_renderer.reset();
    m_display.reset();
}

} // namespace fascia::view
