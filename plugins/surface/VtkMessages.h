#pragma once
/// VTK's readers report trouble by printing it (through vtkOutputWindow, and vtkLogger for objects
/// nobody observes) and returning an empty or partial output; they throw nothing. While a
/// VtkMessages lives, those messages go to it instead of the console, so that the .vtp reader
/// (VtpReader.cpp) can turn them into one located Fascia error. Private to the surface library;
/// needs VTK. (plugins/meshio/VTKReader.cpp does the same for .vtu meshes, privately: meshio links
/// this library, not the reverse, so the surface library cannot use it.)
#include <memory>
#include <string>

class vtkObject;

namespace fascia::surface::detail {

class VtkMessages {
public:
    VtkMessages();   ///< starts capturing (the output window, vtkLogger's stderr)
    ~VtkMessages();  ///< restores what was there before
    VtkMessages(const VtkMessages&) = delete;
    VtkMessages& operator=(const VtkMessages&) = delete;

    /// Also catches obj's ErrorEvent and WarningEvent (an observed object sends its messages there
    /// rather than to the output window).
    void watch(vtkObject* obj);
    /// Whether an error, or a warning that reports one, was caught.
    bool any() const;
    /// The messages caught, each reduced to its text (VTK's "ERROR: In file.cxx, line N" and
    /// "vtkClass (0x...):" prefixes dropped), "; "-separated, each once.
    std::string text() const;

private:
    struct State;
    std::unique_ptr<State> m;
};

} // namespace fascia::surface::detail
