#!/usr/bin/env python3
"""Tables and plot of the downstream benchmark (scripts/bench_downstream.sh): the distance between
each method's Screened Poisson reconstruction and the original mesh.

    downstream_report.py --csv downstream.csv --header raw/downstream_header.txt --out DIR

writes DIR/downstream.md and DIR/downstream.png. bench/results_doc.py uses the same tables for
docs/results.md. Distances are in units of 10^-3 of the original mesh's bounding-box diagonal.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from report import md_table, models_in_order, num, read_rows  # noqa: E402

METHOD_LABEL = {
    "ours": "ours, the feature-sensitive output (level 8)",
    "ours-none": "ours, unweighted",
    "ours-quality": "ours (confidence = points represented)",
    "ours-area": "ours (confidence = ellipse area)",
    "ours-sqrt": "ours (confidence = square root of the points represented)",
    "ours-nofit": "ours without the fit to the blended surface (--fit-offsets 0), unweighted",
    "ours-even": "ours for reconstruction (level 8, --spread-evenly 1: the same count; what resample_and_reconstruct.mlx reconstructs), unweighted",
    "cgal-hierarchy": "CGAL hierarchy",
    "cgal-grid": "CGAL grid",
    "meshlab-poisson": "MeshLab Poisson disk",
    "floor": "floor: the whole input",
}
METHOD_ORDER = list(METHOD_LABEL)
PEERS = ["cgal-hierarchy", "cgal-grid", "meshlab-poisson"]
SHORT = {"ours": "ours", "ours-none": "ours unweighted", "ours-quality": "ours by points", "ours-area": "ours area", "ours-sqrt": "ours sqrt",
         "ours-nofit": "ours no fit", "ours-even": "ours even", "cgal-hierarchy": "hierarchy",
         "cgal-grid": "grid", "meshlab-poisson": "Poisson disk", "floor": "floor"}
STATS = [("rms", "RMS"), ("p99", "p99"), ("max", "max")]
DIRECTIONS = [("symmetric", "both ways"), ("to_original", "reconstruction → original"),
              ("to_reconstruction", "original → reconstruction")]
# The issue's criterion: ours' RMS and p99 below every peer's, its max at most 10 % above.
MAX_SLACK = 1.10


def milli(v):
    return f"{1000 * v:.3f}"


def pick(rows, model, method):
    return next((r for r in rows if r["model"] == model and r["method"] == method), None)


def methods_present(rows):
    present = {r["method"] for r in rows}
    return [m for m in METHOD_ORDER if m in present] + sorted(present - set(METHOD_ORDER))


def depth_note(rows):
    depths = {}
    for r in rows:
        depths.setdefault(r["depth"], []).append(r["model"])
    parts = [f"depth {d} for {', '.join(dict.fromkeys(ms))}" for d, ms in sorted(depths.items())]
    return "; ".join(parts)


def model_table(rows, model):
    """Every method on one model: points, weighting, and RMS / p99 / max each way."""
    headings = ["method", "points", "weight"] + [f"{d} {s}" for _, d in DIRECTIONS for _, s in STATS]
    lines = []
    for method in methods_present(rows):
        r = pick(rows, model, method)
        if r is None:
            continue
        name = METHOD_LABEL.get(method, method) + (" (count NOT matched)" if r["matched"] == "no" else "")
        lines.append([name, f"{int(r['points']):,}", r["weight"]] +
                     [milli(num(r, f"{d}_{s}")) for d, _ in DIRECTIONS for s, _ in STATS])
    return md_table(headings, lines)


def overview_table(rows, stat):
    """One line per model: every method's symmetric `stat`, the best compared method in bold."""
    methods = methods_present(rows)
    compared = [m for m in methods if m != "floor"]
    lines = []
    for model in models_in_order(rows):
        values = {m: num(pick(rows, model, m), f"symmetric_{stat}") for m in methods if pick(rows, model, m)}
        best = min((values[m] for m in compared if m in values), default=None)
        lines.append([model] + [cell(values[m], values[m] == best and m != "floor", unmatched(rows, model, m))
                                if m in values else "–" for m in methods])
    return md_table(["model"] + [SHORT.get(m, m) for m in methods], lines)


def cell(value, best, not_matched):
    text = milli(value)
    return ("**" + text + "**" if best else text) + ("†" if not_matched else "")


def unmatched(rows, model, peer):
    p = pick(rows, model, peer)
    return p is not None and p["matched"] == "no"


