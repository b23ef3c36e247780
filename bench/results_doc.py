#!/usr/bin/env python3
"""Writes docs/results.md, the results page a user reads, from the committed result files, and
prints README.md's results table (the lines between <!-- results:begin --> and
<!-- results:end -->).

    results_doc.py            write docs/results.md and print the README table
    results_doc.py --check    write nothing; fail when docs/results.md or README.md's table
                              differs from what the result files give (ctest cli.results_table)

Sources, each section stamped with the run (commit, machine, date) its figures come from:
  bench/results/header.txt, raw/table1.csv, raw/speed_{warm,cold}.csv, figure7_*.png
                                            scripts/bench.sh (level 8, speed target, figure 7)
  bench/results/raw/control_header.txt, raw/control_{targets,error_bound}.csv
                                            scripts/bench_control.sh (output size, error bound)
  bench/results/raw/downstream_header.txt, downstream.csv, downstream.png
                                            scripts/bench_downstream.sh (surface reconstruction)
  bench/results/filter_speed.md             bench/filter_speed.sh (the whole filter against CGAL)
  bench/results/seed_spread.md              bench/seed_spread.py (the error figures by seed order)
  bench/render/results.md                   scripts/bench_render.sh (rendering quality)
  bench/scale/results.md, results.csv, results_target.csv
                                            scripts/bench_scale.sh (scale)
bench/report.py calls this after writing bench/results/ (a full run of bench.sh or
bench_control.sh); after filter_speed.sh, seed_spread.py, bench_render.sh or bench_scale.sh run it by hand.
"""
import argparse
import difflib
import os
import re
import statistics
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import downstream_report  # noqa: E402
import report  # noqa: E402  (the same formatting and row selection as the benchmark's tables)
from report import fmt, md_table, models_in_order, num, ours_row, pick  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
RESULTS_DIR = os.path.join(ROOT, "bench", "results")
DOC = os.path.join(ROOT, "docs", "results.md")
README = os.path.join(ROOT, "README.md")
BEGIN, END = "<!-- results:begin -->", "<!-- results:end -->"

# The level-8 comparison: (csv key, README heading, number format).
LEVEL8_METRICS = [("dstar_rms", "Δ*RMS", "e"), ("dstar_max", "Δ*max", "f"), ("l21_blend_rms", "L2,1 RMS", "f")]


def path(*parts):
    return os.path.join(ROOT, *parts)


def read(p):
    with open(p) as f:
        return f.read()


def rel(p):
    """p relative to docs/, for links from docs/results.md."""
    return os.path.relpath(p, os.path.dirname(DOC)).replace(os.sep, "/")


# ------------------------------------------------------------------------------------------------
# Stamps

def bench_stamp(header_file, script, files):
    """The stamp of a gsbench run from its header (scripts/bench_common.sh's bench_header)."""
    text = read(header_file)
    m = re.search(r"^Run (.+?) at commit (\S+)\s*\non (.+?),?\s*$", text, re.M)
    if not m:
        sys.exit(f"results_doc.py: {header_file} names no run (Run DATE at commit HASH / on MACHINE)")
    dirty = re.search(r"^Built with uncommitted changes in: (.+)$", text, re.M)
    return (f"*Data: `{script}` at commit {m.group(2)}"
            + (f" (built with uncommitted changes in {dirty.group(1).strip()})" if dirty else "")
            + f", on {m.group(3)}, {m.group(1)}; " + ", ".join(f"`{f}`" for f in files) + ".*")


def render_stamp(text):
    """The stamp of bench/render/results.md, or None when it names no commit."""
    commit = re.search(r"of commit (\w+)", text)
    run = re.search(r"Written by .*? on (\d{4}-\d{2}-\d{2}), (.+?),\s*OpenGL: ([^;]+?);", text, re.S)
    if not (commit and run):
        return None
    dirty = re.search(r"at run time: (.+?)\.", text, re.S)
    dirty = " ".join(dirty.group(1).split()) if dirty else "not recorded"
    machine = " ".join(run.group(2).split())
    renderer = " ".join(run.group(3).split())
    return (f"*Data: `scripts/bench_render.sh` at commit {commit.group(1)} (uncommitted changes: {dirty}), "
            f"on {machine}, OpenGL {renderer}, {run.group(1)}; `bench/render/results.md`.*")


