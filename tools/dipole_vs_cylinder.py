#!/usr/bin/env python3
"""Point-dipole force (SPEC 6.12) against magpylib's finite-cylinder force for the thesis'
magnets: 3 mm diameter x 5 mm NdFeB cylinders, axially magnetised (Br = 1.3 T, as
foldchain::Design), standing upright side by side with opposite poles (attracting), centre
distance r from 1.02 to 10 diameters.

Writes tools/dipole_vs_cylinder.csv: r/D, r (mm), the cylinder force (N, magpylib getFT on a
meshed target), the dipole force 3 mu0 m^2 / (4 pi r^4) (N) with m = Br V / mu0, and their
ratio. Run: pip install magpylib; python3 tools/dipole_vs_cylinder.py
"""
import csv
import math
import os

import magpylib as magpy
import numpy as np

MU0 = 4e-7 * math.pi
D, H, BR = 3e-3, 5e-3, 1.3
V = math.pi * (D / 2) ** 2 * H
M = BR * V / MU0


def dipole_force(r):
    return 3 * MU0 * M * M / (4 * math.pi * r**4)


def cylinder_force(r, mesh):
    src = magpy.magnet.Cylinder(polarization=(0, 0, BR), dimension=(D, H))
    tgt = magpy.magnet.Cylinder(polarization=(0, 0, -BR), dimension=(D, H), position=(r, 0, 0))
    f, _t = magpy.getFT(src, tgt, meshing=mesh)
    return -float(np.asarray(f).ravel()[0])  # attraction: force on target towards -x


def main():
    here = os.path.dirname(os.path.abspath(__file__))
    rows = []
    for k in [1.02, 1.04, 1.1, 1.25, 1.5, 1.87, 2.0, 2.5, 3.0, 4.0, 4.8, 5.0, 6.0, 8.0, 10.0]:
        r = k * D
        fc = cylinder_force(r, 4000)
        fc2 = cylinder_force(r, 8000)  # mesh convergence check
        fd = dipole_force(r)
        rows.append((k, r * 1e3, fc, fd, fd / fc, abs(fc2 - fc) / abs(fc)))
        print(f"r = {k:5.2f} D ({r*1e3:6.2f} mm): cylinder {fc:.4e} N, dipole {fd:.4e} N, "
              f"dipole/cylinder {fd/fc:.4f} (mesh change {abs(fc2-fc)/abs(fc):.1e})")
    with open(os.path.join(here, "dipole_vs_cylinder.csv"), "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["r_over_d", "r_mm", "cylinder_force_n", "dipole_force_n",
                    "dipole_over_cylinder", "mesh_change"])
        for row in rows:
            w.writerow([f"{row[0]:.2f}", f"{row[1]:.3f}", f"{row[2]:.6e}", f"{row[3]:.6e}",
                        f"{row[4]:.5f}", f"{row[5]:.1e}"])


if __name__ == "__main__":
    main()
