#!/usr/bin/env python3
"""ctest bench.gsmeshdist_cubes: gsmeshdist on two PLY files whose distance is known.

    gsmeshdist_test.py --gsmeshdist PATH --work DIR

Writes the unit cube and the cube grown by g = 0.1 on every side as PLY meshes, runs
`gsmeshdist GROWN UNIT` and checks its CSV line against the answer, over the unit cube's
diagonal sqrt(3): every point of the unit cube lies exactly g from the grown cube (RMS = p99 =
max = g); the grown cube lies at most g sqrt(3) from the unit cube (at its corners) and its RMS
distance is sqrt(g^2 + 4 g^3 / (3 (1 + 2 g))).
"""
import argparse
import math
import os
import subprocess
import sys

G = 0.1


def cube_ply(path, lo, hi):
    corners = [(x, y, z) for x in (lo, hi) for y in (lo, hi) for z in (lo, hi)]
    index = {c: i for i, c in enumerate(corners)}
    faces = []
    for axis in range(3):
        for side in (lo, hi):
            quad = [c for c in corners if c[axis] == side]
            # quad's corners in order around the face: sort by angle around its centre.
            u, v = [a for a in range(3) if a != axis]
            mid = (lo + hi) / 2
            quad.sort(key=lambda c: math.atan2(c[v] - mid, c[u] - mid))
            a, b, c, d = (index[q] for q in quad)
            faces += [(a, b, c), (a, c, d)]
    with open(path, "w") as f:
        f.write(f"ply\nformat ascii 1.0\nelement vertex {len(corners)}\nproperty float x\nproperty float y\n"
                f"property float z\nelement face {len(faces)}\nproperty list uchar int vertex_indices\nend_header\n")
        f.writelines(f"{x} {y} {z}\n" for x, y, z in corners)
        f.writelines(f"3 {a} {b} {c}\n" for a, b, c in faces)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gsmeshdist", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    unit, grown = os.path.join(args.work, "unit.ply"), os.path.join(args.work, "grown.ply")
    cube_ply(unit, 0.0, 1.0)
    cube_ply(grown, -G, 1.0 + G)
    header = subprocess.run([args.gsmeshdist, "--csv-header"], check=True, capture_output=True, text=True).stdout
    line = subprocess.run([args.gsmeshdist, grown, unit, "--samples", "200000"], check=True,
                          capture_output=True, text=True).stdout
    row = dict(zip(header.strip().split(","), (float(v) for v in line.strip().split(","))))
    print(row)
    diagonal = math.sqrt(3)
    rms_grown = math.sqrt(G * G + 4 * G ** 3 / (3 * (1 + 2 * G)))
    checks = [
        ("faces", row["reconstruction_faces"] == 12 and row["original_faces"] == 12),
        ("diagonal", abs(row["diagonal"] - diagonal) < 1e-6),
        *((f"to_reconstruction_{s}", abs(row[f"to_reconstruction_{s}"] - G / diagonal) < 1e-6)
          for s in ("rms", "p99", "max")),
        ("to_original_rms", abs(row["to_original_rms"] - rms_grown / diagonal) < 2e-3 * rms_grown / diagonal),
        ("to_original_max", 0.98 * G * math.sqrt(3) <= row["to_original_max"] * diagonal <= G * math.sqrt(3) + 1e-6),
        ("symmetric_max", row["symmetric_max"] == row["to_original_max"]),
    ]
    failed = [name for name, ok in checks if not ok]
    if failed:
        sys.exit(f"gsmeshdist_test.py: FAILED: {', '.join(failed)}")
    print("gsmeshdist_test.py: ok")


if __name__ == "__main__":
    main()
