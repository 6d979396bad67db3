#include "SceneRenderer.h"

#include "fascia/base/Error.h"

#include <vtkActor.h>
#include <vtkCamera.h>
#include <vtkCellArray.h>
#include <vtkCellPicker.h>
#include <vtkDoubleArray.h>
#include <vtkLookupTable.h>
#include <vtkNew.h>
#include <vtkPNGWriter.h>
#include <vtkPointData.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkPolyDataNormals.h>
#include <vtkProperty.h>
#include <vtkRenderWindow.h>
#include <vtkRenderer.h>
#include <vtkScalarBarActor.h>
#include <vtkSmartPointer.h>
#include <vtkTextActor.h>
#include <vtkTextProperty.h>
#include <vtkWindowToImageFilter.h>

#include <cmath>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <sstream>

namespace fascia::view {

namespace {

/// A surface drawn from our points and triangles, optionally through point normals (smooth shading).
struct Surface {
    vtkNew<vtkPolyData> poly;
    vtkNew<vtkPoints> points;
    vtkNew<vtkDoubleArray> field;
    vtkNew<vtkPolyDataNormals> normals;
    vtkNew<vtkPolyDataMapper> mapper;
    vtkNew<vtkActor> actor;

    Surface(const Triangles& triangles, bool smooth) {
        points->SetDataTypeToDouble();
        poly->SetPoints(points);
        vtkNew<vtkCellArray> cells;
        for (auto& t : triangles) {
            const vtkIdType ids[3] = {t[0], t[1], t[2]};
            cells->InsertNextCell(3, ids);
        }
        poly->SetPolys(cells);
        if (smooth) {
            normals->SetInputData(poly);
            normals->SplittingOff();       // one normal per point: cell and point ids stay ours
            normals->ConsistencyOff();     // (the triangles are turned outwards already)
            normals->AutoOrientNormalsOff();
            normals->ComputeCellNormalsOff();
            mapper->SetInputConnection(normals->GetOutputPort());
        } else {
            mapper->SetInputData(poly);
        }
        actor->SetMapper(mapper);
    }
    void setPoints(const Positions& p) {
        points->SetNumberOfPoints(vtkIdType(p.size()));
        for (size_t i = 0; i < p.size(); ++i) points->SetPoint(vtkIdType(i), p[i].data());
        points->Modified();
        poly->Modified();
    }
};

/// A diverging blue - white - red table (Moreland's cool to warm end points).
vtkSmartPointer<vtkLookupTable> coolToWarm() {
    auto lut = vtkSmartPointer<vtkLookupTable>::New();
    lut->SetNumberOfTableValues(256);
    const double lo[3] = {0.23, 0.30, 0.75}, mid[3] = {0.87, 0.87, 0.87}, hi[3] = {0.71, 0.02, 0.15};
    for (int i = 0; i < 256; ++i) {
        const double s = i / 255.0;
        const double* a = s < 0.5 ? lo : mid;
        const double* b = s < 0.5 ? mid : hi;
        const double w = s < 0.5 ? 2 * s : 2 * s - 1;
        lut->SetTableValue(i, a[0] + w * (b[0] - a[0]), a[1] + w * (b[1] - a[1]), a[2] + w * (b[2] - a[2]), 1.0);
    }
    lut->SetNanColor(0.6, 0.6, 0.6, 1.0);
    lut->Build();
    return lut;
}

/// The camera's view direction and up vector for a named view.
bool namedView(const std::string& name, Vec3& dir, Vec3& up) {
    up = Vec3(0, 0, 1);
    if (name == "iso") dir = Vec3(-0.5, 1, -0.9).normalized();  // from the front (-y), right (+x) and above
    else if (name == "x" || name == "-x") dir = Vec3(name[0] == '-' ? -1 : 1, 0, 0);
    else if (name == "y" || name == "-y") dir = Vec3(0, name[0] == '-' ? -1 : 1, 0);
    else if (name == "z" || name == "-z") dir = Vec3(0, 0, name[0] == '-' ? -1 : 1), up = Vec3(0, 1, 0);
    else return false;
    return true;
}

bool explicitCamera(const std::string& text, Vec3& position, Vec3& focal) {
    std::istringstream in(text);
    double v[6];
    for (double& d : v)
        if (!(in >> d) || !std::isfinite(d)) return false;
    std::string rest;
    if (in >> rest) return false;
    position = Vec3(v[0], v[1], v[2]), focal = Vec3(v[3], v[4], v[5]);
    return (position - focal).norm() > 0;
}

} // namespace

void checkCamera(const std::string& camera) {
    Vec3 a, b;
    if (!namedView(camera, a, b) && !explicitCamera(camera, a, b))
        core::throwInputError({}, "camera '" + camera + "' is not a view",
                              {"give iso, x, -x, y, -y, z or -z (looking along that axis), or six numbers: the camera's "
                               "position and its focal point (m)"});
}

struct SceneRenderer::Impl {
    RenderOptions options;
    vtkNew<vtkRenderWindow> window;
    vtkNew<vtkRenderer> renderer;
    vtkSmartPointer<vtkLookupTable> lut = coolToWarm();
    vtkNew<vtkScalarBarActor> bar;
    vtkNew<vtkTextActor> status, help;
    std::vector<std::unique_ptr<Surface>> bodies, tools;
    std::vector<vtkSmartPointer<vtkPolyData>> marks;  ///< per body: its constrained points
    std::vector<vtkSmartPointer<vtkActor>> markActors;
    vtkNew<vtkPolyData> grab;
    vtkNew<vtkActor> grabActor;
    vtkNew<vtkCellPicker> picker;
    Vec3 lo = Vec3::Constant(1e300), hi = Vec3::Constant(-1e300);  ///< the bodies' box at the first frame
    double range[2] = {0, 1e-9};
    bool built = false;

