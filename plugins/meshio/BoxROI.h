#pragma once
#include "fascia/sim/Mechanics.h"

namespace fascia::meshio {

/// The nodes (and elements) inside an axis-aligned box, as index lists for constraints, loads and
/// monitors: `<FixedConstraint indices="@box.indices"/>`. Uses the rest positions of the mesh source
/// in its context, or `position` when given.
class BoxROI : public core::Component {
public:
    void init() override;

    core::Param<NumberList> m_box{this, core::ParamSpec("box").count(6).unit("m").required().help("xmin ymin zmin xmax ymax zmax (bounds included)")};
    core::Param<Positions> m_position{this, core::ParamSpec("position").unit("m").help("points to select from (default: the mesh source in the context)")};
    core::Param<IndexList> m_indices{this, core::ParamSpec("indices").output().help("indices of the nodes inside the box")};
    core::Param<IndexList> m_tetrahedronIndices{this, core::ParamSpec("tetrahedronIndices").output().help("tetrahedra with all four nodes inside")};
    core::Param<IndexList> m_hexahedronIndices{this, core::ParamSpec("hexahedronIndices").output().help("hexahedra with all eight nodes inside")};
};

} // namespace fascia::meshio
