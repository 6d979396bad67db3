#!/usr/bin/env python3
"""Writes the broken meshes of the bad-input catalogue (tests/apps/badinput/catalogue.txt) into this
folder, each from a good cube mesh of plugins/meshio/tests/data (or, for .vtu and binary .vtk, from
the cube written here) with one defect. The files are committed; the test does not run this script.
Run it from anywhere: python3 tests/apps/badinput/meshes/make_meshes.py"""
import os
import struct
import zlib

HERE = os.path.dirname(os.path.abspath(__file__))
DATA = os.path.join(HERE, "..", "..", "..", "..", "plugins", "meshio", "tests", "data")


def read(name):
    with open(os.path.join(DATA, name), "rb") as f:
        return f.read().decode()


def write(name, data):
    with open(os.path.join(HERE, name), "wb") as f:
        f.write(data if isinstance(data, bytes) else data.encode())


def edit(text, edits=None, keep=None):
    """text with line n (1-based) replaced by edits[n] (None: the line removed), cut to `keep` lines."""
    lines = text.split("\n")
    if keep is not None:
        lines = lines[:keep]
    out = []
    for i, l in enumerate(lines, 1):
        if edits and i in edits:
            if edits[i] is not None:
                out.append(edits[i])
        else:
            out.append(l)
    return "\n".join(out) + ("" if keep is None else "\n")


# ---- Gmsh 2.2 (nodes on lines 12-19, elements on 23-30) ------------------------------------------
g22 = read("cube_gmsh22.msh")
write("g22_truncated.msh", edit(g22, keep=15))
write("g22_node_count_lies.msh", edit(g22, {11: "9"}))
write("g22_element_count_lies.msh", edit(g22, {22: "12"}))
write("g22_bad_node_index.msh", edit(g22, {27: "5 4 2 1 1 30 40 20 99"}))
write("g22_inverted.msh", edit(g22, {26: "4 4 2 1 1 10 40 20 50"}))
write("g22_degenerate.msh", edit(g22, {26: "4 4 2 1 1 10 20 40 40"}))
write("g22_nan_coordinate.msh", edit(g22, {14: "30 1 nan 0"}))
write("g22_malformed_number.msh", edit(g22, {14: "30 1 1,0 0"}))
write("g22_wrong_node_count.msh", edit(g22, {26: "4 4 2 1 1 10 20 40"}))
write("g22_element_type_malformed.msh", edit(g22, {26: "4 tet 2 1 1 10 20 40 50"}))
write("g22_surface_only.msh", edit(g22, {22: "3", 26: None, 27: None, 28: None, 29: None, 30: None}))
write("g22_binary.msh", edit(g22, {2: "2.2 1 8"}))
write("g22_duplicate_node_id.msh", edit(g22, {13: "10 1 0 0"}))
write("g22_no_elements.msh", edit(g22, keep=20))

# ---- Gmsh 4.1 and 1 -------------------------------------------------------------------------------
g41 = read("cube_gmsh41.msh")
write("g41_truncated.msh", edit(g41, keep=33))
write("g41_block_count_lies.msh", edit(g41, {44: "3 1 4 7"}))
write("g41_bad_node_index.msh", edit(g41, {47: "6 1 4 7 9"}))
write("g41_entity_counts_overflow.msh", edit(g41, {11: "9223372036854775807 9223372036854775807 1 1"}))
write("g41_binary.msh", edit(g41, {2: "4.1 1 8"}))
g1 = read("cube_gmsh1.msh")
write("g1_truncated.msh", edit(g1, keep=18))

# ---- legacy VTK, ASCII (points on lines 6-13, cells on 15-21, types on 23-29) --------------------
vtk = read("cube.vtk")
write("vtk_truncated.vtk", edit(vtk, keep=10))
write("vtk_cells_size_lies.vtk", edit(vtk, {14: "CELLS 7 3300"}))
write("vtk_cell_count_lies.vtk", edit(vtk, {15: "40 0 1 3 4"}))
write("vtk_bad_point_index.vtk", edit(vtk, {15: "4 0 1 3 40"}))
write("vtk_inverted.vtk", edit(vtk, {16: "4 2 1 3 6"}))
write("vtk_nan_coordinate.vtk", edit(vtk, {8: "1 nan 0"}))
write("vtk_tetra_three_points.vtk", edit(vtk, {14: "CELLS 7 32", 15: "3 0 1 3"}))
write("vtk_cell_type_out_of_range.vtk", edit(vtk, {23: "300"}))
write("vtk_types_short.vtk", edit(vtk, {22: "CELL_TYPES 6", 29: None}))
write("vtk_polydata.vtk", edit(vtk, {4: "DATASET POLYDATA"}))
write("vtk_not_vtk.vtk", "solid cube\nfacet normal 0 0 1\n")
write("vtk_empty.vtk", "")