def scale_stamp(text):
    """The stamp of bench/scale/results.md, or None when it names no commit."""
    commit = re.search(r"^- commit: (.+)$", text, re.M)
    if not commit:
        return None
    machine = re.search(r"^- machine: (.+)$", text, re.M)
    date = re.search(r"^- date: (.+)$", text, re.M)
    return (f"*Data: `scripts/bench_scale.sh` at commit {commit.group(1).strip()}, on "
            f"{machine.group(1).strip() if machine else 'a machine not recorded'}, "
            f"{date.group(1).strip() if date else 'run date not recorded by gsscale'}; "
            "`bench/scale/results.md`, `results_target.md`.*")


# ------------------------------------------------------------------------------------------------
# Level 8: ours against CGAL's hierarchy and MeshLab's Poisson disk

def level8_cells(rows, model):
    """(ours, hierarchy, poisson, hierarchy unmatched) rows of one model."""
    o = ours_row(rows, model)
    h, p = pick(rows, model, "cgal-hierarchy"), pick(rows, model, "meshlab-poisson")
    return o, h, p, bool(h and h.get("matched") == "no")


def readme_table(rows):
    """README.md's results table and its footnote (the lines between the results markers)."""
    headings = ["model", "input points", "our surfels (% of input)"] + \
               [f"{h}: ours / hierarchy / Poisson" for _, h, _ in LEVEL8_METRICS]
    lines, unmatched = [], []
    for model in models_in_order(rows):
        o, h, p, dagger = level8_cells(rows, model)
        if o is None:
            continue
        if dagger:
            unmatched.append(model)
        cell = lambda r, k, kind: fmt(num(r, k), kind) if r else "–"
        lines.append([model, f"{int(o['input_points']):,}", f"{int(o['points']):,} ({num(o, 'percent'):.1f} %)"] +
                     [f"{cell(o, k, kind)} / {cell(h, k, kind)}{'†' if dagger else ''} / {cell(p, k, kind)}"
                      for k, _, kind in LEVEL8_METRICS])
    out = md_table(headings, lines)
    if unmatched:
        at = statistics.median(num(pick(rows, m, "cgal-hierarchy"), "percent") for m in unmatched)
        not_lower = []
        for m in unmatched:
            exact, h = pick(rows, m, "ours@cgal-hierarchy"), pick(rows, m, "cgal-hierarchy")
            if exact is None or any(not num(exact, k) < num(h, k) for k, _, _ in LEVEL8_METRICS):
                not_lower.append(m)
        still = "is lower still" if not not_lower else "is not lower on every figure (" + ", ".join(not_lower) + ")"
        out += ("\n\n† CGAL's hierarchy has no output between ~42 % and ~58 % of the input: its figure is at its own\n"
                f"count (~{at:.0f} %), where ours, made exact by `TargetCount`, {still} (`table1.md`).")
    return out


def level8_wins(rows):
    """One line per peer: on how many models ours is lower, per metric (at the peer's count where
    the peer's could not be matched to ours)."""
    out = []
    for peer in ("cgal-hierarchy", "meshlab-poisson"):
        counts = []
        for key, heading, _ in LEVEL8_METRICS:
            won = total = 0
            for model in models_in_order(rows):
                pair = report.comparable(rows, model, peer, key, ours_row(rows, model))
                if pair:
                    total += 1
                    won += num(pair[0], key) < num(pair[1], key)
            counts.append(f"{heading} on {won}/{total}")
        out.append(f"- against {report.METHOD_LABEL[peer]}: " + ", ".join(counts))
    return "Ours is lower:\n\n" + "\n".join(out)


# ------------------------------------------------------------------------------------------------
# Output size and error bound (bench_control.sh)

CONTROL_SHOWN = [m for m in report.CONTROL_METRICS if m[0] in ("l21_blend_rms", "dstar_rms", "dstar_max", "time")]


def control_targets(rows):
    for r in rows:
        r["target"] = f"{num(r, 'target_percent'):g} %"
    ours = [r for r in rows if r["method"] == "ours"]
    exact = sum(1 for r in ours if int(r["points"]) == int(r["target_points"]))
    wins, _ = report.control_wins(rows, "target", "target", CONTROL_SHOWN)
    seconds = md_table(["target", "ours alg s: median (largest)", "CGAL hierarchy alg s: median",
                        "ours process s: median", "MeshLab Poisson process s: median"],
                       [[t, f"{fmt(med(g, 'ours', 'time_alg_s'), 's')} ({fmt(top(g, 'ours', 'time_alg_s'), 's')})",
                         fmt(med(g, "cgal-hierarchy", "time_alg_s"), "s"), fmt(med(g, "ours", "time_process_s"), "s"),
                         fmt(med(g, "meshlab-poisson", "time_process_s"), "s")]
                        for t, g in report.group_rows(rows, "target").items()])
    return [f"Ours at an exact output size (`TargetPercentage`: {', '.join(report.group_rows(rows, 'target'))} of "
            f"the input, 1 thread) on {len(models_in_order(rows))} models; each peer matched to our count "
            f"within ±2 %. Ours gave exactly the target on **{exact}/{len(ours)}** runs.",
            "On how many models ours is lower (errors; *time*: ours / CGAL in-process, ours / MeshLab whole "
            "processes, since MeshLab runs only as meshlabserver):", wins,
            "Time per run, median over the models:", seconds]


