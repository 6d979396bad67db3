// Checkpoint and restart, the divergence check's snapshot and the last good state (Simulation.h).
//
// The checkpoint file (format version 1), host byte order:
//   bytes 0-7    magic "FASCIACK"
//   8-11         uint32 format version
//   12-15        uint32 0x01020304 (the writer's byte order)
//   16-23        uint64 scene hash (Simulation::sceneHash)
//   24-31        uint64 payload length L
//   32..32+L     payload: the "scene" section (per node and component its path and hash, for the
//                message of a mismatch), the "Simulation" section, then one section per component in
//                scene order (StateWriter records: name, type, count, values)
//   32+L..+8     uint64 hashBytes of bytes [0, 32 + L): the checksum
#include "fascia/base/Error.h"
#include "fascia/base/Format.h"
#include "fascia/base/StateIO.h"
#include "fascia/sim/Simulation.h"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>

namespace fascia::core {

namespace {

constexpr char kMagic[8] = {'F', 'A', 'S', 'C', 'I', 'A', 'C', 'K'};
constexpr std::uint32_t kFormatVersion = 1, kByteOrder = 0x01020304;
constexpr size_t kHeaderBytes = 32, kChecksumBytes = 8;

std::string hex(std::uint64_t h) {
    char b[17];
    std::snprintf(b, sizeof b, "%016llx", static_cast<unsigned long long>(h));
    return b;
}

/// The canonical text of one node or component (Simulation::sceneHash).
std::string canonicalText(const Base& b, bool isRoot) {
    std::string s = b.path() + "\n" + b.className() + "\n";
    for (const BaseParam* p : b.params()) {
        if (p->spec().isOutput) continue;
        const std::string& n = p->name();
        if (isRoot && (n == "dt" || n == "dtSafety" || n == "endTime")) continue;
        s += n + "=" + (p->linkText().empty() ? p->valueText() : p->linkText()) + "\n";
        if (auto* f = dynamic_cast<const Param<FilePath>*>(p); f && p->linkText().empty() && !f->get().resolved.empty()) {
            std::ifstream in(f->get().resolved, std::ios::binary);
            std::ostringstream content;
            content << in.rdbuf();
            s += in ? "content=" + hex(hashBytes(content.str().data(), content.str().size())) + "\n" : "content=unreadable\n";
        }
    }
    return s;
}

template <class T>
T at(const std::string& bytes, size_t offset) {
    T v;
    std::memcpy(&v, bytes.data() + offset, sizeof(T));
    return v;
}

/// The first difference between the saved "path hash" lines and this scene's.
std::string sceneDifference(const std::string& saved, const std::string& current, const Node& root) {
    auto parse = [](const std::string& text) {
        std::vector<std::pair<std::string, std::string>> out;
        std::istringstream in(text);
        for (std::string line; std::getline(in, line);)
            if (auto tab = line.find('\t'); tab != std::string::npos) out.emplace_back(line.substr(0, tab), line.substr(tab + 1));
        return out;
    };
    const auto a = parse(saved), b = parse(current);
    auto describe = [&](const std::string& path) {
        const Base* o = path.find('/') != std::string::npos ? static_cast<const Base*>(root.resolveComponent(path)) : nullptr;
        if (!o && path == root.path()) o = &root;
        return o ? o->className() + " '" + path + "'" : "'" + path + "'";
    };
    for (size_t i = 0; i < std::max(a.size(), b.size()); ++i) {
        if (i >= a.size()) return "this scene has " + describe(b[i].first) + ", which the checkpoint does not";
        if (i >= b.size()) return "the checkpoint has '" + a[i].first + "', which this scene does not";
        if (a[i].first != b[i].first)
            return "the checkpoint has '" + a[i].first + "' where this scene has " + describe(b[i].first);
        if (a[i].second != b[i].second)
            return describe(b[i].first) + " differs (a parameter, or the content of a file it reads)";
    }
    return "the scene hashes differ";
}

[[noreturn]] void failFile(const std::string& file, const std::string& message, std::vector<std::string> notes = {}) {
    throwInputError({file, 0}, message, std::move(notes));
}

} // namespace

std::uint64_t Simulation::sceneHash() const {
    if (m_haveSceneHash) return m_sceneHash;
    std::string lines;
    const Node* root = m_root.get();
    m_root->visit([&](const Node& n) {
        const std::string own = canonicalText(n, &n == root);
        lines += n.path() + "\t" + hex(hashBytes(own.data(), own.size())) + "\n";
        for (auto& c : n.components()) {
            const std::string text = canonicalText(*c, false);
            lines += c->path() + "\t" + hex(hashBytes(text.data(), text.size())) + "\n";
        }
    });
    m_sceneLines = lines;
    m_sceneHash = hashBytes(lines.data(), lines.size());
    m_haveSceneHash = true;
    return m_sceneHash;
}

void Simulation::writeState(StateWriter& w, bool observers) const {
    fetchState();
    w.beginSection("/", "Simulation");
    w.put("time", m_time);
    w.put("step", m_step);
    w.put("dt", m_dt);
    w.put("timeAtDtChange", m_timeAtDtChange);
    w.put("stepAtDtChange", m_stepAtDtChange);
    w.put("groups", long(m_groups.size()));
    for (const auto& g : m_groups) {
        w.put("kinetic", g.kinetic);
        w.put("kineticMax", g.kineticMax);
        w.put("kineticGrowth", g.kineticGrowth);
    }
    w.endSection();
    for (const Component* c : m_all) {
        if (!observers && dynamic_cast<const BaseObserver*>(c)) continue;
        w.beginSection(c->path(), c->className());
        c->saveState(w);
        w.endSection();
    }
}

void Simulation::readState(StateReader& r, bool observers) {
    const double dtBefore = m_dt;
    r.beginSection("/", "Simulation");
    m_time = r.getDouble("time");
    m_step = r.getLong("step");
    m_dt = r.getDouble("dt");
    m_timeAtDtChange = r.getDouble("timeAtDtChange");
    m_stepAtDtChange = r.getLong("stepAtDtChange");
    const long groups = r.getLong("groups");
    if (groups != long(m_groups.size()))
        r.fail("[/] the checkpoint has " + std::to_string(groups) + " mechanical groups, this scene " +
               std::to_string(m_groups.size()));
    for (auto& g : m_groups) {
        g.kinetic = r.getDouble("kinetic");
        g.kineticMax = r.getDouble("kineticMax");
        g.kineticGrowth = int(r.getLong("kineticGrowth"));
    }
    r.endSection();
    if (!(m_dt > 0) || !std::isfinite(m_time) || m_step < 0)
        r.fail("[/] the saved time step " + formatNumber(m_dt, 4) + " s, time " + formatNumber(m_time, 4) + " s or step " +
               std::to_string(m_step) + " is not valid");
    // every component hears the saved dt before it reads its records (coefficients such as Prony's)
    m_root->context().dt = m_dt;
    if (m_dt != dtBefore)
        for (Component* c : m_all) c->dtChanged(m_dt);
    for (Component* c : m_all) {
        if (!observers && dynamic_cast<BaseObserver*>(c)) continue;
        r.beginSection(c->path(), c->className());
        c->restoreState(r);
        r.endSection();
    }
    if (!r.atEnd()) r.fail("the checkpoint has more sections than this scene has components");
    for (auto& g : m_groups) {
        g.firstBadStep = -1;
        if (g.backend) g.backend->push(g);
    }
}

void Simulation::save(const std::string& path) const {
    if (!m_initialised) throwInputError({}, "save('" + path + "') before init()");
    StateWriter w;
    w.beginSection("scene", "Scene");
    sceneHash();
    w.put("lines", m_sceneLines);
    w.endSection();
    writeState(w, true);
    std::string out(kMagic, sizeof kMagic);
    auto put = [&](auto v) { out.append(reinterpret_cast<const char*>(&v), sizeof v); };
    put(kFormatVersion);
    put(kByteOrder);
    put(sceneHash());
    put(std::uint64_t(w.bytes().size()));
    out += w.bytes();
    put(hashBytes(out.data(), out.size()));
    // atomically: a temporary file in the same folder, fsync'ed, renamed over the target
    const std::string tmp = path + ".tmp";
    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (fd < 0) throwOutputError({}, "cannot write the checkpoint '" + tmp + "': " + std::strerror(errno));
    size_t done = 0;
    while (done < out.size()) {
        const ssize_t n = ::write(fd, out.data() + done, out.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            const int err = errno;
            ::close(fd);
            ::unlink(tmp.c_str());
            throwOutputError({}, "cannot write the checkpoint '" + tmp + "': " + std::strerror(err));
        }
        done += size_t(n);
    }
    if (::fsync(fd) != 0 || ::close(fd) != 0) {
        const int err = errno;
        ::unlink(tmp.c_str());
        throwOutputError({}, "cannot write the checkpoint '" + tmp + "': " + std::strerror(err));
    }
    if (::rename(tmp.c_str(), path.c_str()) != 0) {
        const int err = errno;
        ::unlink(tmp.c_str());
        throwOutputError({}, "cannot rename '" + tmp + "' to '" + path + "': " + std::strerror(err));
    }
}

void Simulation::restore(const std::string& path) {
    if (!m_initialised) init();
    if (m_started || m_step > 0)
        throwInputError({path, 0}, "restore() on a simulation that has already started: restore right after loading the scene");
    // the file: a regular file, read whole
    struct stat st;
    if (::stat(path.c_str(), &st) != 0) failFile(path, std::string("cannot read the checkpoint: ") + std::strerror(errno));
    if (!S_ISREG(st.st_mode)) failFile(path, "not a regular file: give the checkpoint file fascia-run wrote (--checkpoint)");
    std::string bytes;
    {
        std::ifstream in(path, std::ios::binary);
        std::ostringstream ss;
        ss << in.rdbuf();
        if (!in) failFile(path, std::string("cannot read the checkpoint: ") + std::strerror(errno));
        bytes = ss.str();
    }
    const size_t size = bytes.size();
    if (size < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0) {
        if (size < sizeof kMagic && std::memcmp(bytes.data(), kMagic, size) == 0)
            failFile(path, "truncated checkpoint: " + std::to_string(size) + " bytes");
        failFile(path, "not a Fascia checkpoint (it does not start with \"FASCIACK\")");
    }
    if (size < kHeaderBytes) failFile(path, "truncated checkpoint: " + std::to_string(size) + " bytes, less than its header");
    const auto version = at<std::uint32_t>(bytes, 8);
    if (version != kFormatVersion)
        failFile(path, "checkpoint format version " + std::to_string(version) + "; this build reads version " +
                           std::to_string(kFormatVersion));
    if (at<std::uint32_t>(bytes, 12) != kByteOrder)
        failFile(path, "the checkpoint was written on a machine of another byte order");
    const auto payload = at<std::uint64_t>(bytes, 24);
    if (payload > size || size - kHeaderBytes - kChecksumBytes < payload || size < kHeaderBytes + kChecksumBytes)
        failFile(path, "truncated checkpoint: " + std::to_string(size) + " bytes, its header announces " +
                           (payload > (std::uint64_t(1) << 60) ? std::string("more than 2^60")
                                                              : std::to_string(kHeaderBytes + payload + kChecksumBytes)));
    const size_t end = kHeaderBytes + size_t(payload);
    if (size != end + kChecksumBytes)
        failFile(path, "the checkpoint has " + std::to_string(size - end - kChecksumBytes) + " bytes after its end");
    if (hashBytes(bytes.data(), end) != at<std::uint64_t>(bytes, end))
        failFile(path, "checksum mismatch: the checkpoint is corrupt (changed or damaged since it was written)");
    StateReader r(bytes, kHeaderBytes, end, path);
    r.beginSection("scene", "Scene");
    const std::string lines = r.getText("lines");
    r.endSection();
    if (at<std::uint64_t>(bytes, 16) != sceneHash())
        failFile(path, "the checkpoint was written by another scene: " + sceneDifference(lines, m_sceneLines, *m_root),
                 {"restart with the scene (and the mesh files) that wrote it"});
    // the state: the saved dt first (the components' coefficients), then every component's records
    const double sceneDt = m_dt;
    m_failed = true;  // until it is complete: a failed restore records nothing at finish()
    readState(r, true);
    SceneContext& ctx = m_root->context();
    m_failed = false;
    m_started = true;  // the observers recorded the initial state in the run that wrote the checkpoint
    m_snapshotStep = -1;
    ctx.time = m_time;
    ctx.step = m_step;
    if (sceneDt > 0 && sceneDt != m_dt) applyDt(sceneDt, true);  // a restart with another dt continues with it
}

void Simulation::setSnapshotEvery(long steps) {
    m_snapshotEvery = steps < 0 ? 0 : steps;
    m_snapshotStep = -1;
    m_snapshots.clear();
}

void Simulation::takeSnapshot() {
    StateWriter w;
    const bool reuse = m_snapshots.size() >= kSnapshotsKept;
    if (reuse) {
        w.bytes().swap(m_snapshots.front().second);  // reuses the oldest one's memory
        m_snapshots.pop_front();
    }
    w.clear();
    if (!reuse) {
        // no buffer to reuse yet: allocate it at its size at once (a growing buffer is copied at
        // each growth, the old and the new one held together: a transient of a large state's size)
        StateWriter count(StateWriter::CountOnly{});
        writeState(count, false);
        w.bytes().reserve(count.size());
    }
    writeState(w, false);
    m_snapshots.emplace_back(m_step, std::string());
    m_snapshots.back().second.swap(w.bytes());
    m_snapshotStep = m_step;
}

long Simulation::saveLastGoodState(const std::string& path) {
    if (m_failedStep < 0 || m_snapshots.empty()) return -1;
    // the newest snapshot at or before the last good step (or the oldest kept)
    const long wanted = m_lastGoodStep;
    size_t k = 0;
    for (size_t i = 0; i < m_snapshots.size(); ++i)
        if (m_snapshots[i].first <= wanted) k = i;
    const long from = m_snapshots[k].first;
    const long target = std::max(wanted, from);
    StateReader r(m_snapshots[k].second, 0, m_snapshots[k].second.size(), "<snapshot>");
    readState(r, false);
    // the steps from the snapshot to the start of the failing step again, observers muted
    m_replaying = true;
    m_failed = false;
    try {
        while (m_step < target) advance(std::numeric_limits<double>::quiet_NaN());
    } catch (const Error& e) {
        m_replaying = false;
        m_failed = true;
        throw Error(ErrorKind::Internal, {},
                    "the replay from the snapshot of step " + std::to_string(from) + " failed at step " +
                        std::to_string(m_step + 1) + ", before the step that failed (" + std::to_string(m_failedStep) +
                        "): a component does not save all its state (saveState): " + e.message());
    }
    m_replaying = false;
    m_failed = true;  // the run failed: finish() records no final state
    save(path);
    return target;
}

void Simulation::checkGroup(MechanicalGroup& g) {
    try {
        g.checkStep(m_time + m_dt);
    } catch (const Error& e) {
        if (e.kind() != ErrorKind::Simulation) throw;
        throw Error(ErrorKind::Simulation, {}, e.message() + divergenceDiagnosis(g));
    }
}

std::string Simulation::divergenceDiagnosis(const MechanicalGroup& g) const {
    std::ostringstream os;
    os.precision(6);
    os << "; at t = " << (m_time + m_dt) << " s (the end of step " << g.stepIndex << ")";
    // the worst element over the group's force fields
    ElementReport worst;
    const BaseForceField* where = nullptr;
    for (const BaseForceField* ff : g.forceFields) {
        ElementReport r;
        if (ff->worstElement(*g.state, r) && (!where || worseElement(r, worst))) worst = r, where = ff;
    }
    if (where)
        os << "; worst element: " << worst.index << " of " << where->className() << " '" << where->path() << "' (J = "
           << worst.J << ", rest centroid " << worst.centroid[0] << " " << worst.centroid[1] << " " << worst.centroid[2]
           << " m)";
    // a stable dt, as dt="auto" computes it
    const double crit = limitingForceField().first, lim = integratorLimit().step, safety = m_root->dtSafety.get();
    const double stable = std::min(crit, lim) * safety;
    if (std::isfinite(stable) && stable > 0)
        os << "; a stable dt: " << stable << " s (the stable step " << std::min(crit, lim) << " s x dtSafety " << safety
           << "; this run's dt is " << m_dt << " s)";
    return os.str();
}

} // namespace fascia::core
