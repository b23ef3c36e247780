#!/usr/bin/env python3
"""How far the error figures of table 1 move by chance: the resampler at level 8 on every model,
once per seed salt (ResamplingTuning::seedSalt, gsbench --seed-salt), each salt another, equally
valid order of the seeds of index propagation (vcg_ext/gaussphere/clustering/seed_order.h).

    bench/seed_spread.py [--build DIR] [--salts N] [--baseline CSV --baseline-name NAME] [models...]

Runs salts 0 (the default) to N-1 (default 9) on the models of ../shared/data (default: the
16 of table 1), two threads, and writes bench/results/seed_spread.md and its rows to
bench/results/raw/seed_spread.csv. The spread of a cell is (largest - smallest) / median over
the salts. With --baseline (a table1.csv of other code) it also counts, per salt, the cells more
than 1 % worse than the baseline's, and lists the cells where salt 0 is, with the salts' range.
"""
import argparse
import csv
import os
import statistics
import subprocess
import sys
from datetime import datetime, timezone

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
MODELS = ["dragon", "igea", "bunny", "horse", "armadillo_43k", "maxplanck_25k", "buddha_res3", "dragon_res2",
          "fandisk", "rocker_arm", "anchor", "block", "casting", "sharp_sphere", "trim_star", "twirl"]
COLUMNS = ["l21_own_rms", "l21_own_max", "l21_own_p999", "l21_blend_rms", "l21_blend_max", "l21_blend_p999",
           "dstar_rms", "dstar_max", "dstar_p999"]
HEADINGS = ["L2,1 own RMS", "L2,1 own max", "L2,1 own p99.9", "L2,1 blend RMS", "L2,1 blend max",
            "L2,1 blend p99.9", "Δ* RMS", "Δ* max", "Δ* p99.9"]
KINDS = [("RMS", "_rms"), ("p99.9", "_p999"), ("max", "_max")]