def med(rows, method, key):
    values = [num(r, key) for r in rows if r["method"] == method and num(r, key) == num(r, key)]
    return statistics.median(values) if values else float("nan")


def top(rows, method, key):
    values = [num(r, key) for r in rows if r["method"] == method and num(r, key) == num(r, key)]
    return max(values) if values else float("nan")


def control_error_bound(rows):
    for r in rows:
        r["bound"] = f"{num(r, 'max_error'):g}"
    compared = [r for r in rows if r["method"] != "floor"]
    wins, _ = report.control_wins(compared, "bound", "ε", CONTROL_SHOWN)
    lines = []
    for bound, g in report.group_rows(rows, "bound").items():
        ours = [r for r in g if r["method"] == "ours"]
        floors = [r for r in g if r["method"] == "floor"]
        held = sum(1 for r in ours if num(r, "dstar_max") <= num(r, "max_error"))
        floor_held = sum(1 for r in floors if num(r, "dstar_max") <= num(r, "max_error"))
        pct = [num(r, "percent") for r in ours]
        lines.append([bound, f"{held}/{len(ours)}", f"{floor_held}/{len(floors)}" if floors else "–",
                      f"{statistics.median(pct):.1f} ({min(pct):.1f}–{max(pct):.1f})"])
    return [f"Ours under an error bound ε (`MaxError`, a fraction of the bounding-box diagonal) at level 8, "
            f"1 thread, on {len(models_in_order(rows))} models; each peer matched to our resulting count "
            "within ±2 %. *floor*: the input itself as circular surfels (S' = S), whose blended surface "
            "already departs from the points by more than small ε.",
            md_table(["ε", "ours: Δ*max ≤ ε", "floor S' = S: Δ*max ≤ ε", "ours: output % of input, median (range)"],
                     lines),
            "On how many models ours is lower (peers at our count):", wins]


# ------------------------------------------------------------------------------------------------
# Surface reconstruction downstream

def downstream():
    """The section's parts, or [] before the first run of scripts/bench_downstream.sh."""
    header, table = os.path.join(RESULTS_DIR, "raw", "downstream_header.txt"), os.path.join(RESULTS_DIR, "downstream.csv")
    if not (os.path.exists(header) and os.path.exists(table)):
        return []
    rows = report.read_rows(table)
    if not rows:
        return []
    variants = [m for m in downstream_report.methods_present(rows) if m.startswith("ours-")]
    parts = ["## Reconstruction downstream",
             bench_stamp(header, "scripts/bench_downstream.sh", ["bench/results/downstream.csv"]),
             downstream_report.intro(rows) + " Definitions: [bench/README.md](../bench/README.md); every "
             f"model, each way: [downstream.md]({rel(os.path.join(RESULTS_DIR, 'downstream.md'))}).",
             downstream_report.lead(rows),
             "On how many models ours' RMS and p99 are lower than the peer's and its max at most 10 % above:",
             downstream_report.wins_table(rows)]
    for variant in variants:
        parts += [f"The same table for {downstream_report.METHOD_LABEL[variant]}, in place of the feature-sensitive "
                  "output (level 8, unweighted):",
                  downstream_report.wins_table(rows, variant)]
    for stat, title in downstream_report.STATS:
        parts += [f"{title} of the distance both ways, 10⁻³ of the diagonal (best compared method in bold):",
                  downstream_report.overview_table(rows, stat)]
    parts.append(downstream_report.unmatched_note(rows))
    if os.path.exists(os.path.join(RESULTS_DIR, "downstream.png")):
        parts += ["Each method's figures over the floor's (the whole input reconstructed the same way):",
                  f"![Both-way RMS, p99 and max per model and method, over the floor's]"
                  f"({rel(os.path.join(RESULTS_DIR, 'downstream.png'))})"]
    return parts


# ------------------------------------------------------------------------------------------------
# Speed (table 1's timing and the speed target)

