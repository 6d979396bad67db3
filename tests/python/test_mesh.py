"""Meshes from numpy arrays and through meshio, and back."""
import numpy as np
import pytest

import fascia


def _cube_mesh():
    g = np.linspace(0, 0.02, 3)
    pts = np.array([[x, y, z] for z in g for y in g for x in g])
    idx = lambda i, j, k: i + 3 * (j + 3 * k)  # noqa: E731
    hexes = [[idx(i, j, k), idx(i + 1, j, k), idx(i + 1, j + 1, k), idx(i, j + 1, k),
              idx(i, j, k + 1), idx(i + 1, j, k + 1), idx(i + 1, j + 1, k + 1), idx(i, j + 1, k + 1)]
             for k in range(2) for j in range(2) for i in range(2)]
    base = [n for n in range(27) if pts[n, 2] == 0]
    return fascia.Mesh(pts, hexahedra=np.array(hexes), groups={"base": base})


def _scene(mesh):
    root = fascia.Node("root", dt=1e-4, gravity=[0, 0, -9.81])
    body = root.add_child("body")
    body.add(mesh, name="mesh")
    body.add("MechanicalObject", name="state")
    body.add("LumpedMass", density=1000)
    body.add("NeoHookean", youngModulus=5000, poissonRatio=0.3)
    body.add("TLEDForceField", name="tled")
    body.add("SemiImplicitEuler", damping=10)
    body.add("FixedConstraint", group="base")
    return root


def test_mesh_from_numpy_runs(tmp_path):
    sim = fascia.Simulation(_scene(_cube_mesh()))
    sim.run(steps=50)
    st = sim.state("state")
    assert np.all(st.x[:9, 2] == 0)           # the base group is held
    assert st.x[26, 2] < 0.02                 # the top sags under gravity
    tets, hexes = sim.elements("/root/body/tled")
    assert hexes.shape == (8, 8) and tets.shape == (0, 4)
    points, triangles = sim.surface("state")
    assert triangles.shape == (2 * 6 * 4, 3)


def test_meshio_round_trip(tmp_path):
    mesh = _cube_mesh()
    path = str(tmp_path / "cube.vtu")
    fascia.write_mesh(path, mesh.points, hexahedra=mesh.hexahedra)
    back = fascia.read_mesh(path)
    assert np.array_equal(back.points, mesh.points) and np.array_equal(back.hexahedra, mesh.hexahedra)
    sim = fascia.Simulation(_scene(fascia.Mesh(back.points, hexahedra=back.hexahedra, groups=mesh.groups)))
    sim.run(steps=5)
    out = str(tmp_path / "deformed.vtu")
    fascia.write_mesh(out, np.asarray(sim.state("state").x), hexahedra=back.hexahedra,
                      cell_data={"J": [sim.cell_data("/root/body/tled")["J"]]})
    import meshio
    assert meshio.read(out).cell_data["J"][0].shape == (8,)


@pytest.mark.parametrize("kwargs, match", [
    (dict(points=np.zeros((4, 2))), r"shape \(n, 3\)"),
    (dict(points=np.zeros((4, 3)), tetrahedra=np.zeros((1, 4)) + 0.5), "integer node indices"),
    (dict(points=np.zeros((4, 3)), tetrahedra=[[0, 1, 2, 9]]), r"in \[0, 4\)"),
    (dict(points=np.full((4, 3), np.nan), tetrahedra=[[0, 1, 2, 3]]), "NaN"),
    (dict(points=np.zeros((4, 3)), tetrahedra=[[0, 1, 2, 3]], groups={"bad name": [0]}), "must be a word"),
])
def test_bad_mesh_arrays(kwargs, match):
    with pytest.raises(fascia.ParameterError, match=match):
        fascia.Mesh(**kwargs)


def test_a_degenerate_mesh_is_a_located_error():
    flat = fascia.Mesh(np.array([[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0.0]]), tetrahedra=[[0, 1, 2, 3]])
    with pytest.raises(fascia.SceneError) as e:
        fascia.Simulation(_scene(flat))
    assert e.value.file and e.value.line


def test_fix_orientation_flips_an_inverted_element():
    pts = np.array([[0, 0, 0], [0.01, 0, 0], [0, 0.01, 0], [0, 0, 0.01]])
    inverted = [[0, 2, 1, 3]]  # negative volume
    root = fascia.Node("root", dt=1e-5)
    body = root.add_child("body")
    body.add("InlineMesh", points=pts, tetrahedra=inverted, fixOrientation=True)
    body.add("MechanicalObject", name="state")
    body.add("LumpedMass", density=1000)
    body.add("NeoHookean", youngModulus=5000, poissonRatio=0.3)
    body.add("TLEDForceField", name="tled")
    body.add("CentralDifference")
    sim = fascia.Simulation(root)
    tets, _ = sim.elements("/root/body/tled")
    assert sorted(tets[0]) == [0, 1, 2, 3] and list(tets[0]) != inverted[0]
    with pytest.raises(fascia.SceneError, match="nverted|negative"):
        body.components[0].set(fixOrientation=False)
        fascia.Simulation(root)
