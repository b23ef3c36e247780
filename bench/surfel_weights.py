#!/usr/bin/env python3
"""Writes our surfels with another weight as quality, for the downstream benchmark's weightings
(scripts/bench_downstream.sh, OURS_WEIGHTS=area or sqrt).

    surfel_weights.py IN.surfel OUT.ply area|sqrt

IN is a `.surfel` file (docs/surfel_format.md); OUT is a binary PLY with x y z nx ny nz quality:
- area: proportional to pi |major semi-axis| |minor semi-axis|;
- sqrt: the square root of the points each surfel represents;
scaled so that the qualities sum to the input points represented, as the points-represented
weighting's do: Screened Poisson's result depends on the weights' scale, and areas in model units
(1e-5 on the bunny) leave it no surface.
"""
import sys

import numpy as np

FIELDS = ["x", "y", "z", "nx", "ny", "nz", "radius", "major_x", "major_y", "major_z",
          "minor_x", "minor_y", "minor_z", "quality", "blend_scale", "fit_offset"]


def read_surfels(path):
    data = open(path, "rb").read()
    end = data.index(b"end_header\n") + len(b"end_header\n")
    header = data[:end].decode("ascii").splitlines()
    if "comment gaussphere-surfel 3" not in header:
        sys.exit(f"surfel_weights.py: {path} is not a version-3 .surfel file")
    count = next(int(line.split()[2]) for line in header if line.startswith("element vertex"))
    dtype = np.dtype([(f, "<f4") for f in FIELDS] + [(c, "u1") for c in ("red", "green", "blue", "alpha")])
    return np.frombuffer(data, dtype=dtype, count=count, offset=end)


def main():
    if len(sys.argv) != 4 or sys.argv[3] not in ("area", "sqrt"):
        sys.exit(__doc__)
    s = read_surfels(sys.argv[1])
    major = np.stack([s["major_x"], s["major_y"], s["major_z"]], axis=1)
    minor = np.stack([s["minor_x"], s["minor_y"], s["minor_z"]], axis=1)
    out = np.empty(len(s), dtype=[(f, "<f4") for f in ("x", "y", "z", "nx", "ny", "nz", "quality")])
    for f in ("x", "y", "z", "nx", "ny", "nz"):
        out[f] = s[f]
    if sys.argv[3] == "area":
        weight = np.pi * np.linalg.norm(major, axis=1) * np.linalg.norm(minor, axis=1)
    else:
        weight = np.sqrt(s["quality"].astype(np.float64))
    out["quality"] = weight * (s["quality"].sum() / weight.sum())
    header = ("ply\nformat binary_little_endian 1.0\n"
              f"element vertex {len(out)}\n"
              + "".join(f"property float {f}\n" for f in out.dtype.names) + "end_header\n")
    with open(sys.argv[2], "wb") as f:
        f.write(header.encode("ascii"))
        f.write(out.tobytes())


if __name__ == "__main__":
    main()
