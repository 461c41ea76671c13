#!/usr/bin/env python3
"""Writes algorithms/models/teapot.obj: Newell's Utah teapot tessellated from its 32
Bézier patches, made into closed 2-manifolds so that every hard-shadow method
(Crow's volumes included) can use it. Run from the repository root.

- Each patch is cut into N x N cells split into triangles; points shared between
  patches are welded, so the patches of a part share their seams.
- The data set is open where the lid meets the rim (the lid's edge has radius 1.3,
  the rim's inner edge 1.4, both at height 2.4): a flat ring of 4 ruled patches
  closes it, so rim, body, bottom and lid form one closed surface.
- The handle and the spout are tubes whose ends sit on or inside the body: each open
  end, and the spout's mouth, is closed by a fan around the loop's centroid.
- Faces are oriented outwards (consistently across each part, then by its signed
  volume); vertex normals are the patches' own (du x dv), flat on the ring and caps.
- Axes: the data is z up; the file is y up, (x, y, z) -> (x, z, -y), spout along +x,
  base on y = 0.
"""
import math
from collections import defaultdict, deque

from teapot_data import PATCHES, POINTS

N = 5
OUT = "algorithms/models/teapot.obj"


def bernstein(t):
    s = 1.0 - t
    return (s * s * s, 3 * s * s * t, 3 * s * t * t, t * t * t)


def bernstein_derivative(t):
    s = 1.0 - t
    return (-3 * s * s, 3 * s * s - 6 * s * t, 6 * s * t - 3 * t * t, 3 * t * t)


def add(a, b):
    return tuple(x + y for x, y in zip(a, b))


def sub(a, b):
    return tuple(x - y for x, y in zip(a, b))


def scale(a, k):
    return tuple(x * k for x in a)


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def dot(a, b):
    return sum(x * y for x, y in zip(a, b))


def norm(a):
    length = math.sqrt(dot(a, a))
    return scale(a, 1.0 / length) if length > 0 else a


def evaluate(rows, u, v):
    """Point and (unnormalised) normal du x dv of a bicubic patch at (u, v)."""
    bu, bv, du, dv = bernstein(u), bernstein(v), bernstein_derivative(u), bernstein_derivative(v)
    point, tu, tv = (0.0,) * 3, (0.0,) * 3, (0.0,) * 3
    for i in range(4):
        for j in range(4):
            p = rows[i][j]
            point = add(point, scale(p, bu[i] * bv[j]))
            tu = add(tu, scale(p, du[i] * bv[j]))
            tv = add(tv, scale(p, bu[i] * dv[j]))
    return point, cross(tu, tv)


def control_rows(indices):
    points = [POINTS[k - 1] for k in indices]
    return [points[4 * i:4 * i + 4] for i in range(4)]


def ring_patch(lid, rim):
    """The flat ruled patch from the lid's last row to the rim's first row."""
    a, b = control_rows(PATCHES[lid])[3], control_rows(PATCHES[rim])[0]
    return [[add(a[j], scale(sub(b[j], a[j]), i / 3)) for j in range(4)] for i in range(4)]


