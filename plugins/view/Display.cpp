#include "Display.h"

#include <X11/Xlib.h>

#include <cerrno>
#include <csignal>
#include <cstdlib>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <sys/wait.h>
#include <unistd.h>

namespace fascia::view {

bool displayOpens() {
    const char* name = std::getenv("DISPLAY");
    if (!name || !*name) return false;
    Display* d = XOpenDisplay(name);
    if (!d) return false;
    XCloseDisplay(d);
    return true;
}

namespace {

bool onPath(const char* program) {
    const char* path = std::getenv("PATH");
    std::string dirs = path ? path : "/usr/bin:/bin";
    size_t start = 0;
    while (start <= dirs.size()) {
        const size_t end = std::min(dirs.find(':', start), dirs.size());
        const std::string file = dirs.substr(start, end - start) + "/" + program;
        if (access(file.c_str(), X_OK) == 0) return true;
        start = end + 1;
    }
    return false;
}

/// Reads the display number Xvfb writes to fd when it is ready (-displayfd), waiting at most 10 s.
std::string readDisplayNumber(int fd) {
    std::string number;
    pollfd p{fd, POLLIN, 0};
    for (int waited = 0; waited < 100;) {
        const int r = poll(&p, 1, 100);
        if (r < 0 && errno == EINTR) continue;
        if (r == 0) {
            ++waited;
            continue;
        }
        char c;
        const ssize_t n = read(fd, &c, 1);
        if (n <= 0) break;  // Xvfb exited
        if (c == '\n') return number;
        number += c;
    }
    return "";
}

} // namespace

PrivateDisplay::PrivateDisplay(bool allowStart) {
    if (displayOpens()) return;
    const char* name = std::getenv("DISPLAY");
    const std::string why = name && *name ? "the display '" + std::string(name) + "' does not open" : "no display (DISPLAY is not set)";
    if (!allowStart)
        throw NoDisplayError(why + ": a window needs a display; run under `xvfb-run -a` for a virtual one, or use "
                                   "--screenshot FILE.png for a picture without a window");
    if (!onPath("Xvfb"))
        throw NoDisplayError(why + ", and Xvfb is not on PATH to render offscreen: install Debian's xvfb "
                                   "(apt-get install xvfb) or run on a machine with a display");
    int fds[2];
    if (pipe(fds) != 0) throw NoDisplayError(std::string("cannot start Xvfb: pipe: ") + std::strerror(errno));
    m_pid = fork();
    if (m_pid == 0) {
        close(fds[0]);
        const int devnull = open("/dev/null", O_RDWR);
        dup2(devnull, STDIN_FILENO), dup2(devnull, STDOUT_FILENO), dup2(devnull, STDERR_FILENO);
        const std::string fd = std::to_string(fds[1]);
        execlp("Xvfb", "Xvfb", "-displayfd", fd.c_str(), "-screen", "0", "1920x1200x24", "-nolisten", "tcp", "-noreset",
               static_cast<char*>(nullptr));
        _exit(127);
    }
    close(fds[1]);
    const std::string number = m_pid > 0 ? readDisplayNumber(fds[0]) : "";
    close(fds[0]);
    if (number.empty()) {
        if (m_pid > 0) kill(m_pid, SIGTERM), waitpid(m_pid, nullptr, 0);
        m_pid = -1;
        throw NoDisplayError(why + ", and Xvfb did not start (within 10 s) to render offscreen");
    }
    setenv("DISPLAY", (":" + number).c_str(), 1);
}

PrivateDisplay::~PrivateDisplay() {
    if (m_pid <= 0) return;
    kill(m_pid, SIGTERM);
    waitpid(m_pid, nullptr, 0);
}

} // namespace fascia::view
