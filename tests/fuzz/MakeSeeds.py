#!/usr/bin/env python3
"""Writes the generated seeds of tests/fuzz/corpus/ (the copied ones are listed in
tests/fuzz/corpus/README.md): the unit cube as 5 tetrahedra (the cube of
plugins/meshio/tests/data/cube.vtk) in the encodings no test file has: Gmsh 2.2 and 4.1 binary,
legacy VTK BINARY and version 5.1, .vtu ASCII, inline base64 (UInt32 and UInt64 headers),
zlib-compressed and appended raw, and its boundary as STL (ASCII, binary) and OBJ surfaces. Run from the repository root: python3 tests/fuzz/MakeSeeds.py"""
import base64
import os
import struct
import zlib

CORPUS = os.path.join(os.path.dirname(os.path.abspath(__file__)), "corpus")
POINTS = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
TETS = [(0, 1, 3, 4), (2, 3, 1, 6), (5, 4, 6, 1), (7, 6, 4, 3), (1, 3, 4, 6)]
TRIS = [(0, 3, 1), (1, 3, 2)]
# the cube's boundary as 6 quadrilaterals, counter-clockwise seen from outside
QUADS = [(0, 3, 2, 1), (4, 5, 6, 7), (0, 1, 5, 4), (2, 3, 7, 6), (0, 4, 7, 3), (1, 2, 6, 5)]