def run_salts(gsbench, data, models, salts, csv_path, work):
    if os.path.exists(csv_path):
        os.remove(csv_path)
    env = dict(os.environ, OMP_NUM_THREADS="2", GLIBC_TUNABLES="glibc.malloc.hugetlb=1")
    for salt in range(salts):
        for model in models:
            subprocess.run([gsbench, "compare", os.path.join(data, model + ".ply"), "--name", f"{model}@{salt}",
                            "--methods", "ours", "--threads", "2", "--runs", "1", "--no-process",
                            "--seed-salt", str(salt), "--csv", csv_path, "--work", work],
                           check=True, env=env, stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        print(f"[seed_spread] salt {salt} done", file=sys.stderr)


def load_runs(csv_path):
    """{model: [row of salt 0, row of salt 1, ...]}"""
    runs = {}
    for row in csv.DictReader(open(csv_path)):
        model, salt = row["model"].rsplit("@", 1)
        runs.setdefault(model, {})[int(salt)] = row
    return {m: [by_salt[s] for s in sorted(by_salt)] for m, by_salt in runs.items()}


def change(value, reference):
    return (value - reference) / reference if reference else 0.0


def spread(values):
    middle = statistics.median(values)
    return (max(values) - min(values)) / middle if middle else 0.0


def summary_lines(runs):
    lines = ["| statistic | cells | median spread | largest spread | cells spread over 1 % |", "|---|---|---|---|---|"]
    for kind, suffix in KINDS:
        spreads = [spread([float(r[c]) for r in rows]) for rows in runs.values() for c in COLUMNS if c.endswith(suffix)]
        lines.append(f"| {kind} | {len(spreads)} | {100 * statistics.median(spreads):.1f} % | "
                     f"{100 * max(spreads):.1f} % | {sum(s > 0.01 for s in spreads)} |")
    return lines


def per_salt_lines(runs, baseline):
    head = "| salt | surfels | cells > 1 % worse than salt 0 | > 1 % better |"
    rule = "|---|---|---|---|"
    if baseline:
        head += " > 1 % worse than the baseline | > 1 % better |"
        rule += "---|---|"
    lines = [head, rule]
    salts = len(next(iter(runs.values())))
    for s in range(salts):
        def count(reference, sign):
            return sum(1 for m, rows in runs.items() for c in COLUMNS
                       if sign * change(float(rows[s][c]), float(reference(m)[c])) > 0.01)
        own = lambda m: runs[m][0]
        cells = [str(s), str(sum(int(rows[s]["points"]) for rows in runs.values())),
                 str(count(own, 1)) if s else "-", str(count(own, -1)) if s else "-"]
        if baseline:
            base = lambda m: baseline[m]
            cells += [str(count(base, 1)), str(count(base, -1))]
        lines.append("| " + " | ".join(cells) + " |")
    return lines


def spread_table_lines(runs):
    lines = ["| model | " + " | ".join(HEADINGS) + " |", "|---" * (len(COLUMNS) + 1) + "|"]
    for model, rows in runs.items():
        lines.append(f"| {model} | " + " | ".join(f"{100 * spread([float(r[c]) for r in rows]):.1f}"
                                                  for c in COLUMNS) + " |")
    return lines


def baseline_lines(runs, baseline, name):
    lines = [f"| model | figure | {name} | salt 0 | salts' smallest | median | largest | {name} inside |",
             "|---|---|---|---|---|---|---|---|"]
    for model, rows in runs.items():
        for column, heading in zip(COLUMNS, HEADINGS):
            reference, values = float(baseline[model][column]), [float(r[column]) for r in rows]
            if change(values[0], reference) <= 0.01:
                continue
            inside = "yes" if min(values) <= reference <= max(values) else "no"
            lines.append(f"| {model} | {heading} | {reference:.4g} | {values[0]:.4g} ({100 * change(values[0], reference):+.1f} %) | "
                         f"{min(values):.4g} | {statistics.median(values):.4g} | {max(values):.4g} | {inside} |")
    return lines


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("models", nargs="*", default=MODELS)
    parser.add_argument("--build", default=os.path.join(ROOT, "build"))
    parser.add_argument("--salts", type=int, default=9)
    parser.add_argument("--baseline", help="a table1.csv to count the cells against")
    parser.add_argument("--baseline-name", default="baseline")
    args = parser.parse_args()
    if args.salts < 2:
        parser.error("--salts needs at least 2")
    data = os.environ.get("SHARED_DATA_DIR", os.path.join(ROOT, "..", "shared", "data"))
    gsbench = os.path.join(args.build, "bench", "gsbench")
    if not os.access(gsbench, os.X_OK):
        sys.exit(f"seed_spread: build the gsbench target in {args.build} first")
    csv_path = os.path.join(HERE, "results", "raw", "seed_spread.csv")
    os.makedirs(os.path.dirname(csv_path), exist_ok=True)
    run_salts(gsbench, data, args.models, args.salts, csv_path, "/tmp/gsbench_seed_spread")
    runs = load_runs(csv_path)
    baseline = None
    if args.baseline:
        baseline = {r["model"]: r for r in csv.DictReader(open(args.baseline))
                    if r["method"] == "ours" and r["threads"] == "2"}
        missing = [m for m in runs if m not in baseline]
        if missing:
            sys.exit("seed_spread: the baseline lacks " + ", ".join(missing))
    commit = subprocess.run(["git", "-C", ROOT, "rev-parse", "--short", "HEAD"], capture_output=True,
                            text=True).stdout.strip()
    out = [f"# Error figures by seed salt: {len(runs)} models, salts 0 to {args.salts - 1}", "",
           f"Level 8, 2 threads; `bench/seed_spread.py`, commit {commit}, "
           f"{datetime.now(timezone.utc):%Y-%m-%d}. Each salt is another, equally valid order of the "
           "seeds (salt 0 is the default); spread = (largest - smallest) / median over the salts.", "",
           *summary_lines(runs), "", "Per salt, the 144 cells against salt 0"
           + (f" and against {args.baseline_name}:" if baseline else ":"), "", *per_salt_lines(runs, baseline), "",
           "Spread per cell (%):", "", *spread_table_lines(runs)]
    if baseline:
        out += ["", f"Cells where salt 0 is more than 1 % worse than {args.baseline_name}:", "",
                *baseline_lines(runs, baseline, args.baseline_name)]
    path = os.path.join(HERE, "results", "seed_spread.md")
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")
    print("\n".join(out))
    print(f"[seed_spread] wrote {path}", file=sys.stderr)


if __name__ == "__main__":
    main()
