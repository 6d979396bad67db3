// Capturing VTK's messages while a .vtp is read: VtkMessages.h.
#include "VtkMessages.h"

#include <vtkCallbackCommand.h>
#include <vtkCommand.h>
#include <vtkLogger.h>
#include <vtkNew.h>
#include <vtkObject.h>
#include <vtkObjectFactory.h>
#include <vtkOutputWindow.h>
#include <vtkSmartPointer.h>

#include <cctype>
#include <cstring>
#include <vector>

namespace fascia::surface::detail {

namespace {

/// Warnings that say a read went wrong count as errors ("Error reading ..." comes as a warning from
/// some of VTK's parsers); the others (deprecated attributes, ...) are dropped.
bool reportsError(const char* text) { return text && std::strstr(text, "rror"); }

/// An output window that prints nothing and keeps the errors.
class SilentWindow : public vtkOutputWindow {
public:
    static SilentWindow* New();
    vtkTypeMacro(SilentWindow, vtkOutputWindow)
    void DisplayText(const char*) override {}
    void DisplayDebugText(const char*) override {}
    void DisplayErrorText(const char* text) override {
        if (text) caught.emplace_back(text);
    }
    void DisplayWarningText(const char* text) override { keepIfError(text); }
    void DisplayGenericWarningText(const char* text) override { keepIfError(text); }
    std::vector<std::string> caught;

protected:
    SilentWindow() = default;

private:
    void keepIfError(const char* text) {
        if (reportsError(text)) caught.emplace_back(text);
    }
};
vtkStandardNewMacro(SilentWindow)

/// The text of one VTK message: "ERROR: In /path/x.cxx, line 12\nvtkXMLPolyDataReader (0x55..): text\n\n"
/// becomes "text"; only its first line is kept.
std::string plain(std::string m) {
    for (const char* head : {"ERROR:", "Warning:", "Generic Warning:"})
        if (m.compare(0, std::strlen(head), head) == 0) {
            const size_t nl = m.find('\n');
            m = nl == std::string::npos ? std::string() : m.substr(nl + 1);
            break;
        }
    if (m.compare(0, 3, "vtk") == 0)
        if (const size_t p = m.find("): "); p != std::string::npos) m = m.substr(p + 3);
    if (const size_t nl = m.find('\n'); nl != std::string::npos) m.resize(nl);
    while (!m.empty() && std::isspace((unsigned char)m.back())) m.pop_back();
    // the pipeline's "Algorithm ... returned failure for request" repeats the reader's failure
    if (m.find("returned failure for request") != std::string::npos) return {};
    return m;
}

} // namespace

struct VtkMessages::State {
    vtkSmartPointer<vtkOutputWindow> previous;
    int warningDisplay = 1;
    vtkLogger::Verbosity stderrVerbosity = vtkLogger::VERBOSITY_INFO;
    vtkNew<SilentWindow> window;
    vtkNew<vtkCallbackCommand> observer;
    std::vector<std::string> observed;

    static void onEvent(vtkObject*, unsigned long event, void* self, void* data) {
        const char* text = static_cast<const char*>(data);
        if (text && (event == vtkCommand::ErrorEvent || reportsError(text))) static_cast<State*>(self)->observed.emplace_back(text);
    }
};

VtkMessages::VtkMessages() : m(std::make_unique<State>()) {
    m->previous = vtkOutputWindow::GetInstance();
    m->warningDisplay = vtkObject::GetGlobalWarningDisplay();
    m->stderrVerbosity = vtkLogger::GetCurrentVerbosityCutoff();
    // with the global display off VTK drops its messages before any observer or window sees them
    vtkObject::GlobalWarningDisplayOn();
    vtkOutputWindow::SetInstance(m->window);
    vtkLogger::SetStderrVerbosity(vtkLogger::VERBOSITY_OFF);
    m->observer->SetClientData(m.get());
    m->observer->SetCallback(&State::onEvent);
}

VtkMessages::~VtkMessages() {
    vtkLogger::SetStderrVerbosity(m->stderrVerbosity);
    vtkOutputWindow::SetInstance(m->previous);
    vtkObject::SetGlobalWarningDisplay(m->warningDisplay);
}

void VtkMessages::watch(vtkObject* obj) {
    obj->AddObserver(vtkCommand::ErrorEvent, m->observer);
    obj->AddObserver(vtkCommand::WarningEvent, m->observer);
}

bool VtkMessages::any() const { return !m->observed.empty() || !m->window->caught.empty(); }

std::string VtkMessages::text() const {
    std::string out;
    auto add = [&](const std::string& raw) {
        const std::string t = plain(raw);
        if (!t.empty() && out.find(t) == std::string::npos) out += (out.empty() ? "" : "; ") + t;
    };
    for (const auto& e : m->observed) add(e);
    for (const auto& e : m->window->caught) add(e);
    return out;
}

} // namespace fascia::surface::detail
