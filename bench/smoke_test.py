#!/usr/bin/env python3
"""ctest bench.smoke: one small comparison (ours at n = 8 against CGAL's hierarchy clustering)
through gsbench and report.py; fails unless every figure of the table is present and finite.
Then gsbench knn (nanoflann's reference neighbour search): one finite time, and a misspelt option
refused. Timings are only required to exist: their values depend on the machine."""
import argparse
import csv
import math
import os
import shutil
import subprocess
import sys

ERROR_COLUMNS = ["l21_own_rms", "l21_own_max", "l21_own_p999", "l21_blend_rms", "l21_blend_max",
                 "l21_blend_p999", "dstar_rms", "dstar_max", "dstar_p999"]


def fail(message):
    print(f"bench.smoke: FAIL: {message}")
    sys.exit(1)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--gsbench", required=True)
    ap.add_argument("--report", required=True)
    ap.add_argument("--input", required=True)
    ap.add_argument("--work", required=True)
    args = ap.parse_args()
    shutil.rmtree(args.work, ignore_errors=True)
    os.makedirs(args.work)
    raw = os.path.join(args.work, "raw.csv")
    subprocess.run([args.gsbench, "compare", args.input, "--name", "bunny", "--level", "8", "--methods",
                    "ours,cgal-hierarchy", "--threads", "1", "--runs", "1", "--csv", raw, "--work", args.work],
                   check=True)
    subprocess.run([sys.executable, args.report, "--table1", raw, "--out", args.work], check=True)

    with open(raw, newline="") as f:
        rows = {r["method"]: r for r in csv.DictReader(f)}
    for method in ("ours", "cgal-hierarchy"):
        if method not in rows:
            fail(f"no {method} row in {raw}")
        r = rows[method]
        for key in ERROR_COLUMNS + ["time_alg_s", "time_process_s", "peak_mb"]:
            try:
                value = float(r[key])
            except ValueError:
                fail(f"{method}: {key} is {r[key]!r}")
            if not math.isfinite(value) or value < 0:
                fail(f"{method}: {key} = {value}")
        if int(r["points"]) <= 0:
            fail(f"{method}: no points")
    target = int(rows["ours"]["points"])
    if abs(int(rows["cgal-hierarchy"]["points"]) - target) > 0.02 * target or rows["cgal-hierarchy"]["matched"] != "yes":
        fail(f"CGAL hierarchy count {rows['cgal-hierarchy']['points']} not within 2 % of {target}")

    with open(os.path.join(args.work, "table1.md")) as f:
        table = f.read()
    for needed in ("| bunny | ours, 1 thread |", "| bunny | CGAL hierarchy |"):
        if needed not in table:
            fail(f"table1.md lacks the row {needed!r}")
    if "nan" in table.lower():
        fail("table1.md shows a NaN")

    knn = subprocess.run([args.gsbench, "knn", args.input, "--runs", "1"], capture_output=True, text=True)
    try:
        seconds = float(knn.stdout)
    except ValueError:
        fail(f"gsbench knn printed {knn.stdout!r} (status {knn.returncode}, {knn.stderr.strip()!r})")
    if knn.returncode != 0 or not math.isfinite(seconds) or seconds <= 0:
        fail(f"gsbench knn: status {knn.returncode}, {seconds} s")
    misspelt = subprocess.run([args.gsbench, "knn", args.input, "--kk", "16"], capture_output=True, text=True)
    if misspelt.returncode == 0 or "unknown option --kk" not in misspelt.stderr:
        fail(f"gsbench knn --kk: status {misspelt.returncode}, {misspelt.stderr.strip()!r}")
    print("bench.smoke: ok")


if __name__ == "__main__":
    main()