    void build(const Frame& f);
    void update(const Frame& f);
    void colourRange(const Frame& f);
};

SceneRenderer::SceneRenderer(const RenderOptions& options) : m_impl(std::make_unique<Impl>()) {
    Impl& m = *m_impl;
    m.options = options;
    checkCamera(options.camera);
    m.window->SetSize(options.width, options.height);
    m.window->SetMultiSamples(0);  // (8 by default: in software rendering, several times the frame time)
    m.window->SetOffScreenRendering(options.offscreen ? 1 : 0);
    m.window->SetWindowName("fascia-view");
    m.window->AddRenderer(m.renderer);
    m.renderer->SetBackground(0.12, 0.13, 0.16);
    m.renderer->SetBackground2(0.32, 0.34, 0.40);
    m.renderer->SetGradientBackground(options.gradient);
    m.picker->SetTolerance(0.0005);
    m.picker->PickFromListOn();
}

SceneRenderer::~SceneRenderer() = default;

void SceneRenderer::Impl::build(const Frame& f) {
    for (auto& b : f.bodies) {
        auto s = std::make_unique<Surface>(b.triangles, true);
        s->setPoints(b.points);
        s->field->SetName("field");
        s->poly->GetPointData()->SetScalars(s->field);
        s->mapper->SetLookupTable(lut);
        s->mapper->SetScalarVisibility(f.field != Field::None);
        s->mapper->SetScalarModeToUsePointData();
        s->actor->GetProperty()->SetColor(0.85, 0.55, 0.50);  // tissue, for Field::None
        s->actor->GetProperty()->SetSpecular(0.2);
        s->actor->GetProperty()->SetSpecularPower(20);
        renderer->AddActor(s->actor);
        picker->AddPickList(s->actor);
        for (auto& p : b.points) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
        bodies.push_back(std::move(s));
        auto mark = vtkSmartPointer<vtkPolyData>::New();
        auto markActor = vtkSmartPointer<vtkActor>::New();
        vtkNew<vtkPolyDataMapper> markMapper;
        markMapper->SetInputData(mark);
        markMapper->ScalarVisibilityOff();
        markActor->SetMapper(markMapper);
        markActor->GetProperty()->SetColor(0.1, 0.1, 0.1);
        markActor->GetProperty()->SetPointSize(6);
        markActor->GetProperty()->RenderPointsAsSpheresOn();
        markActor->SetVisibility(options.markConstrained && !b.constrained.empty());
        renderer->AddActor(markActor);
        marks.push_back(mark);
        markActors.push_back(markActor);
    }
    for (auto& t : f.tools) {
        auto s = std::make_unique<Surface>(t.triangles, t.triangles.size() > 2);
        s->setPoints(t.points);
        s->mapper->ScalarVisibilityOff();
        s->actor->GetProperty()->SetColor(0.72, 0.74, 0.78);
        s->actor->GetProperty()->SetSpecular(0.6);
        s->actor->GetProperty()->SetSpecularPower(40);
        if (t.triangles.size() <= 2) s->actor->GetProperty()->SetOpacity(0.35);  // a plane's square
        s->actor->SetVisibility(options.drawTools);
        renderer->AddActor(s->actor);
        tools.push_back(std::move(s));
    }
    grabActor->GetProperty()->SetColor(1.0, 0.85, 0.1);
    grabActor->GetProperty()->SetLineWidth(3);
    grabActor->GetProperty()->SetPointSize(10);
    grabActor->GetProperty()->RenderPointsAsSpheresOn();
    vtkNew<vtkPolyDataMapper> grabMapper;
    grabMapper->SetInputData(grab);
    grabActor->SetMapper(grabMapper);
    grabActor->VisibilityOff();
    renderer->AddActor(grabActor);
    bar->SetLookupTable(lut);
    bar->SetTitle((std::string(fieldName(f.field)) + (*fieldUnit(f.field) ? std::string("\n(") + fieldUnit(f.field) + ")" : "")).c_str());
    bar->SetNumberOfLabels(5);
    bar->UnconstrainedFontSizeOn();
    for (vtkTextProperty* p : {bar->GetTitleTextProperty(), bar->GetLabelTextProperty()}) {
        p->SetFontSize(p == bar->GetTitleTextProperty() ? 16 : 14);
        p->ItalicOff();
        p->BoldOff();
        p->ShadowOff();
        p->SetColor(0.95, 0.95, 0.95);
    }
    bar->SetVerticalTitleSeparation(8);
    bar->SetMaximumWidthInPixels(90);
    bar->SetPosition(0.86, 0.1);
    bar->SetHeight(0.8);
    bar->SetVisibility(options.scalarBar && f.field != Field::None);
    renderer->AddViewProp(bar);
    for (vtkTextActor* t : {status.Get(), help.Get()}) {
        t->GetTextProperty()->SetFontSize(15);
        t->GetTextProperty()->SetColor(0.95, 0.95, 0.95);
        t->SetVisibility(options.text);
        renderer->AddViewProp(t);
    }
    status->GetTextProperty()->SetVerticalJustificationToTop();
    help->SetPosition(10, 10);
    help->SetInput(options.help.c_str());
    help->GetTextProperty()->SetFontSize(13);
    built = true;
}

void SceneRenderer::Impl::colourRange(const Frame& f) {
    if (options.rangeMin < options.rangeMax) {
        range[0] = options.rangeMin, range[1] = options.rangeMax;
        return;
    }
    double a = 1e300, b = -1e300;
    for (auto& body : f.bodies)
        for (double v : body.field)
            if (std::isfinite(v)) a = std::min(a, v), b = std::max(b, v);
    if (!(a <= b)) a = 0, b = 1;
    if (f.field == Field::Displacement) a = 0;            // displacement from zero
    if (f.field == Field::J) {                             // J about 1, symmetric
        const double d = std::max({std::abs(a - 1), std::abs(b - 1), 1e-6});
        a = 1 - d, b = 1 + d;
    }
    if (b - a < 1e-9) b = a + 1e-9;
    range[0] = a, range[1] = b;
}

void SceneRenderer::Impl::update(const Frame& f) {
    colourRange(f);
    lut->SetTableRange(range);
    for (size_t k = 0; k < f.bodies.size() && k < bodies.size(); ++k) {
        const BodyFrame& b = f.bodies[k];
        Surface& s = *bodies[k];
        s.setPoints(b.points);
        s.field->SetNumberOfTuples(vtkIdType(b.field.size()));
        for (size_t i = 0; i < b.field.size(); ++i) s.field->SetValue(vtkIdType(i), b.field[i]);
        s.field->Modified();
        s.mapper->SetScalarRange(range);
        vtkNew<vtkPoints> mp;
        vtkNew<vtkCellArray> verts;
        for (int i : b.constrained) {
            const vtkIdType id = mp->InsertNextPoint(b.points[i].data());
            verts->InsertNextCell(1, &id);
        }
        marks[k]->SetPoints(mp);
        marks[k]->SetVerts(verts);
    }
    for (size_t k = 0; k < f.tools.size() && k < tools.size(); ++k) tools[k]->setPoints(f.tools[k].points);
    grabActor->SetVisibility(f.grab.active);
    if (f.grab.active) {
        vtkNew<vtkPoints> gp;
        gp->InsertNextPoint(f.grab.node.data());
        gp->InsertNextPoint(f.grab.target.data());
        vtkNew<vtkCellArray> line, verts;
        const vtkIdType ids[2] = {0, 1};
        line->InsertNextCell(2, ids);
        verts->InsertNextCell(1, &ids[1]);
        grab->SetPoints(gp);
        grab->SetLines(line);
        grab->SetVerts(verts);
    }
}

void SceneRenderer::show(const Frame& frame) {
    if (!m_impl->built) {
        m_impl->build(frame);
        m_impl->update(frame);
        fitCamera();
    } else {
        m_impl->update(frame);
    }
    m_impl->renderer->ResetCameraClippingRange();
}

void SceneRenderer::setStatus(const std::string& text) {
    m_impl->status->SetInput(text.c_str());
    m_impl->status->SetPosition(10, m_impl->window->GetSize()[1] - 10);
}

void SceneRenderer::render() { m_impl->window->Render(); }

void SceneRenderer::fitCamera() {
    Impl& m = *m_impl;
    vtkCamera* cam = m.renderer->GetActiveCamera();
    const Vec3 centre = 0.5 * (m.lo + m.hi);
    const double radius = std::max(0.5 * (m.hi - m.lo).norm(), 1e-6);
    Vec3 dir, up, position, focal;
    if (namedView(m.options.camera, dir, up)) {
        // the body's bounding sphere fills the view angle (30 degrees), a little margin around it
        const double distance = 1.1 * radius / std::sin(M_PI / 12);
        focal = centre, position = centre - distance * dir;
    } else {
        explicitCamera(m.options.camera, position, focal);
        up = std::abs((focal - position).normalized().z()) > 0.99 ? Vec3(0, 1, 0) : Vec3(0, 0, 1);
    }
    cam->SetFocalPoint(focal.data());
    cam->SetPosition(position.data());
    cam->SetViewUp(up.data());
    cam->SetViewAngle(30);
    m.renderer->ResetCameraClippingRange();
}

void SceneRenderer::writePng(const std::string& path) {
    namespace fs = std::filesystem;
    const fs::path target(path);
    const fs::path tmp = target.parent_path() / ("." + target.filename().string() + ".tmp");
    if (target.filename().empty() || fs::is_directory(target))
        core::throwOutputError({path, 0}, "the picture's path is a folder, not a file");
    if (FILE* probe = std::fopen(tmp.c_str(), "wb")) std::fclose(probe);
    else core::throwOutputError({path, 0}, "cannot write the picture here: " + std::string(std::strerror(errno)));
    render();
    vtkNew<vtkWindowToImageFilter> grabber;
    grabber->SetInput(m_impl->window);
    grabber->SetInputBufferTypeToRGB();
    grabber->ReadFrontBufferOff();
    grabber->Update();
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(tmp.c_str());
    writer->SetInputConnection(grabber->GetOutputPort());
    writer->Write();
    std::error_code ec;
    if (writer->GetErrorCode() != 0) {
        fs::remove(tmp, ec);
        core::throwOutputError({path, 0}, "the picture could not be written (VTK's PNG writer failed: disk full?)");
    }
    fs::rename(tmp, target, ec);
    if (ec) {
        fs::remove(tmp, ec);
        core::throwOutputError({path, 0}, "cannot write the picture here: " + ec.message());
    }
}

bool SceneRenderer::pick(int x, int y, int& body, int& point, Vec3& world) {
    Impl& m = *m_impl;
    if (!m.picker->Pick(x, y, 0, m.renderer)) return false;
    vtkActor* actor = m.picker->GetActor();
    for (size_t k = 0; k < m.bodies.size(); ++k) {
        if (m.bodies[k]->actor.Get() != actor) continue;
        const vtkIdType cell = m.picker->GetCellId();
        if (cell < 0) return false;
        m.picker->GetPickPosition(world.data());
        vtkIdType n;
        const vtkIdType* ids;
        m.bodies[k]->poly->GetCellPoints(cell, n, ids);
        double best = 1e300;
        for (vtkIdType i = 0; i < n; ++i) {
            Vec3 p;
            m.bodies[k]->points->GetPoint(ids[i], p.data());
            if ((p - world).squaredNorm() < best) best = (p - world).squaredNorm(), point = int(ids[i]);
        }
        body = int(k);
        return true;
    }
    return false;
}

Vec3 SceneRenderer::worldToDisplay(const Vec3& world) {
    vtkRenderer* r = m_impl->renderer;
    r->SetWorldPoint(world.x(), world.y(), world.z(), 1.0);
    r->WorldToDisplay();
    Vec3 d;
    r->GetDisplayPoint(d.data());
    return d;
}

Vec3 SceneRenderer::displayToWorld(int x, int y, const Vec3& depth) {
    vtkRenderer* r = m_impl->renderer;
    const double z = worldToDisplay(depth).z();
    r->SetDisplayPoint(x, y, z);
    r->DisplayToWorld();
    double w[4];
    r->GetWorldPoint(w);
    return Vec3(w[0], w[1], w[2]) / (w[3] != 0 ? w[3] : 1.0);
}

vtkRenderWindow* SceneRenderer::window() { return m_impl->window; }
vtkRenderer* SceneRenderer::renderer() { return m_impl->renderer; }
double SceneRenderer::rangeMin() const { return m_impl->range[0]; }
double SceneRenderer::rangeMax() const { return m_impl->range[1]; }

} // namespace fascia::view