# ---- legacy VTK 5.1 (OFFSETS and CONNECTIVITY) and BINARY, written here from the cube -------------
points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0), (0, 0, 1), (1, 0, 1), (1, 1, 1), (0, 1, 1)]
tets = [(0, 1, 3, 4), (2, 3, 1, 6), (5, 4, 6, 1), (7, 6, 4, 3), (1, 3, 4, 6)]


def vtk51_ascii(offsets):
    conn = [i for t in tets for i in t]
    return ("# vtk DataFile Version 5.1\ncube, VTK 5.1 cells\nASCII\nDATASET UNSTRUCTURED_GRID\n"
            "POINTS 8 double\n" + "".join("%g %g %g\n" % p for p in points) +
            "CELLS %d %d\nOFFSETS vtktypeint64\n%s\nCONNECTIVITY vtktypeint64\n%s\n" %
            (len(offsets), len(conn), " ".join(map(str, offsets)), " ".join(map(str, conn))) +
            "CELL_TYPES 5\n10 10 10 10 10\n")


write("vtk51_offsets_decrease.vtk", vtk51_ascii([0, 4, 8, 6, 16, 20]))


def vtk_binary(cell_sizes=None, cells_header=None, keep=None):
    """The cube as a legacy BINARY file (big-endian), optionally with lying per-cell point counts,
    a lying CELLS header, or cut after `keep` bytes. Returns the bytes."""
    out = b"# vtk DataFile Version 3.0\ncube, binary\nBINARY\nDATASET UNSTRUCTURED_GRID\n"
    out += b"POINTS 8 double\n" + b"".join(struct.pack(">3d", *p) for p in points) + b"\n"
    sizes = cell_sizes or [4] * len(tets)
    out += (cells_header or "CELLS %d %d\n" % (len(tets), 5 * len(tets))).encode()
    out += b"".join(struct.pack(">5i", s, *t) for s, t in zip(sizes, tets)) + b"\n"
    out += b"CELL_TYPES 5\n" + struct.pack(">5i", *[10] * 5) + b"\n"
    return out if keep is None else out[:keep]


write("vtkb_good_reference.vtk", vtk_binary())
write("vtkb_cells_size_lies.vtk", vtk_binary(cells_header="CELLS 5 2500000\n"))
write("vtkb_cell_point_count_lies.vtk", vtk_binary(cell_sizes=[4, 4, 400, 4, 4]))
write("vtkb_truncated.vtk", vtk_binary(keep=150))
nan_cube = vtk_binary()
at = nan_cube.index(b"POINTS 8 double\n") + len(b"POINTS 8 double\n") + 8 * 4  # point 1, y
write("vtkb_nan_coordinate.vtk", nan_cube[:at] + struct.pack(">d", float("nan")) + nan_cube[at + 8:])

# ---- VTK XML (.vtu): an ASCII cube, and one with zlib-compressed appended data -------------------


def vtu_ascii(npoints=8, types=None, conn_last=6):
    conn = [i for t in tets for i in t]
    conn[-1] = conn_last
    types = types if types is not None else [10] * 5
    return ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian">\n'
            '  <UnstructuredGrid>\n    <Piece NumberOfPoints="%d" NumberOfCells="5">\n      <Points>\n'
            '        <DataArray type="Float64" Name="Points" NumberOfComponents="3" format="ascii">\n'
            '          %s\n        </DataArray>\n      </Points>\n      <Cells>\n'
            '        <DataArray type="Int64" Name="connectivity" format="ascii">\n          %s\n        </DataArray>\n'
            '        <DataArray type="Int64" Name="offsets" format="ascii">\n          4 8 12 16 20\n        </DataArray>\n'
            '        <DataArray type="UInt8" Name="types" format="ascii">\n          %s\n        </DataArray>\n'
            '      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n' %
            (npoints, " ".join("%g %g %g" % p for p in points), " ".join(map(str, conn)), " ".join(map(str, types))))


write("vtu_good_reference.vtu", vtu_ascii())
write("vtu_truncated.vtu", vtu_ascii()[:700])
write("vtu_points_lie.vtu", vtu_ascii(npoints=800000000000))
write("vtu_types_short.vtu", vtu_ascii(types=[10] * 4))
write("vtu_bad_point_index.vtu", vtu_ascii(conn_last=40))
write("vtu_not_vtu.vtu", "<html><body>not a mesh</body></html>\n")