def timing_table(rows):
    lines = []
    for model in models_in_order(rows):
        o1, o2 = pick(rows, model, "ours", "1"), pick(rows, model, "ours", "2")
        h, p = pick(rows, model, "cgal-hierarchy"), pick(rows, model, "meshlab-poisson")
        if o1 is None:
            continue
        hier = "–" if h is None or h.get("matched") == "no" else fmt(num(h, "time_alg_s"), "s")
        lines.append([model, f"{int(o1['points']):,}", fmt(num(o1, "time_alg_s"), "s"),
                      fmt(num(o2, "time_alg_s"), "s") if o2 else "–", hier,
                      fmt(num(o1, "time_process_s"), "s"), fmt(num(p, "time_process_s"), "s") if p else "–"])
    return md_table(["model", "surfels", "ours alg s, 1 thread", "2 threads", "CGAL hierarchy alg s",
                     "ours process s, 1 thread", "MeshLab Poisson process s"], lines)


# ------------------------------------------------------------------------------------------------
# Rendering and scale (their own result files)

def render_summary(text):
    """The summary table of bench/render/results.md."""
    m = re.search(r"^## Summary[^\n]*\n\n((?:\|[^\n]*\n)+)", text, re.M)
    return m.group(1).rstrip("\n") if m else None


def scale_table():
    import csv
    lines = []
    for name, control in (("results.csv", "level 8"), ("results_target.csv", "10 % (TargetPercentage)")):
        p = path("bench", "scale", name)
        if not os.path.exists(p):
            continue
        with open(p, newline="") as f:
            for r in csv.DictReader(f):
                points = int(r["points"])
                lines.append([f"{points:,}", control, r["threads"], f"{int(r['output']):,}",
                              f"{float(r['total_s']):.2f}", f"{float(r['cpu_s']):.2f}",
                              f"{float(r['peak_bytes']) / 2**20:.0f}",
                              f"{float(r['beyond_input_bytes']) / points:.1f}"])
    return md_table(["input points", "output size", "threads", "surfels", "wall s", "CPU s", "peak MiB",
                     "B/point beyond the input"], lines) if lines else None


def whole_vs_tiled_rows(f, shape):
    """Rows of a whole-against-tiled table from bench_tile.sh's compare lines, at 5 and 20 million
    points of `shape` (its tag prefix: "" for the dragon, "drilled-box_")."""
    rows = []
    for points in ("5000000", "20000000"):
        tag = shape + points
        c, whole, tiled = f"compare_{tag}", f"whole_{tag}", f"tiled_{tag}"
        if (c, "count_diff_pct") not in f:
            continue
        rows.append([f"{int(points):,}", f[(tiled, "tiles")],
                     f"{int(f[(c, 'count_whole')]):,} / {int(f[(c, 'count_tiled')]):,} "
                     f"({signed_percent(float(f[(c, 'count_diff_pct')]))})",
                     ", ".join(signed_percent(float(f[(c, k)])) for k in
                               ("delta_rms_diff_pct", "delta_max_diff_pct", "l21_own_rms_diff_pct",
                                "l21_blended_rms_diff_pct")),
                     largest_tail_difference(f, c),
                     signed_percent(float(f[(c, "members_diff_pct")])),
                     f"{f[(c, 'whole_border_uncovered')]} / {f[(c, 'tiled_border_uncovered')]} of "
                     f"{int(f[(c, 'tiled_border_points')]):,}",
                     rescued_cell(f, c),
                     f"{f[(whole, 'wall_s')]} / {f[(tiled, 'wall_s')]}",
                     f"{f[(whole, 'peak_mib')]} / {f[(tiled, 'peak_mib')]}"])
    return rows


def largest_tail_difference(f, name):
    """Of the Δ* 99.9th percentile and the L2,1 maxima and 99.9th percentiles, tiled against
    whole, the difference farthest from 0."""
    keys = ["delta_p999_diff_pct"] + [f"l21_{kind}_{figure}_diff_pct" for kind in ("own", "blended")
                                      for figure in ("max", "p999")]
    if any((name, k) not in f for k in keys):
        return "not measured"
    return signed_percent(max((float(f[(name, k)]) for k in keys), key=abs))


def rescued_cell(f, name):
    """Surfels the merge kept for border points no tile kept nor covered, and those points."""
    if (name, "tiled_rescued_surfels") not in f:
        return "–"
    return f"{int(f[(name, 'tiled_rescued_surfels')]):,} for {int(f[(name, 'tiled_orphans_uncovered')]):,}"