def comparison(rows, model, peer, ours="ours"):
    """(RMS lower, p99 lower, max within 10 %) of ours against `peer` on `model`, or None when
    either is missing or the peer's count could not be matched to ours (CGAL's hierarchy has no
    output between ~42 % and ~58 % of the input)."""
    o, p = pick(rows, model, ours), pick(rows, model, peer)
    if o is None or p is None or unmatched(rows, model, peer):
        return None
    return (num(o, "symmetric_rms") < num(p, "symmetric_rms"), num(o, "symmetric_p99") < num(p, "symmetric_p99"),
            num(o, "symmetric_max") <= MAX_SLACK * num(p, "symmetric_max"))


def unmatched_note(rows):
    """The footnote for † in the overview tables, or "" when every peer was matched."""
    models = [(m, p) for m in models_in_order(rows) for p in PEERS if unmatched(rows, m, p)]
    if not models:
        return ""
    return ("† count NOT matched to ours' (" + ", ".join(f"{SHORT[p]} on {m}: {int(pick(rows, m, p)['points']):,} "
                                                        f"points for {int(pick(rows, m, 'ours')['points']):,}"
                                                        for m, p in models) +
            "): left out of the wins; CGAL's hierarchy has no output between ~42 % and ~58 % of the input.")


def wins_table(rows, ours="ours"):
    """Per peer: on how many models ours meets each part of the criterion, and all of it."""
    models = models_in_order(rows)
    lines = []
    for peer in PEERS:
        results = [c for c in (comparison(rows, m, peer, ours) for m in models) if c]
        if not results:
            continue
        n = len(results)
        lines.append([METHOD_LABEL[peer]] + [f"{sum(c[i] for c in results)}/{n}" for i in range(3)] +
                     [f"{sum(all(c) for c in results)}/{n}"])
    return md_table(["peer", "ours' RMS lower", "ours' p99 lower", "ours' max ≤ 1.1 × peer's", "all three"], lines)


def beats_every_peer(rows, ours):
    """The models where `ours` meets the criterion against every peer matched to its count."""
    return [m for m in models_in_order(rows)
            if all(c is None or all(c) for c in (comparison(rows, m, peer, ours) for peer in PEERS))]


def lead(rows):
    """One sentence for what users reconstruct from: the output resample_and_reconstruct.mlx makes
    (ours-even) against the feature-sensitive one, both against every peer at once; "" without it."""
    if pick(rows, models_in_order(rows)[0], "ours-even") is None:
        return ""
    n = len(models_in_order(rows))
    even, plain = beats_every_peer(rows, "ours-even"), beats_every_peer(rows, "ours")
    missed = [m for m in models_in_order(rows) if m not in even]
    return (f"**{METHOD_LABEL['ours-even'][0].upper() + METHOD_LABEL['ours-even'][1:]}** meets the criterion "
            f"(RMS and p99 lower, max at most 10 % above) against every peer at once on {len(even)} of {n} models"
            + (f" (not on {', '.join(missed)})" if missed else "") +
            f"; the feature-sensitive output on {len(plain)}.")


def failures(rows, ours="ours"):
    """The models where ours misses the criterion against some peer, with the figures that miss."""
    out = []
    for model in models_in_order(rows):
        o = pick(rows, model, ours)
        missed = []
        for peer in PEERS:
            c = comparison(rows, model, peer, ours)
            if c is None or all(c):
                continue
            p = pick(rows, model, peer)
            parts = [f"{label} {milli(num(o, 'symmetric_' + key))} vs {milli(num(p, 'symmetric_' + key))}"
                     for ok, (key, label) in zip(c, STATS) if not ok]
            missed.append(f"{SHORT[peer]} ({', '.join(parts)})")
        if missed:
            out.append(f"- **{model}**: " + "; ".join(missed))
    return "\n".join(out) if out else "None: ours meets the criterion against every peer on every model."


