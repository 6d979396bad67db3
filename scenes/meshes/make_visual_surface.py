#!/usr/bin/env python3
"""Makes a finer visual surface for a tetrahedral Gmsh 2.2 ASCII mesh, as an OBJ file: the boundary
faces of its tetrahedra (turned outwards), each split once into four (edge midpoints), then smoothed
by Taubin's lambda/mu filter (G. Taubin, "A signal processing approach to fair surface design",
SIGGRAPH 1995: lambda = 0.5, mu = -0.53, 4 pairs of passes), which smooths without shrinking much.
The smoothed vertices lie just inside or just outside the volume mesh, as a visual mesh made
separately would.

    python3 scenes/meshes/make_visual_surface.py scenes/meshes/organ_2428.msh scenes/meshes/organ_2428_visual.obj
"""
import sys


def read_msh(path):
    nodes, tets, ids = [], [], {}
    lines = open(path).read().split("\n")
    i = 0
    while i < len(lines):
        if lines[i] == "$Nodes":
            n = int(lines[i + 1])
            for k in range(n):
                f = lines[i + 2 + k].split()
                ids[int(f[0])] = len(nodes)
                nodes.append(tuple(float(x) for x in f[1:4]))
            i += n + 2
        elif lines[i] == "$Elements":
            n = int(lines[i + 1])
            for k in range(n):
                f = [int(x) for x in lines[i + 2 + k].split()]
                if f[1] == 4:
                    tets.append([ids[x] for x in f[3 + f[2]:]])
            i += n + 2
        else:
            i += 1
    return nodes, tets


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def boundary(nodes, tets):
    faces = {}
    for t in tets:
        c = tuple(sum(nodes[n][a] for n in t) / 4 for a in range(3))
        for k in range(4):
            f = [t[(k + 1) % 4], t[(k + 2) % 4], t[(k + 3) % 4]]
            key = tuple(sorted(f))
            faces.setdefault(key, [f, c, 0])[2] += 1
    out = []
    for key in sorted(faces):
        f, c, uses = faces[key]
        if uses != 1:
            continue
        n = cross(sub(nodes[f[1]], nodes[f[0]]), sub(nodes[f[2]], nodes[f[0]]))
        if dot(n, sub(nodes[f[0]], c)) < 0:
            f = [f[0], f[2], f[1]]
        out.append(f)
    return out


def subdivide(points, tris):
    points = list(points)
    mid = {}

    def m(a, b):
        key = (min(a, b), max(a, b))
        if key not in mid:
            mid[key] = len(points)
            points.append(tuple((points[a][k] + points[b][k]) / 2 for k in range(3)))
        return mid[key]

    out = []
    for a, b, c in tris:
        ab, bc, ca = m(a, b), m(b, c), m(c, a)
        out += [[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]
    return points, out


def taubin(points, tris, passes=4, lam=0.5, mu=-0.53):
    nbr = [set() for _ in points]
    for t in tris:
        for k in range(3):
            nbr[t[k]].add(t[(k + 1) % 3])
            nbr[t[k]].add(t[(k + 2) % 3])
    p = [list(x) for x in points]
    for _ in range(passes):
        for f in (lam, mu):
            q = []
            for i, x in enumerate(p):
                avg = [sum(p[j][a] for j in nbr[i]) / len(nbr[i]) for a in range(3)]
                q.append([x[a] + f * (avg[a] - x[a]) for a in range(3)])
            p = q
    return p


def main():
    src, dst = sys.argv[1], sys.argv[2]
    nodes, tets = read_msh(src)
    tris = boundary(nodes, tets)
    used = sorted({n for t in tris for n in t})
    local = {n: i for i, n in enumerate(used)}
    points = [nodes[n] for n in used]
    tris = [[local[n] for n in t] for t in tris]
    points, tris = subdivide(points, tris)
    points = taubin(points, tris)
    with open(dst, "w") as out:
        out.write("# visual surface of %s: its %d boundary triangles split once into four and Taubin-smoothed\n" % (src.split("/")[-1], len(tris) // 4))
        out.write("# made by scenes/meshes/make_visual_surface.py (see scenes/meshes/README.md); %d vertices, %d triangles, metres\n" % (len(points), len(tris)))
        for x in points:
            out.write("v %.9g %.9g %.9g\n" % tuple(x))
        for t in tris:
            out.write("f %d %d %d\n" % (t[0] + 1, t[1] + 1, t[2] + 1))


main()
