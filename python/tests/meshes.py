# Copyright (c) 2026 mrepair contributors. SPDX-License-Identifier: GPL-3.0-or-later
"""Small meshes the tests build themselves (no files)."""

import numpy as np


def sphere(rings=12, sectors=24, radius=1.0):
    """a closed UV sphere: poles plus rings x sectors vertices, all triangles."""
    V = [(0.0, 0.0, radius)]
    for i in range(1, rings):
        theta = np.pi * i / rings
        for j in range(sectors):
            phi = 2 * np.pi * j / sectors
            V.append((radius * np.sin(theta) * np.cos(phi), radius * np.sin(theta) * np.sin(phi),
                      radius * np.cos(theta)))
    V.append((0.0, 0.0, -radius))
    V = np.array(V)
    south = len(V) - 1

    def ring(i, j):  # vertex j of ring i (1 .. rings-1)
        return 1 + (i - 1) * sectors + j % sectors

    F = []
    for j in range(sectors):
        F.append((0, ring(1, j), ring(1, j + 1)))
        F.append((south, ring(rings - 1, j + 1), ring(rings - 1, j)))
    for i in range(1, rings - 1):
        for j in range(sectors):
            a, b = ring(i, j), ring(i, j + 1)
            c, d = ring(i + 1, j), ring(i + 1, j + 1)
            F.append((a, c, d))
            F.append((a, d, b))
    return V, np.array(F, dtype=np.int64)


def grid(nx, ny, x0=0.0, width=1.0, height=1.0):
    """an open flat sheet of nx x ny squares, each split in two triangles."""
    xs = np.linspace(x0, x0 + width, nx + 1)
    ys = np.linspace(0.0, height, ny + 1)
    V = np.array([(x, y, 0.0) for y in ys for x in xs])
    F = []
    for j in range(ny):
        for i in range(nx):
            a = j * (nx + 1) + i
            b, c, d = a + 1, a + nx + 1, a + nx + 2
            F.append((a, b, d))
            F.append((a, d, c))
    return V, np.array(F, dtype=np.int64)


def two_sheets(gap, ny_left=8, ny_right=8):
    """two sheets side by side with a crack `gap` wide between them; with
    different row counts the crack has T-junctions (vertex-edge contractions)."""
    V1, F1 = grid(8, ny_left)
    V2, F2 = grid(8, ny_right, x0=1.0 + gap)
    return np.vstack([V1, V2]), np.vstack([F1, F2 + len(V1)])


def cube_quads():
    """a closed cube of six quads (a polygon mesh)."""
    V = np.array([(x, y, z) for z in (0.0, 1.0) for y in (0.0, 1.0) for x in (0.0, 1.0)])
    F = [[0, 2, 3, 1], [4, 5, 7, 6], [0, 1, 5, 4], [2, 6, 7, 3], [0, 4, 6, 2], [1, 3, 7, 5]]
    return V, F


def canonical_faces(F):
    """faces as a sorted list of triples rotated to start at their smallest index
    (same faces with the same orientation compare equal)."""
    out = []
    for f in np.asarray(F).tolist():
        k = f.index(min(f))
        out.append(tuple(f[k:] + f[:k]))
    return sorted(out)