def tile_results(stage):
    """bench/tile/results/STAGE.txt (bench/tile/bench_tile.sh): its stamp lines and its figures as
    {(name, key): value}, or None when absent."""
    p = path("bench", "tile", "results", f"{stage}.txt")
    if not os.path.exists(p):
        return None
    stamp, figures = {}, {}
    for line in read(p).splitlines():
        if line.startswith("# load average at "):
            stamp[line.split()[4]] = line[2:]
        elif line.startswith("# "):
            key, _, value = line[2:].partition(" ")
            stamp[key] = value
        elif line.startswith("outputs_1_and_2_workers="):
            figures[("outputs", "identical")] = line.split("=", 1)[1] == "identical"
        elif line.startswith("[merge] "):
            merged = re.match(r"\[merge\] (\d+) surfels .*; (\d+) kept for (\d+) border points", line)
            if merged:
                figures[("merge", "surfels")], figures[("merge", "rescued")], figures[("merge", "uncovered")] = \
                    merged.groups()
        else:
            words = line.split()
            for word in words[1:]:
                if "=" in word:
                    key, value = word.split("=", 1)
                    figures[(words[0], key)] = value
    return stamp, figures


def signed_percent(value):
    text = f"{value:+.2f}"
    return ("0.00" if text in ("+0.00", "-0.00") else text) + " %"


def tile_stamp(stage, stamp):
    loads = "; ".join(v for k, v in stamp.items() if k in ("start", "end"))
    return (f"*Data: `bench/tile/bench_tile.sh WORK {stage}` at commit {stamp.get('commit', '?')}, on "
            f"{stamp.get('machine', '?')}, {stamp.get('date', '?')}; {loads}; `bench/tile/results/{stage}.txt`.*")