def vtu_zlib(block_bytes=None):
    """The cube's points as one zlib block of appended raw data (UInt32 header: blocks, block size,
    last block size, compressed size); block_bytes overrides the announced block sizes."""
    raw = b"".join(struct.pack("<3d", *p) for p in points)
    z = zlib.compress(raw)
    size = block_bytes if block_bytes is not None else len(raw)
    pts = struct.pack("<4I", 1, size, size, len(z)) + z
    conn = b"".join(struct.pack("<q", i) for t in tets for i in t)
    offs = b"".join(struct.pack("<q", 4 * (k + 1)) for k in range(5))
    typ = bytes([10] * 5)
    arrays, offset, blob = [], 0, b""
    for name, kind, data in (("connectivity", "Int64", conn), ("offsets", "Int64", offs), ("types", "UInt8", typ)):
        zz = zlib.compress(data)
        block = struct.pack("<4I", 1, len(data), len(data), len(zz)) + zz
        arrays.append((name, kind, len(pts) + offset))
        blob += block
        offset += len(block)
    cells = "".join('        <DataArray type="%s" Name="%s" format="appended" offset="%d"/>\n' % (kind, name, at)
                    for name, kind, at in arrays)
    head = ('<?xml version="1.0"?>\n<VTKFile type="UnstructuredGrid" version="0.1" byte_order="LittleEndian" '
            'header_type="UInt32" compressor="vtkZLibDataCompressor">\n  <UnstructuredGrid>\n'
            '    <Piece NumberOfPoints="8" NumberOfCells="5">\n      <Points>\n'
            '        <DataArray type="Float64" Name="Points" NumberOfComponents="3" format="appended" offset="0"/>\n'
            '      </Points>\n      <Cells>\n' + cells + '      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n'
            '  <AppendedData encoding="raw">\n   _')
    return head.encode() + pts + blob + b"\n  </AppendedData>\n</VTKFile>\n"


write("vtu_zlib_good_reference.vtu", vtu_zlib())
write("vtu_zlib_block_huge.vtu", vtu_zlib(block_bytes=2300000000))

# ---- surface tools (.vtp, VTK XML PolyData): the cube of tool_open.obj, ascii -------------------
CUBE_POINTS = ["0 0 0", "0.1 0 0", "0.1 0.1 0", "0 0.1 0", "0 0 0.1", "0.1 0 0.1", "0.1 0.1 0.1", "0 0.1 0.1"]
CUBE_TRIANGLES = [(0, 3, 2), (0, 2, 1), (4, 5, 6), (4, 6, 7), (0, 1, 5), (0, 5, 4),
                  (1, 2, 6), (1, 6, 5), (2, 3, 7), (2, 7, 6), (3, 0, 4), (3, 4, 7)]


def vtp_ascii(triangles):
    """A .vtp of the cube's points and these triangles, one per line."""
    conn = "".join("          %d %d %d\n" % t for t in triangles)
    offsets = " ".join(str(3 * (i + 1)) for i in range(len(triangles)))
    return ('<?xml version="1.0"?>\n<VTKFile type="PolyData" version="0.1" byte_order="LittleEndian">\n  <PolyData>\n'
            '    <Piece NumberOfPoints="8" NumberOfPolys="%d">\n      <Points>\n'
            '        <DataArray type="Float64" Name="Points" NumberOfComponents="3" format="ascii">\n'
            '          %s\n        </DataArray>\n      </Points>\n      <Polys>\n'
            '        <DataArray type="Int64" Name="connectivity" format="ascii">\n%s        </DataArray>\n'
            '        <DataArray type="Int64" Name="offsets" format="ascii">\n          %s\n        </DataArray>\n'
            '      </Polys>\n    </Piece>\n  </PolyData>\n</VTKFile>\n') % (len(triangles), "  ".join(CUBE_POINTS), conn, offsets)


write("tool_open.vtp", vtp_ascii(CUBE_TRIANGLES[:-1]))  # the last triangle left out, as in tool_open.obj
write("tool_bad_index.vtp", vtp_ascii(CUBE_TRIANGLES[:3] + [(4, 6, 40)] + CUBE_TRIANGLES[4:]))
write("tool_is_vtu.vtp", vtu_ascii())  # a .vtu mesh named .vtp

# ---- TetGen (cube1.node: 8 points; cube1.ele: 5 tetrahedra) ---------------------------------------
node, ele = read("cube1.node"), read("cube1.ele")
write("tg_truncated.node", edit(node, keep=6))
write("tg_truncated.ele", ele)
write("tg_bad_index.node", node)
write("tg_bad_index.ele", edit(ele, {3: "2 3 4 2 12"}))
write("tg_nan.node", edit(node, {4: "3 1 NaN 0"}))
write("tg_nan.ele", ele)
write("tg_order2.node", node)
write("tg_order2.ele", edit(ele, {1: "5 10 0"}))
write("tg_lonely.node", node)
write("tg_inverted.node", node)
write("tg_inverted.ele", edit(ele, {4: "3 6 5 2 7"}))
