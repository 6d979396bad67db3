#!/usr/bin/env python3
"""Makes a closed, outward triangle surface for a SurfaceTool, as an OBJ file: a box with rounded
edges and corners (an ultrasound probe's head, a retractor's blade), made by Fascia's authors.

The surface of a box of cells (nx, ny, nz) on a regular lattice, each boundary quadrilateral split
in two, is mapped onto the rounded box of half-sizes H and edge radius r by
    q -> clamp(q, -(H - r), H - r) + r (q - clamp(q)) / |q - clamp(q)|
(a lattice point q on the outer box goes to the rounded surface along the direction from the inner
box; the flat parts stay where they are). r = 0 gives the plain box. The tool's frame has its
origin at the centre of the bottom face (z = 0, the probe's contact face), the box above it.

    python3 tools/make_tool_surface.py scenes/meshes/probe.obj
    python3 tools/make_tool_surface.py --triangles 10000 out/probe_10k.obj   # the benchmark's surface
    options: --size X Y Z (m, default 0.05 0.02 0.08), --radius R (m, default 0.008),
             --cells N (cells along the longest side, default 24), --triangles T (overrides --cells:
             the cells that give about T triangles)
"""
import argparse
import math


def lattice_cells(size, cells):
    longest = max(size)
    return [max(1, round(cells * s / longest)) for s in size]


def rounded_box(size, radius, n):
    half = [s / 2 for s in size]
    inner = [h - radius for h in half]
    index, points, triangles = {}, [], []

    def vertex(ijk):
        if ijk in index:
            return index[ijk]
        q = [-half[a] + 2 * half[a] * ijk[a] / n[a] for a in range(3)]
        c = [min(max(q[a], -inner[a]), inner[a]) for a in range(3)]
        d = [q[a] - c[a] for a in range(3)]
        length = math.sqrt(sum(x * x for x in d))
        p = [c[a] + (radius * d[a] / length if radius > 0 else d[a]) for a in range(3)]
        p[2] += half[2]  # the bottom face at z = 0
        index[ijk] = len(points)
        points.append(p)
        return index[ijk]

    for a in range(3):
        b, c = (a + 1) % 3, (a + 2) % 3  # e_b x e_c = e_a
        for side in (0, n[a]):
            for u in range(n[b]):
                for v in range(n[c]):
                    corners = []
                    for du, dv in ((0, 0), (1, 0), (1, 1), (0, 1)):
                        ijk = [0, 0, 0]
                        ijk[a], ijk[b], ijk[c] = side, u + du, v + dv
                        corners.append(vertex(tuple(ijk)))
                    if side == 0:
                        corners.reverse()  # facing -e_a
                    triangles.append((corners[0], corners[1], corners[2]))
                    triangles.append((corners[0], corners[2], corners[3]))
    return points, triangles


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("output")
    ap.add_argument("--size", type=float, nargs=3, default=[0.05, 0.02, 0.08])
    ap.add_argument("--radius", type=float, default=0.008)
    ap.add_argument("--cells", type=int, default=24)
    ap.add_argument("--triangles", type=int, default=0)
    args = ap.parse_args()
    if not 0 <= args.radius <= min(args.size) / 2:
        ap.error("the radius must be between 0 and half the smallest size")
    n = lattice_cells(args.size, args.cells)
    if args.triangles > 0:  # 4 (nx ny + ny nz + nz nx) triangles grow with the square of the cells
        k = 1.0
        for _ in range(50):
            m = [max(1, round(k * x)) for x in n]
            t = 4 * (m[0] * m[1] + m[1] * m[2] + m[2] * m[0])
            k *= math.sqrt(args.triangles / t)
        n = [max(1, round(k * x)) for x in n]
    points, triangles = rounded_box(args.size, args.radius, n)
    with open(args.output, "w") as f:
        f.write("# a rounded box %g x %g x %g m, edge radius %g m, %d x %d x %d lattice cells, %d triangles:\n"
                % (*args.size, args.radius, *n, len(triangles)))
        f.write("# generated for Fascia by tools/make_tool_surface.py (closed, outward, bottom face at z = 0)\n")
        for p in points:
            f.write("v %.7g %.7g %.7g\n" % tuple(p))
        for t in triangles:
            f.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))
    print("%s: %d vertices, %d triangles" % (args.output, len(points), len(triangles)))


if __name__ == "__main__":
    main()