def tiling():
    parts = []
    big = tile_results("big")
    if big:
        stamp, f = big
        one, two = float(f[("dask_1_workers", "wall_s")]), float(f[("dask_2_workers", "wall_s")])
        points = int(f[("big_parameters", "points")])
        parts += [f"### {points / 1e6:,.0f} million points from disk, on Dask", tile_stamp("big", stamp),
                  f"The dragon densified by `gsscale` to {points // 20000000} samplings of 20 million points "
                  f"({points * 24 / 1e9:.1f} GB of binary PLY), split into tiles of about "
                  f"{int(f[('big_parameters', 'tile_points')]) / 1e6:g} million points and resampled through "
                  "`scripts/gstile_dask.py` on a local cluster, each tile's run in its own process under a "
                  f"{int(f[('big_parameters', 'cap_mib')]) / 1024:g} GiB address-space cap (`ulimit -v`).",
                  md_table(["step", "wall s", "points/s", "peak MiB"],
                           [["split", f[("split_big", "wall_s")], f"{points / float(f[('split_big', 'wall_s')]):,.0f}",
                             f[("split_big", "peak_mib")]],
                            ["tiles on 1 worker", f"{one:.1f}", f"{points / one:,.0f}",
                             f[("dask_1_workers", "largest_tile_peak_mib")] + " (largest tile)"],
                            ["tiles on 2 workers", f"{two:.1f}", f"{points / two:,.0f}",
                             f[("dask_2_workers", "largest_tile_peak_mib")] + " (largest tile)"]]),
                  f"Speed-up from one worker to two: {one / two:.2f}. The outputs of one and two workers are "
                  + ("identical." if f.get(("outputs", "identical")) else "NOT identical.")
                  + (f" The merge wrote {int(f[('merge', 'surfels')]):,} surfels, {int(f[('merge', 'rescued')]):,} of "
                     f"them kept for {int(f[('merge', 'uncovered')]):,} border points no tile kept nor covered "
                     "(docs/tiling.md, *Border points*)." if ("merge", "surfels") in f else "")]
    compare_columns = ["points", "tiles", "surfels whole / tiled", "Δ* RMS, Δ* max, L2,1 own RMS, "
                       "L2,1 blended RMS: tiled − whole",
                       "Δ* p99.9, L2,1 max and p99.9 own and blended: the largest tiled − whole",
                       "points represented: tiled − whole",
                       "uncovered points along tile faces, whole / tiled",
                       "surfels kept for border points no tile kept nor covered", "wall s whole / tiled",
                       "peak MiB whole / tiled"]
    for stage, shape, title, text in (
            ("compare", "", "Tiled against whole",
             "The dragon densified by `gsscale` (random order), level 8, halo 24 sample spacings; `gstile all` "
             "against `gsresample` on the same input, compared by `gstile_compare` (docs/tiling.md, *Checking a "
             "tiled run*)."),
            ("flat", "drilled-box_", "Flat faces",
             "The drilled box of `gsscale` (a cube with a cylindrical hole: flat faces, sharp edges), otherwise as "
             "above (docs/tiling.md, *Halo width*: on a flat face, one Gaussian triangle wide, clusters depend "
             "only on points near them because seeds come in an order hashed from their positions).")):
        results = tile_results(stage)
        rows = whole_vs_tiled_rows(results[1], shape) if results else []
        if rows:
            parts += [f"### {title}", tile_stamp(stage, results[0]), text, md_table(compare_columns, rows)]
    halo = tile_results("halo")
    if halo:
        stamp, f = halo
        rows = []
        for width in ("1", "2", "4", "6", "8", "12", "16", "24", "32"):
            name = f"halo_{width}"
            if (name, "count_diff_pct") not in f:
                continue
            rows.append([width, f"{int(f[(name, 'count_tiled')]):,}", f"{round(float(f[(name, 'members_tiled')])):,}",
                         signed_percent(float(f[(name, "delta_rms_diff_pct")])), f[(name, "tiled_border_uncovered")],
                         rescued_cell(f, name)])
        if rows:
            name = "halo_24" if ("halo_24", "count_whole") in f else f"halo_{rows[0][0]}"
            parts += ["### Halo width", tile_stamp("halo", stamp),
                      f"The dragon (437,645 points) in 13 tiles of at most 150,000 points with their halo, level 8, "
                      f"at each halo width in sample spacings; the whole run: {int(f[(name, 'count_whole')]):,} surfels "
                      f"representing {round(float(f[(name, 'members_whole')])):,} points, "
                      f"{f[(name, 'whole_border_uncovered')]} points along the tile faces uncovered "
                      "(docs/tiling.md, *Halo width*).",
                      md_table(["halo (spacings)", "surfels", "points represented", "Δ* RMS: tiled − whole",
                                "uncovered points along tile faces",
                                "surfels kept for border points no tile kept nor covered"], rows)]
    for stage, runs, label, title, text in (
            ("target", ("4000", "8000", "10000", "40000", "100000"), lambda run: f"{int(run):,}", "A target count shared over the tiles",
             "`--target N` whole and tiled (docs/tiling.md, *Size and error controls*); tiled against whole "
             "(below 0: lower tiled; the whole run's rounds of exchanges for the largest error shared over the "
             "tiles, each at its core points' worst, each tile's crease fit judged against the whole scan's "
             "99.9th percentiles, then the seam step's rounds beside the surfels its neighbours keep):"),
            ("bound", ("0.002", "0.0005"), lambda run: run, "An error bound over the tiles",
             "`--max-error E` (a fraction of the whole scan's diagonal) whole and tiled (docs/tiling.md, *Size and "
             "error controls*); tiled against whole:")):
        results = tile_results(stage)
        if not results:
            continue
        stamp, f = results
        rows = []
        for run in runs:
            name = f"{stage}_{run}"
            if (name, "count_diff_pct") not in f:
                continue
            rows.append([label(run), f"{int(f[(name, 'count_tiled')]):,}"] +
                        [signed_percent(float(f[(name, k)])) for k in ("count_diff_pct", "delta_rms_diff_pct", "delta_max_diff_pct",
                                                                  "delta_p999_diff_pct", "l21_own_rms_diff_pct",
                                                                  "l21_blended_rms_diff_pct")] +
                        [l21_tails(f, name)] +
                        [f"{f[(f'whole_{name}', 'wall_s')]} / {f[(f'tiled_{name}', 'wall_s')]}"])
        parts += [f"### {title}", tile_stamp(stage, stamp),
                  "The dragon (437,645 points) in 13 tiles of at most 150,000 points with their halo, " + text,
                  md_table([stage if stage == "target" else "bound", "surfels tiled", "count", "Δ* RMS", "Δ* max",
                            "Δ* p99.9", "L2,1 own RMS", "L2,1 blended RMS", "L2,1 max, p99.9: own; blended",
                            "wall s whole / tiled"], rows)]
    if parts:
        parts = ["## Tiled resampling",
                 "`gstile` resamples a scan of any size tile by tile ([docs/tiling.md](tiling.md); the benchmark: "
                 "[bench/tile/README.md](../bench/tile/README.md))."] + parts
    return parts


def l21_tails(f, name):
    """The L2,1 maxima and 99.9th percentiles, own and blended, tiled against whole, in one cell."""
    keys = [f"l21_{kind}_{figure}_diff_pct" for kind in ("own", "blended") for figure in ("max", "p999")]
    if any((name, k) not in f for k in keys):
        return "not measured"
    cells = [signed_percent(float(f[(name, k)])) for k in keys]
    return f"{cells[0]}, {cells[1]}; {cells[2]}, {cells[3]}"


