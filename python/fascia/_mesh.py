"""Meshes from numpy arrays and through meshio (Debian's python3-meshio), and back."""
import numpy as np

from ._errors import ParameterError


def _array(value, what, cols, integer):
    a = np.asarray(value)
    if a.size == 0:
        return np.zeros((0, cols), dtype=np.int64 if integer else np.float64)
    if a.ndim != 2 or a.shape[1] != cols:
        raise ParameterError(f"{what}: expected an array of shape (n, {cols}), got shape {a.shape}")
    if integer:
        if not np.issubdtype(a.dtype, np.integer):
            raise ParameterError(f"{what}: expected integer node indices, got dtype {a.dtype}")
        return a.astype(np.int64, copy=False)
    if not np.issubdtype(a.dtype, np.number):
        raise ParameterError(f"{what}: expected numbers, got dtype {a.dtype}")
    a = a.astype(np.float64, copy=False)
    if not np.all(np.isfinite(a)):
        raise ParameterError(f"{what}: holds NaN or infinity")
    return a


class Mesh:
    """A volume mesh: points (n, 3) in metres, tetrahedra (m, 4) and/or hexahedra (k, 8, VTK order)
    0-based node indices, and named node groups {name: indices}. ``node.add(mesh, name="mesh")``
    makes it the mesh source of that node (the InlineMesh component), checked as a mesh file is."""

    def __init__(self, points, tetrahedra=None, hexahedra=None, groups=None):
        self.points = _array(points, "Mesh points", 3, False)
        self.tetrahedra = _array([] if tetrahedra is None else tetrahedra, "Mesh tetrahedra", 4, True)
        self.hexahedra = _array([] if hexahedra is None else hexahedra, "Mesh hexahedra", 8, True)
        n = len(self.points)
        for what, cells in (("tetrahedra", self.tetrahedra), ("hexahedra", self.hexahedra)):
            if cells.size and (cells.min() < 0 or cells.max() >= n):
                raise ParameterError(f"Mesh {what}: node indices must be in [0, {n}), got "
                                     f"[{cells.min()}, {cells.max()}]")
        self.groups = {}
        for name, ids in (groups or {}).items():
            ids = np.unique(np.asarray(ids, dtype=np.int64).ravel())
            if not str(name).isidentifier():
                raise ParameterError(f"Mesh group name '{name}' must be a word (letters, digits, _)")
            if ids.size and (ids.min() < 0 or ids.max() >= n):
                raise ParameterError(f"Mesh group '{name}': node indices must be in [0, {n})")
            self.groups[str(name)] = ids

    def params(self):
        """The InlineMesh parameters of this mesh."""
        p = {"points": self.points}
        if len(self.tetrahedra):
            p["tetrahedra"] = self.tetrahedra
        if len(self.hexahedra):
            p["hexahedra"] = self.hexahedra
        if self.groups:
            p["nodeGroups"] = "; ".join(f"{k}: " + " ".join(map(str, v.tolist())) for k, v in self.groups.items())
        return p

    @classmethod
    def from_meshio(cls, m):
        """From a meshio.Mesh: its tetra and hexahedron cells, its point_sets as node groups."""
        tets = [c.data for c in m.cells if c.type == "tetra"]
        hexes = [c.data for c in m.cells if c.type == "hexahedron"]
        groups = dict(getattr(m, "point_sets", {}) or {})
        return cls(m.points[:, :3] if m.points.shape[1] >= 3 else m.points,
                   np.concatenate(tets) if tets else None, np.concatenate(hexes) if hexes else None, groups)

    def to_meshio(self, point_data=None, cell_data=None):
        import meshio
        cells = []
        if len(self.tetrahedra):
            cells.append(("tetra", self.tetrahedra))
        if len(self.hexahedra):
            cells.append(("hexahedron", self.hexahedra))
        return meshio.Mesh(self.points, cells, point_data=point_data or {}, cell_data=cell_data or {})

    def __repr__(self):
        return (f"Mesh({len(self.points)} points, {len(self.tetrahedra)} tetrahedra, {len(self.hexahedra)} hexahedra, "
                f"groups {sorted(self.groups)})")


def read_mesh(path):
    """A fascia.Mesh read by meshio (any format meshio reads: .vtu, .msh, .mesh, .xdmf ...)."""
    import meshio
    return Mesh.from_meshio(meshio.read(path))


def write_mesh(path, points, tetrahedra=None, hexahedra=None, point_data=None, cell_data=None):
    """Writes a mesh with meshio (the format from the extension): e.g. a state's current positions
    with the force field's elements (Simulation.elements) and its cell data."""
    Mesh(points, tetrahedra, hexahedra).to_meshio(point_data, cell_data).write(path)
