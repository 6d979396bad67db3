#include "PvdSeries.h"
#include "fascia/base/Component.h"
#include "fascia/base/Error.h"
#include "fascia/base/StateIO.h"

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fs = std::filesystem;

namespace fascia::meshio {

SeriesFile seriesFile(const std::string& dir, const std::string& base, long step, const char* extension) {
    char suffix[48];
    std::snprintf(suffix, sizeof suffix, "_%06ld%s", step, extension);
    SeriesFile f;
    f.name = fs::path(base).filename().string() + suffix;
    f.path = fs::path(dir) / fs::path(base).parent_path() / f.name;
    std::error_code ec;
    fs::create_directories(f.path.parent_path(), ec);
    return f;
}

void writeFileAtomically(const std::string& path, const std::string& text) {
    const fs::path p(path);
    const fs::path tmp = p.parent_path() / ("." + p.filename().string() + ".tmp");
    {
        std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
        out << text;
        out.flush();
        if (!out) throw core::Error(core::ErrorKind::Output, {}, "cannot write '" + tmp.string() + "' (disk full or no permission?)");
    }
    std::error_code ec;
    fs::rename(tmp, p, ec);
    if (ec) throw core::Error(core::ErrorKind::Output, {}, "cannot rename '" + tmp.string() + "' to '" + path + "': " + ec.message());
}

void removeStaleTemporaries(const std::string& pvdPath, const std::string& stem) {
    const fs::path pvd(pvdPath);
    std::error_code ec;
    const std::string prefix = "." + stem + "_";
    for (auto& e : fs::directory_iterator(pvd.parent_path().empty() ? fs::path(".") : pvd.parent_path(), ec)) {
        const std::string n = e.path().filename().string();
        if ((n.rfind(prefix, 0) == 0 || n == "." + pvd.filename().string() + ".tmp") && e.path().extension() == ".tmp")
            fs::remove(e.path(), ec);
    }
}

void PvdSeries::reset(std::string pvdPath) {
    m_path = std::move(pvdPath);
    m_written.clear();
    m_files = m_listed = 0;
    m_lastWrite = 0;
}

void PvdSeries::restore(std::vector<PvdStep> steps) {
    m_written = std::move(steps);
    m_files = 0;
    for (const PvdStep& s : m_written) m_files += s.parts.size();
    m_listed = m_written.size();
    m_lastWrite = 0;
}

void PvdSeries::add(double t, std::vector<std::string> parts) {
    for (const std::string& f : parts)
        if (f.empty() || f.find_first_of("/\n") != std::string::npos)
            throw core::Error(core::ErrorKind::Internal, {}, "'" + f + "' is not a file name beside '" + m_path + "'");
    m_files += parts.size();
    m_written.push_back({t, std::move(parts)});
    const double now = core::timerNow();  // steady_clock, or the clock a test injects (setTimerClock)
    if (m_files <= 100 || now - m_lastWrite >= 1.0) {
        write();
        m_lastWrite = now;
    }
}

void PvdSeries::finish() {
    if (!m_path.empty() && m_written.size() != m_listed) write();
}

void PvdSeries::write() {
    std::ostringstream s;
    s.precision(17);
    s << "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n  <Collection>\n";
    for (const PvdStep& step : m_written)
        for (size_t k = 0; k < step.parts.size(); ++k)
            s << "    <DataSet timestep=\"" << step.t << "\" group=\"\" part=\"" << k << "\" file=\"" << step.parts[k] << "\"/>\n";
    s << "  </Collection>\n</VTKFile>\n";
    writeFileAtomically(m_path, s.str());
    m_listed = m_written.size();
}

void PvdSeries::saveState(core::StateWriter& out, const std::string& prefix) const {
    std::vector<double> times;
    std::string lines;
    for (const PvdStep& step : m_written) {
        times.push_back(step.t);
        for (size_t k = 0; k < step.parts.size(); ++k) lines += (k ? "/" : "") + step.parts[k];
        lines += "\n";
    }
    out.put(prefix + "times", times);
    out.put(prefix + "files", lines);
}

namespace {
/// A line of the checkpoint's files record: the parts of a timestep, separated by '/'.
std::vector<std::string> splitParts(const std::string& line) {
    std::vector<std::string> parts;
    std::istringstream s(line);
    for (std::string f; std::getline(s, f, '/');) parts.push_back(f);
    return parts;
}
} // namespace

void PvdSeries::restoreState(core::StateReader& in, const std::string& prefix, const core::Component& owner) {
    const std::vector<double> times = in.getDoubles(prefix + "times");
    const std::string names = in.getText(prefix + "files");
    std::vector<PvdStep> steps;
    std::istringstream lines(names);
    for (std::string line; std::getline(lines, line);) steps.push_back({0.0, splitParts(line)});
    if (steps.size() != times.size())
        in.fail("[" + owner.path() + "] the checkpoint lists " + std::to_string(steps.size()) + " timesteps of files and " +
                std::to_string(times.size()) + " times for '" + fs::path(m_path).filename().string() + "'");
    for (size_t k = 0; k < times.size(); ++k) steps[k].t = times[k];
    restore(steps);  // the .pvd is rewritten with the next file
    const fs::path dir = fs::path(m_path).parent_path();
    std::error_code ec;
    for (const PvdStep& step : m_written)
        for (const std::string& f : step.parts)
            if (!fs::exists(dir / f, ec)) {
                owner.warn("the series of the checkpoint has '" + f + "', which is not in the output folder '" + dir.string() +
                           "': the .pvd will list it (restart into the output folder of the run that wrote the checkpoint)");
                return;
            }
}

} // namespace fascia::meshio