# ------------------------------------------------------------------------------------------------
# The page

def results_doc():
    raw = os.path.join(RESULTS_DIR, "raw")
    rows = report.read_rows(os.path.join(raw, "table1.csv"))
    header = os.path.join(RESULTS_DIR, "header.txt")
    stamp8 = bench_stamp(header, "scripts/bench.sh", ["bench/results/raw/table1.csv"])
    figure_models = models_in_order(report.read_rows(os.path.join(raw, "figure7.csv"))) \
        if os.path.exists(os.path.join(raw, "figure7.csv")) else []
    pngs = [m for m in figure_models if os.path.exists(os.path.join(RESULTS_DIR, f"figure7_{m}.png"))]

    parts = [
        "# Results",
        "Our resampler (Gaussian sphere level 8 unless a section says otherwise) against CGAL's "
        "`hierarchy_simplify_point_set` (Pauly et al.'s hierarchy clustering, the paper's Table 2 peer), "
        "CGAL's grid simplification and MeshLab's *Point Cloud Simplification* (Poisson disk), each peer "
        "matched to our output count within ±2 %, on the point sets of `../shared/data`. Every output is "
        "measured by the same metric (paper, section 5.2; `vcg_ext/surfel_error/`): Δ* is the distance of "
        "each input point to the outputs' blended (MLS) surface over the bounding-box diagonal, L2,1 the "
        "error of its normal against the blended normal. Lower is better. Times are medians over "
        "interleaved rounds on a shared 2-core machine: compare them within one run. The benchmark "
        "program is `bench/` (gsbench); how to run it: [bench/README.md](../bench/README.md).",
        "This page is written by `python3 bench/results_doc.py` from the committed result files; each "
        "section names the run its figures come from.",
        "## Error at level 8",
        stamp8,
        "Ours, CGAL's hierarchy and MeshLab's Poisson disk at our level-8 count; L2,1 RMS is the blended form. "
        "Every method and figure (own-surfel L2,1, 99.9th percentiles, CGAL grid, the metric's floor): "
        f"[table1.md]({rel(os.path.join(RESULTS_DIR, 'table1.md'))}).",
        readme_table(rows),
        level8_wins(rows),
        "### The paper's Table 1 beside ours",
        "Paper values in parentheses (a Pentium IV 3.0 GHz; only the dragon is the paper's exact model). "
        "L2,1 as own surfel / blended.",
        report.table1_paper(rows),
    ]
    spread_md = os.path.join(RESULTS_DIR, "seed_spread.md")
    if os.path.exists(spread_md):
        lines = read(spread_md).strip().split("\n")
        stamp = next(l for l in lines if l.startswith("Level 8"))
        table = [l for l in lines if l.startswith("|")][:5]
        parts += ["### How far these figures move by chance",
                  "The same runs with other seed orders (`ResamplingTuning::seedSalt`), each as valid as the "
                  "default: the spread of each figure over them. The largest errors and their 99.9th "
                  "percentiles come from a few points and move most. Per model and per salt: "
                  f"[seed_spread.md]({rel(spread_md)}).",
                  stamp, "\n".join(table)]
    if pngs:
        parts += ["## Error against output size (the paper's Figure 7)", stamp8.replace(
                      "`bench/results/raw/table1.csv`", "`bench/results/raw/figure7.csv`, `raw/table1.csv`"),
                  "Ours at levels 8 to 24, every peer matched to our count at each level; tables: "
                  f"[figure7.md]({rel(os.path.join(RESULTS_DIR, 'figure7.md'))})."]
        parts += [f"![{m}]({rel(os.path.join(RESULTS_DIR, f'figure7_{m}.png'))})" for m in pngs]

    control_header = os.path.join(raw, "control_header.txt")
    for name, title, write in (("control_targets", "Exact output size", control_targets),
                               ("control_error_bound", "Error bound", control_error_bound)):
        p = os.path.join(raw, f"{name}.csv")
        if os.path.exists(p) and os.path.exists(control_header):
            parts += [f"## {title}", bench_stamp(control_header, "scripts/bench_control.sh",
                                                 [f"bench/results/raw/{name}.csv"])]
            parts += write(report.read_rows(p))
            parts.append(f"Every run: [{name}.md]({rel(os.path.join(RESULTS_DIR, name + '.md'))}).")

    parts += downstream()

    parts += ["## Speed", stamp8.replace("`bench/results/raw/table1.csv`",
                                         "`bench/results/raw/table1.csv`, `raw/speed_warm.csv`, `raw/speed_cold.csv`"),
              "`alg`: the algorithm alone, in-process, after loading (MeshLab runs only as meshlabserver: "
              "no `alg` time); `process`: a process that loads, runs and saves (meshlabserver's start-up "
              "loads ~75 plugins). Level 8; a hierarchy time is left out where its count could not be matched.",
              timing_table(rows)]
    warm, cold = os.path.join(raw, "speed_warm.csv"), os.path.join(raw, "speed_cold.csv")
    if os.path.exists(warm) and os.path.exists(cold):
        parts += ["### Ours on 2 threads against CGAL's hierarchy, more rounds",
                  "*warm*: the heap as the previous rounds left it; *cold*: returned to the system before "
                  "every run, as for a first call in a process. Below 1×: ours is faster.",
                  report.speed_target(report.read_rows(warm), report.read_rows(cold))]

    filter_md = os.path.join(RESULTS_DIR, "filter_speed.md")
    if os.path.exists(filter_md):
        parts += ["### The whole filter through meshlabserver against CGAL's hierarchy",
                  "`bash bench/filter_speed.sh`: the filter's own figures for its whole run, for its glue "
                  "around the algorithm and for the algorithm's neighbour search (its log lines); nanoflann's "
                  "kd-tree finding the 16 nearest neighbours of every point, the paper's first step by a "
                  "standard library; CGAL's hierarchy in process at our count. Medians over the rounds the stamp gives, 2 threads, "
                  "level 8. Below 1×: the whole filter is faster.",
                  read(filter_md).strip()]

    render_md = path("bench", "render", "results.md")
    if os.path.exists(render_md):
        text = read(render_md)
        stamp, summary = render_stamp(text), render_summary(text)
        if stamp and summary:
            parts += ["## Rendering quality", stamp,
                      "The level-8 surfels drawn as ellipse splats (three-pass blended, one-pass opaque) and as "
                      "3-pixel points against the original mesh, at 1024×1024 from 5 views: coverage of the "
                      "mesh's silhouette, pixels drawn outside it, PSNR against the mesh image, time per frame "
                      f"(Mesa llvmpipe, a software renderer). Per view and definitions: [results.md]({rel(render_md)}).",
                      summary]

    parts += tiling()

    scale_md = path("bench", "scale", "results.md")
    if os.path.exists(scale_md):
        stamp, table = scale_stamp(read(scale_md)), scale_table()
        if stamp and table:
            parts += ["## Scale", stamp,
                      "The dragon densified in memory to 1, 5 and 20 million points, default parameters, each "
                      "measurement in a fresh process. Peak is the process's resident memory during the run; "
                      "*beyond the input* subtracts the input mesh. Per stage and the memory ledger: "
                      f"[results.md]({rel(scale_md)}), [results_target.md]({rel(path('bench', 'scale', 'results_target.md'))}).",
                      table]
    return "\n\n".join(p for p in parts if p) + "\n", readme_table(rows)