class Mesh:
    def __init__(self):
        self.positions, self.normals, self.texcoords = [], [], []
        self.welded = {}
        self.faces = []  # [(position, texcoord, normal)] * 3

    def vertex(self, p):
        key = tuple(round(x, 6) for x in p)
        if key not in self.welded:
            self.welded[key] = len(self.positions)
            self.positions.append(p)
        return self.welded[key]

    def patch(self, rows, across=N, flat=False):
        first = len(self.faces)
        grid = []
        for i in range(across + 1):
            row = []
            for j in range(N + 1):
                u, v = i / across, j / N
                p, n = evaluate(rows, u, v)
                if dot(n, n) < 1e-12:  # a degenerate corner (lid knob, bottom centre)
                    p_near, n = evaluate(rows, min(max(u, 1e-4), 1 - 1e-4), v)
                self.normals.append(norm(n))
                self.texcoords.append((v, u))
                row.append((self.vertex(p), len(self.texcoords) - 1, len(self.normals) - 1))
            grid.append(row)
        for i in range(across):
            for j in range(N):
                a, b, c, d = grid[i][j], grid[i + 1][j], grid[i + 1][j + 1], grid[i][j + 1]
                for tri in ((a, b, c), (a, c, d)):
                    if len({corner[0] for corner in tri}) == 3:
                        self.faces.append(list(tri))
        if flat:
            self.flatten(first)

    def flatten(self, first):
        """Give faces from `first` on one flat normal each (the ring's plane)."""
        for face in self.faces[first:]:
            n = self.face_normal(face)
            self.normals.append(n)
            k = len(self.normals) - 1
            for c, corner in enumerate(face):
                face[c] = (corner[0], corner[1], k)

    def face_normal(self, face):
        a, b, c = (self.positions[corner[0]] for corner in face)
        return norm(cross(sub(b, a), sub(c, a)))

    def edges(self):
        uses = defaultdict(list)
        for f, face in enumerate(self.faces):
            for k in range(3):
                a, b = face[k][0], face[(k + 1) % 3][0]
                uses[(min(a, b), max(a, b))].append(f)
        return uses

    def orient(self):
        """Make every part's faces agree across shared edges, then point outwards."""
        uses = self.edges()
        assert all(len(fs) <= 2 for fs in uses.values()), "an edge with more than two faces"
        seen = [False] * len(self.faces)
        for start in range(len(self.faces)):
            if seen[start]:
                continue
            part, queue = [], deque([start])
            seen[start] = True
            while queue:
                f = queue.popleft()
                part.append(f)
                face = self.faces[f]
                for k in range(3):
                    a, b = face[k][0], face[(k + 1) % 3][0]
                    for g in uses[(min(a, b), max(a, b))]:
                        if g == f or seen[g]:
                            continue
                        other = [corner[0] for corner in self.faces[g]]
                        # Agreeing faces run a shared edge in opposite directions.
                        if any(other[m] == a and other[(m + 1) % 3] == b for m in range(3)):
                            self.faces[g].reverse()
                        seen[g] = True
                        queue.append(g)
            if self.signed_volume(part) < 0:
                for f in part:
                    self.faces[f].reverse()

    def signed_volume(self, faces):
        total = 0.0
        for f in faces:
            a, b, c = (self.positions[corner[0]] for corner in self.faces[f])
            total += dot(a, cross(b, c)) / 6
        return total

    def cap_boundaries(self):
        """Close every boundary loop with a fan around its centroid."""
        next_on_boundary = {}
        for (a, b), fs in self.edges().items():
            if len(fs) == 1:
                face = [corner[0] for corner in self.faces[fs[0]]]
                k = face.index(a)
                # Walk the loop against the face's direction so the fan agrees with it.
                if face[(k + 1) % 3] == b:
                    next_on_boundary[b] = a
                else:
                    next_on_boundary[a] = b
        loops = 0
        while next_on_boundary:
            start = next(iter(next_on_boundary))
            loop = [start]
            while next_on_boundary[loop[-1]] != start:
                loop.append(next_on_boundary[loop[-1]])
            for v in loop:
                del next_on_boundary[v]
            centre = scale(tuple(map(sum, zip(*(self.positions[v] for v in loop)))), 1 / len(loop))
            c = len(self.positions)
            self.positions.append(centre)
            self.texcoords.append((0.5, 0.5))
            first = len(self.faces)
            for k in range(len(loop)):
                self.faces.append([(loop[k], len(self.texcoords) - 1, 0), (loop[(k + 1) % len(loop)], len(self.texcoords) - 1, 0), (c, len(self.texcoords) - 1, 0)])
            self.flatten(first)
            loops += 1
        return loops

    def orient_normals(self):
        """Turn each corner's patch normal to the side its face faces."""
        for face in self.faces:
            n = self.face_normal(face)
            for c, (p, t, k) in enumerate(face):
                if dot(self.normals[k], n) < 0:
                    self.normals.append(scale(self.normals[k], -1))
                    face[c] = (p, t, len(self.normals) - 1)

    def check_closed(self):
        uses = self.edges()
        assert all(len(fs) == 2 for fs in uses.values()), "not closed"
        directed = set()
        for face in self.faces:
            for k in range(3):
                edge = (face[k][0], face[(k + 1) % 3][0])
                assert edge not in directed, "inconsistent orientation"
                directed.add(edge)

    def write(self, path):
        y_up = lambda p: (p[0], p[2], -p[1])
        lines = [
            f"# Newell's Utah teapot (1975): 32 Bézier patches at {N} x {N}, closed; generated by tools/teapot_obj.py.",
            "o teapot",
        ]
        lines += ["v {:.9f} {:.9f} {:.9f}".format(*y_up(p)) for p in self.positions]
        lines += ["vt {:.9f} {:.9f}".format(*t) for t in self.texcoords]
        lines += ["vn {:.9f} {:.9f} {:.9f}".format(*y_up(n)) for n in self.normals]
        for face in self.faces:
            lines.append("f " + " ".join(f"{p + 1}/{t + 1}/{k + 1}" for p, t, k in face))
        with open(path, "w") as f:
            f.write("\n".join(lines) + "\n")


def main():
    mesh = Mesh()
    for indices in PATCHES:
        mesh.patch(control_rows(indices))
    for k in range(4):
        mesh.patch(ring_patch(24 + k, k), across=1, flat=True)
    mesh.orient()
    loops = mesh.cap_boundaries()
    mesh.orient()
    mesh.check_closed()
    mesh.orient_normals()
    mesh.write(OUT)
    print(f"{OUT}: {len(mesh.positions)} vertices, {len(mesh.faces)} triangles, {loops} loops capped")


if __name__ == "__main__":
    main()
