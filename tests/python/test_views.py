"""State as numpy views: no copies, writes seen by the next step, stale views raise."""
import numpy as np
import pytest

import fascia
from build_scene import cube


@pytest.fixture
def sim(tmp_path):
    s = fascia.Simulation(cube(3), output_dir=tmp_path)
    yield s
    s.close()


def test_views_share_memory(sim):
    st = sim.state("state")
    x = st.x
    assert isinstance(x, fascia.View) and x.dtype == np.float64 and x.shape == (64, 3)
    assert x.flags.c_contiguous and not x.flags.owndata
    assert st.x.ctypes.data == x.ctypes.data  # the same memory, every time
    sim.run(steps=5)
    assert st.x.ctypes.data == x.ctypes.data
    assert np.array_equal(x, np.asarray(st.x))  # the view moved with the state
    for name in ("v", "f", "x0", "reaction", "external_force"):
        a = getattr(st, name)
        assert a.shape == (64, 3) and not a.flags.owndata


def test_a_write_is_seen_by_the_next_step(sim):
    st = sim.state("state")
    free = 21  # an interior node (1, 1, 1) of the 4 x 4 x 4 grid
    sim.run(steps=2)
    before = st.x[free].copy()
    st.x[free, 0] += 1e-3  # through the view
    assert np.asarray(sim.state("state").x)[free, 0] == before[0] + 1e-3
    st.v[free] = 0.0
    sim.step()
    # the step started from the written position: its elastic force pulls the node back
    assert st.f[free, 0] < 0
    st.external_force[free] = [0, 0, 5.0]
    sim.step()
    assert st.f[free, 2] > 0


def test_read_only_views(sim):
    st = sim.state("state")
    for name in ("f", "x0", "reaction"):
        with pytest.raises(ValueError, match="read-only"):
            getattr(st, name)[0, 0] = 1.0


def test_views_after_close_raise(sim):
    x = sim.state("state").x
    sliced = x[3:5]
    sim.close()
    for use in (lambda: x[0], lambda: x + 1, lambda: np.sum(x), lambda: repr(x), lambda: sliced[0],
                lambda: sim.state("state").x, lambda: sim.step()):
        with pytest.raises((fascia.StaleViewError, fascia.SimulationError)):
            use()


def test_nan_written_through_a_view_is_refused(sim):
    st = sim.state("state")
    st.x[7, 1] = np.nan
    with pytest.raises(fascia.StateError, match=r"state 'state'.x\[7, 1\].*nan"):
        sim.step()
    assert sim.step_count == 0
    st.x[7, 1] = st.x0[7, 1]
    sim.step()
    assert sim.step_count == 1


def test_assignment_checks_shape_and_values(sim):
    st = sim.state("state")
    with pytest.raises(fascia.ParameterError, match=r"expected shape \(64, 3\)"):
        st.x = np.zeros((10, 3))
    with pytest.raises(fascia.ParameterError, match="expected numbers"):
        st.v = np.array([["a", "b", "c"]] * 64)
    with pytest.raises(fascia.StateError, match="finite"):
        st.external_force = np.full((64, 3), np.inf)
    st.external_force = [0, 0, 1.0]  # broadcast to every node
    assert np.all(st.external_force[:, 2] == 1.0)


def test_element_data_and_surface(sim):
    sim.run(steps=3)
    data = sim.cell_data("/root/body/heml")
    tets, hexes = sim.elements("/root/body/heml")
    assert tets.shape == (6 * 27, 4) and hexes.shape == (0, 8)
    assert data["J"].shape == (6 * 27,) and np.all(data["J"] > 0)
    points, triangles = sim.surface("state")
    assert points.ctypes.data == sim.state("state").x.ctypes.data
    assert triangles.shape == (2 * 6 * 9, 3) and triangles.max() < 64