def readme_block(text):
    """The lines between README.md's results markers, or None."""
    m = re.search(r"^" + re.escape(BEGIN) + r"\n(.*?)\n" + re.escape(END) + r"$", text, re.M | re.S)
    return m.group(1) if m else None


def differs(name, have, want):
    if have == want:
        return False
    sys.stdout.writelines(difflib.unified_diff((have or "").splitlines(True), want.splitlines(True),
                                               f"{name} (committed)", f"{name} (from the result files)"))
    print()
    return True


def write_doc():
    """Writes docs/results.md; returns the README table."""
    doc, table = results_doc()
    with open(DOC, "w") as f:
        f.write(doc)
    return table


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--check", action="store_true", help="compare instead of writing; exit 1 on a difference")
    args = ap.parse_args()
    if not args.check:
        print(write_doc())
        print(f"results_doc.py: wrote {os.path.relpath(DOC, ROOT)}; the table above goes between README.md's "
              f"{BEGIN} and {END}", file=sys.stderr)
        return
    doc, table = results_doc()
    bad = differs("docs/results.md", read(DOC) if os.path.exists(DOC) else None, doc)
    block = readme_block(read(README))
    if block is None:
        print(f"results_doc.py: README.md has no {BEGIN} ... {END} block")
        bad = True
    else:
        bad |= differs("README.md results table", block, table)
    if bad:
        sys.exit("results_doc.py: FAILED: run `python3 bench/results_doc.py` and put the table it prints into README.md")
    print("results_doc.py: ok: docs/results.md and README.md's results table match bench/results, bench/render, bench/scale")


if __name__ == "__main__":
    main()