def plot(rows, path):
    """Per model, each method's both-way RMS, p99 and max over the floor's (1 = as good as
    reconstructing from the whole input): the models' scales differ tenfold, the ratios do not."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    models = [m for m in models_in_order(rows) if pick(rows, m, "floor")]
    methods = [m for m in methods_present(rows) if m != "floor"]
    fig, axes = plt.subplots(len(STATS), 1, figsize=(max(9, 0.8 * len(models) + 2), 3.0 * len(STATS)), sharex=True)
    width = 0.8 / len(methods)
    for ax, (stat, title) in zip(axes, STATS):
        for i, method in enumerate(methods):
            xs, ys = [], []
            for j, model in enumerate(models):
                r = pick(rows, model, method)
                if r is not None:
                    xs.append(j + (i - (len(methods) - 1) / 2) * width)
                    ys.append(num(r, f"symmetric_{stat}") / num(pick(rows, model, "floor"), f"symmetric_{stat}"))
            ax.bar(xs, ys, width, label=SHORT.get(method, method), edgecolor="black" if method == "ours" else None)
        ax.axhline(1.0, color="0.4", linewidth=0.8)
        ax.set_ylabel(f"{title} / floor's")
        ax.grid(axis="y", alpha=0.3)
    axes[-1].set_xticks(range(len(models)))
    axes[-1].set_xticklabels(models, rotation=30, ha="right")
    fig.suptitle("Reconstruction against the original mesh, both ways, over the floor's (lower is better)",
                 fontsize=10)
    fig.legend(*axes[0].get_legend_handles_labels(), ncol=len(methods), fontsize=8, loc="upper center",
               bbox_to_anchor=(0.5, 0.965))
    fig.tight_layout(rect=(0, 0, 1, 0.94))
    fig.savefig(path, dpi=100)
    plt.close(fig)


WEIGHTING = {"none": "unweighted", "quality": "with confidence = the points each surfel represents",
             "area": "with confidence = each ellipse's area",
             "sqrt": "with confidence = the square root of the points each surfel represents"}


def intro(rows):
    ours = next((r for r in rows if r["method"] == "ours"), None)
    weighting = WEIGHTING.get(ours["weight"], ours["weight"]) if ours else "as shipped"
    return ("Each model is resampled by ours (`gsresample`, level 8) and by every peer matched to our count "
            "(±2 %); MeshLab's *Screened Poisson* (2020.09, meshlabserver) reconstructs a surface from each "
            f"point set ({depth_note(rows)}; the other parameters at MeshLab's defaults), ours {weighting}, "
            "the peers' points and the floor (the whole input) unweighted. Each reconstruction is measured against the original mesh with uniform area samples "
            "of each surface and the exact distance to the nearest triangle of the other (`gsmeshdist`): "
            "RMS, 99th percentile and maximum, in 10⁻³ of the original's bounding-box diagonal; *both ways* "
            "pools the two directions' samples (RMS over both, p99 of both, max = the Hausdorff distance).")


def write_report(rows, header, out_dir):
    ours_variants = [m for m in methods_present(rows) if m.startswith("ours-")]
    parts = ["# Downstream: surface reconstruction from the resampled points", header.strip(),
             intro(rows) + " Definitions: `bench/README.md`, *Downstream: surface reconstruction*.", lead(rows),
             "## Summary (both ways)",
             "Ours against each peer: on how many models ours' RMS and p99 are lower and its max is at most "
             "10 % above the peer's.", wins_table(rows),
             "Where ours misses (ours vs peer, 10⁻³ diagonal):", failures(rows)]
    if pick(rows, models_in_order(rows)[0], "ours-even") is not None:
        parts += ["Where ours for reconstruction misses (ours even vs peer, 10⁻³ diagonal):",
                  failures(rows, "ours-even")]
    for variant in ours_variants:
        parts += [f"The same with {METHOD_LABEL[variant]} in place of ours:", wins_table(rows, variant)]
    for stat, title in STATS:
        parts += [f"### {title}, both ways (best compared method in bold)", overview_table(rows, stat)]
    parts.append(unmatched_note(rows))
    parts += ["Each method's figures over the floor's (the whole input reconstructed the same way):",
              "![Both-way RMS, p99 and max per model and method, over the floor's](downstream.png)", "## Every model"]
    for model in models_in_order(rows):
        first = pick(rows, model, "ours") or next(r for r in rows if r["model"] == model)
        parts += [f"### {model} ({int(first['input_points']):,} points, depth {first['depth']})",
                  model_table(rows, model)]
    with open(os.path.join(out_dir, "downstream.md"), "w") as f:
        f.write("\n\n".join(p for p in parts if p) + "\n")
    plot(rows, os.path.join(out_dir, "downstream.png"))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--csv", required=True)
    ap.add_argument("--header", required=True)
    ap.add_argument("--out", required=True)
    args = ap.parse_args()
    rows = read_rows(args.csv)
    if not rows:
        sys.exit(f"downstream_report.py: no rows in {args.csv}")
    with open(args.header) as f:
        header = f.read()
    write_report(rows, header, args.out)
    print(f"downstream_report.py: wrote {os.path.join(args.out, 'downstream.md')} and downstream.png")


if __name__ == "__main__":
    main()
