#pragma once
#include "fascia/sim/Mechanics.h"
#include "fascia/sim/Tool.h"

#include <fstream>
#include <memory>

namespace fascia::meshio {

/// A CSV of chosen nodes' positions, displacements and velocities, the summed reaction force on a
/// constraint's nodes (the axes it holds only), and element quantities the force field provides.
/// The first row names every column with its unit: `time [s],u12_x [m],...`. Reactions are those
/// of the step just computed: the forces at the start of the step (time t - dt), as explicit
/// integration has them.
/// Opt-in columns show when a run has settled, each for the whole state: the kinetic energy
/// 1/2 sum_i m_i |v_i|^2 (the masses of the state's context), the strain energy (the sum of the
/// potentialEnergy() of the element force fields acting on the state), and the residual, the norm
/// of the free nodal forces |f| at the recorded positions and time (every force, gravity and load,
/// with the constrained components removed: 0 at a static equilibrium; one more force evaluation
/// per row). A tool (`tool="@probe"`, fascia/sim/Tool.h) adds its force and torque, those of the
/// step just computed: `probe_force_x [N]` ... `probe_torque_z [N m]`; the monitor then records the
/// tool's body when no state is in its context. With toolPosition, the tool's position at the row's
/// time comes first: `probe_x [m]` ... (the force was computed one step earlier, at the pose before:
/// a lag of one step's travel, e.g. 2 um for a probe at 20 mm/s and dt = 0.1 ms). The final
/// state of a run is recorded whatever `every`.
class Monitor : public core::BaseObserver {
public:
    void init() override;
    void observe(double t, long step) override;
    bool records(long step) const override { return step % m_every.get() == 0; }
    void observeFinal(double t, long step) override;
    void cleanup() override;
    /// The step of its last row and the length of its file then: a restored run cuts the file back to
    /// that length (rows a longer run wrote after the checkpoint) and appends to it. The file must be
    /// there, at least that long (an input error at restore otherwise: restart into the output folder
    /// of the run that wrote the checkpoint).
    void saveState(core::StateWriter& out) const override;
    void restoreState(core::StateReader& in) override;

    core::Param<std::string> m_filename{this, core::ParamSpec("filename").help("CSV file, relative to the output folder (default: <name>.csv)")};
    core::Param<IndexList> m_indices{this, core::ParamSpec("indices").help("nodes to record (inline or linked, e.g. \"@box.indices\")")};
    core::Param<std::string> m_group{this, core::ParamSpec("group").help("a node group of the mesh source in the context to record (with indices, if given)")};
    core::Param<bool> m_positions{this, core::ParamSpec("positions").help("record positions"), false};
    core::Param<bool> m_displacements{this, core::ParamSpec("displacements").help("record displacements"), true};
    core::Param<bool> m_velocities{this, core::ParamSpec("velocities").help("record velocities"), false};
    core::Link<core::BaseConstraint> m_reactionOf{this, core::ParamSpec("reactionOf").help("a constraint whose nodes' reaction forces are summed, e.g. \"@fixed\"")};
    core::Param<IndexList> m_elements{this, core::ParamSpec("elements").help("elements to record the force field's element quantities of")};
    core::Param<std::string> m_elementFields{this, core::ParamSpec("elementFields").help("names of the element quantities, space separated (e.g. \"J vonMises\"); default: all the force field offers")};
    core::Link<core::BaseForceField> m_forceField{this, core::ParamSpec("forceField").help("the force field giving element quantities (default: the first element force field in the context)")};
    core::Param<bool> m_kineticEnergy{this, core::ParamSpec("kineticEnergy").help("record the state's kinetic energy 1/2 sum m v^2 (J)"), false};
    core::Param<bool> m_strainEnergy{this, core::ParamSpec("strainEnergy").help("record the strain energy of the element force fields acting on the state (J)"), false};
    core::Param<bool> m_residual{this, core::ParamSpec("residual").help("record the residual: the norm of the free (unconstrained) nodal forces at the recorded state (N), 0 at equilibrium"), false};
    core::Param<int> m_every{this, core::ParamSpec("every").min(1).help("record every N steps (the initial and the final state are always recorded)"), 1};
    core::Param<bool> m_toolPosition{this, core::ParamSpec("toolPosition").help("with tool: record the tool's position too (probe_x [m] ...), e.g. to plot its force against its depth"), false};
    core::Link<core::BaseTool> m_tool{this, core::ParamSpec("tool").help("a rigid tool whose force and torque (the body's push on it) are recorded, e.g. \"@probe\"")};
    core::Link<core::BaseMechanicalState> m_state{this, core::ParamSpec("state").help("the state to record (default: the one in the context)")};

private:
    /// The nodes to record (group, then indices), each checked against the state.
    void resolveNodes();
    /// The element force field (forceField, else the first in the context when elements are given),
    /// and the reactionOf constraint and the force field checked to act on the state.
    void resolveForceField();
    /// The element quantities to record (elementFields, else all the force field offers).
    void resolveCellFields();
    /// The masses and the element force fields acting on the state, for the energy columns.
    void findEnergyTerms();
    /// The CSV header line: every column with its unit.
    std::string headerRow() const;
    void writeRow(double t, long step);
    core::BaseMechanicalState* m_st = nullptr;
    IndexList m_nodes;
    core::BaseForceField* m_ff = nullptr;
    std::vector<std::pair<std::string, int>> m_cellFields;  ///< (name, components)
    std::unique_ptr<std::ofstream> m_out;
    std::string m_path;
    std::string m_header;  ///< the CSV header line, written when the file is created
    std::vector<core::BaseMass*> m_masses;             ///< for the kinetic energy
    std::vector<core::BaseForceField*> m_energyFields; ///< for the strain energy
    long m_lastStep = -1;  ///< the step of the last row
    long m_bytes = -1;     ///< bytes in the file after its last row (-1: no file yet)
    bool m_append = false; ///< a restored run: the first row cuts the file to m_bytes and appends
};

} // namespace fascia::meshio