def write(folder, name, data):
    os.makedirs(os.path.join(CORPUS, folder), exist_ok=True)
    with open(os.path.join(CORPUS, folder, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def gmsh22_binary():
    out = b"$MeshFormat\n2.2 1 8\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n"
    out += b"$Nodes\n%d\n" % len(POINTS)
    for i, p in enumerate(POINTS):
        out += struct.pack("<i3d", i + 1, *p)
    out += b"\n$EndNodes\n$Elements\n%d\n" % (len(TETS) + len(TRIS))
    out += struct.pack("<3i", 2, len(TRIS), 2)  # triangles, 2 tags
    for i, t in enumerate(TRIS):
        out += struct.pack("<6i", i + 1, 2, 5, *[n + 1 for n in t])
    out += struct.pack("<3i", 4, len(TETS), 2)  # tetrahedra, 2 tags
    for i, t in enumerate(TETS):
        out += struct.pack("<7i", len(TRIS) + i + 1, 1, 1, *[n + 1 for n in t])
    return out + b"\n$EndElements\n"


def gmsh41_binary():
    out = b"$MeshFormat\n4.1 1 8\n" + struct.pack("<i", 1) + b"\n$EndMeshFormat\n"
    out += b"$Entities\n" + struct.pack("<4Q", 0, 0, 0, 1)
    out += struct.pack("<i6dQiQ", 1, 0, 0, 0, 1, 1, 1, 1, 1, 0) + b"\n$EndEntities\n"
    n = len(POINTS)
    out += b"$Nodes\n" + struct.pack("<4Q", 1, n, 1, n) + struct.pack("<iiiQ", 3, 1, 0, n)
    out += b"".join(struct.pack("<Q", i + 1) for i in range(n))
    out += b"".join(struct.pack("<3d", *p) for p in POINTS) + b"\n$EndNodes\n"
    m = len(TETS)
    out += b"$Elements\n" + struct.pack("<4Q", 1, m, 1, m) + struct.pack("<iiiQ", 3, 1, 4, m)
    out += b"".join(struct.pack("<5Q", i + 1, *[v + 1 for v in t]) for i, t in enumerate(TETS))
    return out + b"\n$EndElements\n"


def vtk_legacy_binary():
    out = b"# vtk DataFile Version 3.0\nunit cube, 5 tetrahedra\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
    out += b"POINTS 8 float\n" + b"".join(struct.pack(">3f", *p) for p in POINTS) + b"\n"
    out += b"CELLS %d %d\n" % (len(TETS), 5 * len(TETS))
    out += b"".join(struct.pack(">5i", 4, *t) for t in TETS) + b"\n"
    out += b"CELL_TYPES %d\n" % len(TETS) + b"".join(struct.pack(">i", 10) for _ in TETS) + b"\n"
    out += b"CELL_DATA %d\nSCALARS CellEntityIds int 1\nLOOKUP_TABLE default\n" % len(TETS)
    return out + b"".join(struct.pack(">i", 1) for _ in TETS) + b"\n"


def vtk_points_count_lies():
    """BINARY, POINTS announces 100 points and the file holds 8: the bound of every count by the bytes
    left in the file (a located error; without the bound the reader runs past the end of the file)."""
    out = b"# vtk DataFile Version 3.0\nPOINTS announces 100 points, the file holds 8\nBINARY\n"
    out += b"DATASET UNSTRUCTURED_GRID\nPOINTS 100 float\n"
    return out + b"".join(struct.pack(">3f", *p) for p in POINTS) + b"\n"


def vtk51(binary):
    head = b"# vtk DataFile Version 5.1\nunit cube, 5 tetrahedra\n" + (b"BINARY" if binary else b"ASCII")
    out = head + b"\nDATASET UNSTRUCTURED_GRID\nPOINTS 8 double\n"
    conn = [n for t in TETS for n in t]
    offs = [4 * i for i in range(len(TETS) + 1)]
    if binary:
        out += b"".join(struct.pack(">3d", *p) for p in POINTS) + b"\n"
        out += b"CELLS %d %d\nOFFSETS vtktypeint64\n" % (len(offs), len(conn))
        out += b"".join(struct.pack(">q", o) for o in offs) + b"\nCONNECTIVITY vtktypeint64\n"
        out += b"".join(struct.pack(">q", c) for c in conn) + b"\n"
        out += b"CELL_TYPES %d\n" % len(TETS) + b"".join(struct.pack(">i", 10) for _ in TETS) + b"\n"
    else:
        out += b"\n".join(b"%d %d %d" % p for p in POINTS) + b"\n"
        out += b"CELLS %d %d\nOFFSETS vtktypeint64\n" % (len(offs), len(conn))
        out += b" ".join(b"%d" % o for o in offs) + b"\nCONNECTIVITY vtktypeint64\n"
        out += b" ".join(b"%d" % c for c in conn) + b"\n"
        out += b"CELL_TYPES %d\n" % len(TETS) + b"\n".join(b"10" for _ in TETS) + b"\n"
    return out


# (name, VTK type, struct code, values) of the .vtu arrays, in file order
def vtu_arrays():
    return [("Points", "Float64", "d", [c for p in POINTS for c in p], 3),
            ("connectivity", "Int64", "q", [n for t in TETS for n in t], 1),
            ("offsets", "Int64", "q", [4 * (i + 1) for i in range(len(TETS))], 1),
            ("types", "UInt8", "B", [10] * len(TETS), 1),
            ("CellEntityIds", "Int32", "i", [1] * len(TETS), 1)]


def vtu(mode, header="UInt64"):
    hcode = "Q" if header == "UInt64" else "I"
    comp = ' compressor="vtkZLibDataCompressor"' if mode == "zlib" else ""
    appended = b""
    arrays = {}
    for name, vtype, code, values, ncomp in vtu_arrays():
        raw = struct.pack("<%d%s" % (len(values), code), *values)
        attrs = 'type="%s" Name="%s" NumberOfComponents="%d"' % (vtype, name, ncomp)
        if mode == "ascii":
            body = " ".join(str(v) for v in values)
            arrays[name] = '<DataArray %s format="ascii">%s</DataArray>' % (attrs, body)
        elif mode == "base64":
            body = base64.b64encode(struct.pack("<" + hcode, len(raw)) + raw).decode()
            arrays[name] = '<DataArray %s format="binary">%s</DataArray>' % (attrs, body)
        elif mode == "zlib":
            z = zlib.compress(raw)
            hdr = struct.pack("<" + hcode * 4, 1, len(raw), len(raw), len(z))
            body = base64.b64encode(hdr).decode() + base64.b64encode(z).decode()
            arrays[name] = '<DataArray %s format="binary">%s</DataArray>' % (attrs, body)
        else:  # appended raw
            arrays[name] = '<DataArray %s format="appended" offset="%d"/>' % (attrs, len(appended))
            appended += struct.pack("<" + hcode, len(raw)) + raw
    xml = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="1.0" byte_order="LittleEndian"'
           ' header_type="%s"%s>\n<UnstructuredGrid>\n<Piece NumberOfPoints="%d" NumberOfCells="%d">\n'
           "<Points>%s</Points>\n<Cells>%s%s%s</Cells>\n<CellData>%s</CellData>\n</Piece>\n</UnstructuredGrid>\n"
           % (header, comp, len(POINTS), len(TETS), arrays["Points"], arrays["connectivity"],
              arrays["offsets"], arrays["types"], arrays["CellEntityIds"]))
    out = xml.encode()
    if mode == "appended":
        out += b'<AppendedData encoding="raw">\n_' + appended + b"\n</AppendedData>\n"
    return out + b"</VTKFile>\n"


def cube_triangles():
    return [(q[0], q[1], q[2]) for q in QUADS] + [(q[0], q[2], q[3]) for q in QUADS]


def sized(data, parity):
    """data padded with a trailing newline to the size parity the surface target reads as .stl (0)
    or .obj (1) (tests/fuzz/FuzzSurface.cpp)."""
    return data + b"\n" if len(data) % 2 != parity else data


def stl_ascii():
    out = b"solid cube\n"
    for t in cube_triangles():
        out += b"  facet normal 0 0 0\n    outer loop\n"
        out += b"".join(b"      vertex %d %d %d\n" % POINTS[n] for n in t)
        out += b"    endloop\n  endfacet\n"
    return sized(out + b"endsolid cube\n", 0)


def stl_binary(header=b"binary STL: the unit cube, 12 triangles"):
    tris = cube_triangles()
    out = header.ljust(80, b" ") + struct.pack("<I", len(tris))
    for t in tris:
        out += struct.pack("<3f", 0, 0, 0) + b"".join(struct.pack("<3f", *POINTS[n]) for n in t) + b"\0\0"
    return out


def obj(quads):
    out = b"# the unit cube\nmtllib cube.mtl\no cube\n" + b"".join(b"v %d %d %d\n" % p for p in POINTS)
    out += b"vn 0 0 1\nvt 0 0\ng faces\nusemtl skin\ns off\n"
    if quads:  # every corner form: i, i/t, i//n, i/t/n, and negative (relative) indices
        forms = [b"%d", b"%d/1", b"%d//1", b"%d/1/1"]
        for k, q in enumerate(QUADS):
            corners = [forms[(k + c) % 4] % (n + 1) if k % 2 == 0 else b"%d" % (n - len(POINTS)) for c, n in enumerate(q)]
            out += b"f " + b" ".join(corners) + b"\n"
    else:
        out += b"".join(b"f %d %d %d\n" % tuple(n + 1 for n in t) for t in cube_triangles())
    return sized(out + b"l 1 2\n", 1)


write("gmsh", "cube_gmsh22_binary.msh", gmsh22_binary())
write("gmsh", "cube_gmsh41_binary.msh", gmsh41_binary())
write("legacy_vtk", "cube_binary.vtk", vtk_legacy_binary())
write("legacy_vtk", "points_count_lies_binary.vtk", vtk_points_count_lies())
write("legacy_vtk", "cube_v51_ascii.vtk", vtk51(False))
write("legacy_vtk", "cube_v51_binary.vtk", vtk51(True))
write("vtu", "cube_ascii.vtu", vtu("ascii"))
write("vtu", "cube_base64_uint64.vtu", vtu("base64"))
write("vtu", "cube_base64_uint32.vtu", vtu("base64", "UInt32"))
write("vtu", "cube_zlib.vtu", vtu("zlib"))
write("vtu", "cube_appended_raw.vtu", vtu("appended"))
write("surface", "cube_ascii.stl", stl_ascii())
write("surface", "cube_binary.stl", stl_binary())
write("surface", "cube_binary_solid_header.stl", stl_binary(b"solid cube (a binary file whose header says solid)"))
write("surface", "cube_triangles.obj", obj(False))
write("surface", "cube_quads.obj", obj(True))
