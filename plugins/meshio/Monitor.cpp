#include "Monitor.h"
#include "fascia/base/StateIO.h"
#include "fascia/scene/Node.h"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>

namespace fs = std::filesystem;

namespace fascia::meshio {

namespace {
const char* axis[3] = {"x", "y", "z"};
const char* tensorSuffix6[6] = {"xx", "yy", "zz", "xy", "yz", "xz"};
} // namespace

void Monitor::init() {
    m_st = m_state.get() ? m_state.get() : node()->findInContext<core::BaseMechanicalState>();
    if (!m_st && m_tool.get()) m_st = m_tool->body();
    if (!m_st) fail("no MechanicalObject in its context: put one in the same node or link it with state=\"@...\"");
    if (m_toolPosition.get() && !m_tool.get()) fail("toolPosition=\"true\" records a tool's position: give the tool too, e.g. tool=\"@probe\"");
    resolveNodes();
    resolveForceField();
    resolveCellFields();
    findEnergyTerms();
    const std::string header = headerRow();

    const std::string file = m_filename.isSet() ? m_filename.get() : name() + ".csv";
    m_path = (fs::path(node()->context().outputDir) / file).string();
    node()->context().claimOutput(m_path, *this);
    m_header = header;  // the file is created at the first observation: init writes nothing (claimOutput
    m_out.reset();      // has refused a file that could not be created)
}

void Monitor::resolveNodes() {
    if (m_group.isSet()) {
        auto* topo = node()->findInContext<core::BaseTopology>();
        if (!topo) fail(m_group, "group = \"" + m_group.get() + "\" but no mesh source is in the context");
        auto it = topo->meshData().nodeGroups.find(m_group.get());
        if (it == topo->meshData().nodeGroups.end()) fail(m_group, "no node group '" + m_group.get() + "' in '" + topo->name() + "'");
        m_nodes = it->second;
        m_nodes.insert(m_nodes.end(), m_indices.get().begin(), m_indices.get().end());
    } else {
        m_nodes = m_indices.get();
    }
    for (int i : m_nodes)
        if (size_t(i) >= m_st->size())
            fail(m_indices, "node index " + std::to_string(i) + " is out of range: the state '" + m_st->name() + "' has " +
                                std::to_string(m_st->size()) + " nodes");
}

void Monitor::resolveForceField() {
    if (auto* c = m_reactionOf.get(); c && c->node()->findInContext<core::BaseMechanicalState>() != m_st)
        fail(m_reactionOf, "the constraint '" + c->name() + "' acts on another state than '" + m_st->name() + "'");
    m_ff = m_forceField.get();
    if (m_ff && m_ff->node()->findInContext<core::BaseMechanicalState>() != m_st)
        fail(m_forceField, "the force field '" + m_ff->name() + "' acts on another state than '" + m_st->name() + "'");
    if (!m_ff && m_elements.isSet())
        for (const core::Node* n = node(); n && !m_ff; n = n->parent())
            for (auto* ff : n->findAllLocal<core::BaseForceField>())
                if (ff->elementCount() > 0) {
                    m_ff = ff;
                    break;
                }
    if (m_elements.isSet() && !m_ff) fail(m_elements, "elements are given but no element force field is in the context");
}

void Monitor::resolveCellFields() {
    m_cellFields.clear();
    if (!m_ff || !m_elements.isSet()) return;
    for (int e : m_elements.get())
        if (size_t(e) >= m_ff->elementCount())
            fail(m_elements, "element index " + std::to_string(e) + " is out of range: '" + m_ff->name() + "' has " +
                                 std::to_string(m_ff->elementCount()) + " elements");
    std::vector<core::CellField> fields;
    m_ff->cellData(*m_st, fields);
    std::vector<std::string> wanted;
    std::istringstream ws(m_elementFields.get());
    for (std::string w; ws >> w;) wanted.push_back(w);
    std::vector<std::string> offered;
    for (auto& f : fields) offered.push_back(f.name);
    for (auto& w : wanted)
        if (std::find(offered.begin(), offered.end(), w) == offered.end()) {
            std::string all;
            for (auto& o : offered) all += (all.empty() ? "" : ", ") + o;
            fail(m_elementFields, "'" + m_ff->name() + "' offers no element quantity '" + w + "'", {"it offers: " + all});
        }
    for (auto& f : fields)
        if (wanted.empty() || std::find(wanted.begin(), wanted.end(), f.name) != wanted.end())
            m_cellFields.emplace_back(f.name, f.components);
}

void Monitor::findEnergyTerms() {
    m_masses.clear();
    m_energyFields.clear();
    node()->root()->visit([&](const core::Node& n) {
        if (n.findInContext<core::BaseMechanicalState>() != m_st) return;
        for (auto* m : n.findAllLocal<core::BaseMass>()) m_masses.push_back(m);
        for (auto* ff : n.findAllLocal<core::BaseForceField>())
            if (ff->elementCount() > 0) m_energyFields.push_back(ff);
    });
    if (m_kineticEnergy.get() && m_masses.empty())
        fail(m_kineticEnergy, "kineticEnergy needs the masses, but no mass acts on the state '" + m_st->name() + "'");
    if (m_strainEnergy.get() && m_energyFields.empty())
        fail(m_strainEnergy, "strainEnergy needs an element force field, but none acts on the state '" + m_st->name() + "'");
}

std::string Monitor::headerRow() const {
    std::ostringstream h;
    h << "time [s]";
    for (int i : m_nodes) {
        auto vec = [&](const char* q, const char* unit) {
            for (int a = 0; a < 3; ++a) h << "," << q << i << "_" << axis[a] << " [" << unit << "]";
        };
        if (m_positions.get()) vec("x", "m");
        if (m_displacements.get()) vec("u", "m");
        if (m_velocities.get()) vec("v", "m/s");
    }
    if (m_reactionOf.get())
        for (int a = 0; a < 3; ++a) h << ",reaction_" << axis[a] << " [N]";
    if (auto* tool = m_tool.get()) {
        if (m_toolPosition.get())
            for (int a = 0; a < 3; ++a) h << "," << tool->name() << "_" << axis[a] << " [m]";
        for (int a = 0; a < 3; ++a) h << "," << tool->name() << "_force_" << axis[a] << " [N]";
        for (int a = 0; a < 3; ++a) h << "," << tool->name() << "_torque_" << axis[a] << " [N m]";
    }
    if (m_kineticEnergy.get()) h << ",kineticEnergy [J]";
    if (m_strainEnergy.get()) h << ",strainEnergy [J]";
    if (m_residual.get()) h << ",residual [N]";
    std::vector<core::CellField> fields;
    if (!m_cellFields.empty()) m_ff->cellData(*m_st, fields);
    for (int e : m_elements.get())
        for (auto& [name, comps] : m_cellFields) {
            std::string unit = "-";
            for (auto& f : fields)
                if (f.name == name && !f.unit.empty()) unit = f.unit;
            for (int c = 0; c < comps; ++c) {
                h << "," << name << "[" << e << "]";
                if (comps == 6) h << "_" << tensorSuffix6[c];
                else if (comps == 3) h << "_" << axis[c];
                else if (comps > 1) h << "_" << c;
                h << " [" << unit << "]";
            }
        }
    return h.str();
}

void Monitor::observeFinal(double t, long step) {
    if (step != m_lastStep) writeRow(t, step);
}

void Monitor::observe(double t, long step) {
    if (step % m_every.get() == 0) writeRow(t, step);
}

void Monitor::writeRow(double t, long step) {
    m_lastStep = step;
    if (!m_out && m_append) {
        // a restored run continues the file of the run that wrote the checkpoint, as it was then
        std::error_code ec;
        fs::resize_file(m_path, std::uintmax_t(m_bytes), ec);
        m_out = std::make_unique<std::ofstream>(m_path, std::ios::app);
        if (ec || !*m_out) fail(m_filename, "cannot write '" + m_path + "'" + (ec ? ": " + ec.message() : std::string()));
    } else if (!m_out) {
        std::error_code ec;
        fs::create_directories(fs::path(m_path).parent_path(), ec);
        m_out = std::make_unique<std::ofstream>(m_path, std::ios::trunc);
        if (!*m_out) failOutput(&m_filename, "cannot write '" + m_path + "'");
        *m_out << m_header << "\n";
        m_out->precision(12);
    }
    std::ostringstream row;
    row.precision(12);
    row << t;
    for (int i : m_nodes) {
        auto vec = [&](const Vec3& v) { row << "," << v[0] << "," << v[1] << "," << v[2]; };
        if (m_positions.get()) vec(m_st->x()[i]);
        if (m_displacements.get()) vec(m_st->x()[i] - m_st->x0()[i]);
        if (m_velocities.get()) vec(m_st->v()[i]);
    }
    if (auto* c = m_reactionOf.get()) {
        Vec3 sum = Vec3::Zero();
        const auto axes = c->constrainedAxes();
        for (int i : c->constrainedNodes())
            for (int a = 0; a < 3; ++a)
                if (axes[a]) sum[a] += m_st->reaction()[i][a];
        row << "," << sum[0] << "," << sum[1] << "," << sum[2];
    }
    if (auto* tool = m_tool.get()) {
        const Vec3 f = tool->force(), tq = tool->torque();
        if (m_toolPosition.get()) {
            const Vec3 p = tool->pose().position;
            row << "," << p[0] << "," << p[1] << "," << p[2];
        }
        row << "," << f[0] << "," << f[1] << "," << f[2] << "," << tq[0] << "," << tq[1] << "," << tq[2];
    }
    if (m_kineticEnergy.get()) {
        double e = 0;  // in node order
        for (auto* m : m_masses) {
            const auto& mm = m->nodalMasses();
            for (size_t i = 0; i < mm.size() && i < m_st->size(); ++i) e += 0.5 * mm[i] * m_st->v()[i].squaredNorm();
        }
        row << "," << e;
    }
    if (m_strainEnergy.get()) {
        double e = 0;
        for (auto* ff : m_energyFields) e += ff->potentialEnergy(*m_st);
        row << "," << e;
    }
    if (m_residual.get()) {
        double r = std::nan("");  // a state without an integrator is in no group: no forces to speak of
        if (auto* groups = node()->context().groups)
            for (auto& g : *groups)
                if (g.state == m_st) r = g.residualNorm(t);
        row << "," << r;
    }
    if (!m_cellFields.empty()) {
        std::vector<core::CellField> fields;
        m_ff->cellData(*m_st, fields);
        for (int e : m_elements.get())
            for (auto& [name, comps] : m_cellFields)
                for (auto& f : fields)
                    if (f.name == name)
                        for (int c = 0; c < comps; ++c) {
                            const size_t k = size_t(e) * comps + c;
                            row << "," << (k < f.values.size() ? f.values[k] : std::nan(""));
                        }
    }
    row << "\n";
    *m_out << row.str();  // whole rows only
    m_out->flush();
    m_bytes = long(m_out->tellp());
}

void Monitor::saveState(core::StateWriter& out) const {
    out.put("lastStep", m_lastStep);
    out.put("bytes", m_bytes);
}

void Monitor::restoreState(core::StateReader& in) {
    m_lastStep = in.getLong("lastStep");
    m_bytes = in.getLong("bytes");
    m_append = m_bytes >= 0;
    if (!m_append) return;
    std::error_code ec;
    const auto size = fs::file_size(m_path, ec);
    if (ec || size < std::uintmax_t(m_bytes))
        in.fail("[" + path() + "] its file '" + m_path + "' " +
                (ec ? std::string("is missing") : "has " + std::to_string(size) + " bytes") + ", the checkpoint needs " +
                std::to_string(m_bytes) + ": restart into the output folder of the run that wrote the checkpoint");
}

void Monitor::cleanup() {
    if (m_out) m_out->close();
}

} // namespace fascia::meshio
