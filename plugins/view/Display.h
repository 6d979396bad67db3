#pragma once
/// An X display for VTK's render window. Debian's VTK renders through GLX only, and VTK aborts the
/// process when it cannot open a display: so a display is checked (or started) here first, and its
/// absence is a clear error instead (docs/viewer.md, exit code 4).
#include <exception>
#include <string>
#include <sys/types.h>

namespace fascia::view {

/// Thrown when there is no display and none can be started.
struct NoDisplayError : std::exception {
    std::string text;
    explicit NoDisplayError(std::string t) : text(std::move(t)) {}
    const char* what() const noexcept override { return text.c_str(); }
};

/// Whether $DISPLAY names a display that opens.
bool displayOpens();

/// A private Xvfb server for offscreen pictures, started only when no display opens (and stopped
/// when the object goes). Without Xvfb on PATH (Debian's xvfb), a NoDisplayError.
class PrivateDisplay {
public:
    /// `allowStart`: start Xvfb when no display opens (pictures); false: a window was asked for,
    /// which needs the user's display (an error naming xvfb-run otherwise).
    explicit PrivateDisplay(bool allowStart);
    ~PrivateDisplay();
    PrivateDisplay(const PrivateDisplay&) = delete;
    PrivateDisplay& operator=(const PrivateDisplay&) = delete;
    bool started() const { return m_pid > 0; }

private:
    pid_t m_pid = -1;
};

} // namespace fascia::view
