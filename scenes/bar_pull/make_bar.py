#!/usr/bin/env python3
"""Writes notched_bar.csv and notched_bar.bonds.csv: a 3 x 3 x 20 simple-cubic bar of spheres
(r = 1 mm) bonded to its six nearest neighbours, except that layers 9 and 10 are joined by the
central bond only -- the weakest section, where a pulled bar must part into two halves of 90."""
r = 0.001
nx, ny, nz = 20, 3, 3
index, rows = {}, []
for i in range(nx):
    for j in range(ny):
        for k in range(nz):
            index[(i, j, k)] = len(rows)
            rows.append((i * 2 * r, (j - 1) * 2 * r, (k - 1) * 2 * r))
bonds = []
for (i, j, k), a in index.items():
    for di, dj, dk in ((1, 0, 0), (0, 1, 0), (0, 0, 1)):
        b = index.get((i + di, j + dj, k + dk))
        if b is None:
            continue
        if di == 1 and i == 9 and (j, k) != (1, 1):
            continue  # the notch: only the central bond crosses between layers 9 and 10
        bonds.append((a, b))
with open("notched_bar.csv", "w") as f:
    f.write("# 3 x 3 x 20 simple-cubic bar, r = 1 mm; made by scenes/bar_pull/make_bar.py\nx,y,z,r,material\n")
    for x, y, z in rows:
        f.write(f"{x!r},{y!r},{z!r},{r!r},0\n")
with open("notched_bar.bonds.csv", "w") as f:
    f.write("i,j\n")
    for a, b in bonds:
        f.write(f"{a},{b}\n")
