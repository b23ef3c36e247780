#!/usr/bin/env python3
"""Helpers of scripts/bench_render.sh: prepare the resampled surfels for rendering with the
mesh's camera, compute the image metrics, write results.md/.csv, and make the README montages.

Needs numpy and matplotlib only (PNG through matplotlib.image; PLY through plyio.py).

  render_bench.py frame SURFEL MESH OUT.surfel OUT_mesh.ply
  render_bench.py colorize MESH COLOURED_POINTS.ply OUT_mesh.ply
  render_bench.py metrics WORKDIR OUT.csv OUT.md      (reads WORKDIR/runs.tsv)
  render_bench.py montage OUT.png TITLE1=IMG1 TITLE2=IMG2 ... [--crop] [--panel=PX]
"""
import csv
import math
import os
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import plyio  # noqa: E402

import matplotlib  # noqa: E402
matplotlib.use('Agg')
import matplotlib.image as mpimg  # noqa: E402
import matplotlib.pyplot as plt  # noqa: E402

GREY = 192  # tools/splat_render's default albedo, which the mesh (no colours) gets


# ---------------------------------------------------------------------------------------------
# frame: make the surfel file and the mesh frame exactly alike.
#
# splat_render centres the camera on the bounding box of the file's vertices (surfels with a
# fit_offset where it draws them, unfitted: drawn_positions) and fits its bounding sphere.
# Surfel centres lie near cluster centroids, so their box is mostly slightly smaller than the
# mesh's (and may reach slightly beyond it on convex parts): the two images would not share a
# camera. We append, for every box face the surfels do
# not reach, the mesh vertex that attains it, with a zero normal and zero axes: splat_render
# frames every position, then skips such records in every mode but mesh, so they only extend
# the box. Likewise the mesh gets, after its own
# vertices, the surfel centres that reach beyond its box: no face uses them, so mesh mode does
# not draw them. Colours are set to the mesh's grey so that the material is the same.
def drawn_positions(vertices):
    """Where splat_render draws the vertices: those with a fit_offset moved back along their
    normals to their unfitted positions (undoFitOffsets), in float32 as it does."""
    p = np.stack([vertices['x'], vertices['y'], vertices['z']], 1)
    if 'fit_offset' in (vertices.dtype.names or ()):
        p = p - vertices['fit_offset'][:, None] * np.stack([vertices['nx'], vertices['ny'], vertices['nz']], 1)
    return p


def frame(surfel_path, mesh_path, out_path, out_mesh_path):
    """Gives the surfels and the mesh one bounding box (splat_render frames a file's box): each
    gets framing vertices (zero normal, zero axes, never drawn) at the other's extremes beyond
    its own. Surfels may lie slightly outside the mesh on convex parts."""
    s, header = plyio.read_vertices(surfel_path)
    m, mheader = plyio.read_vertices(mesh_path)
    sp = drawn_positions(s)
    mp = drawn_positions(m)

    def extremes_beyond(points, other):
        extra = []
        for axis in range(3):
            lo, hi = int(np.argmin(points[:, axis])), int(np.argmax(points[:, axis]))
            if points[lo, axis] < other[:, axis].min():
                extra.append(lo)
            if points[hi, axis] > other[:, axis].max():
                extra.append(hi)
        return sorted(set(extra))

    def padded(vertices, positions, extra):
        d = np.zeros(len(extra), dtype=vertices.dtype)
        for c, name in enumerate('xyz'):
            d[name] = positions[extra, c]
        if 'blend_scale' in (vertices.dtype.names or ()):
            d['blend_scale'] = 1  # its neutral value; fit_offset's (.surfel version 3) is the zero above
        return np.concatenate([vertices, d])

    from_mesh, from_surfels = extremes_beyond(mp, sp), extremes_beyond(sp, mp)
    out = padded(s, mp, from_mesh)
    for channel in ('red', 'green', 'blue'):
        if channel in out.dtype.names:
            out[channel] = GREY
    if 'alpha' in out.dtype.names:
        out['alpha'] = 255
    plyio.write_vertices(out_path, out, header)
    # The mesh keeps its faces: the framing vertices go after its own, which the faces index.
    mesh_out = padded(m, sp, from_surfels)
    _, offset = plyio.read_header(mesh_path)
    with open(mesh_path, 'rb') as f:
        f.seek(offset + len(m) * m.dtype.itemsize)
        faces = f.read()
    with open(out_mesh_path, 'wb') as f:
        lines = ['element vertex %d' % len(mesh_out) if l.startswith('element vertex') else l for l in mheader]
        f.write(('\n'.join(lines) + '\n').encode('ascii'))
        mesh_out.tofile(f)
        f.write(faces)
    op = drawn_positions(out)
    mo = drawn_positions(mesh_out)
    assert np.array_equal(op.min(0), mo.min(0)) and np.array_equal(op.max(0), mo.max(0)), 'box not matched'
    print('%s: %d surfels + %d framing vertices; %s: %d mesh vertices + %d framing vertices'
          % (out_path, len(s), len(from_mesh), out_mesh_path, len(m), len(from_surfels)))


# ---------------------------------------------------------------------------------------------
# colorize: copy the per-vertex colours of a point set (same vertices, same order as the mesh:
# ../shared/data/README.md) onto the mesh, keeping its faces.
def colorize(mesh_path, points_path, out_path):
    m, mheader = plyio.read_vertices(mesh_path)
    p, _ = plyio.read_vertices(points_path)
    if len(m) != len(p) or not all(np.array_equal(m[c], p[c]) for c in 'xyz'):
        raise SystemExit('colorize: %s and %s do not hold the same vertices' % (mesh_path, points_path))
    _, offset = plyio.read_header(mesh_path)
    names = list(m.dtype.names)
    dtype = np.dtype([(n, m.dtype[n]) for n in names] + [(c, 'u1') for c in ('red', 'green', 'blue', 'alpha')])
    out = np.zeros(len(m), dtype=dtype)
    for n in names:
        out[n] = m[n]
    for c in ('red', 'green', 'blue', 'alpha'):
        out[c] = p[c] if c in p.dtype.names else 255
    header, in_vertex = [], False
    for line in mheader:
        words = line.split()
        if words[:1] == ['element']:
            if in_vertex:
                header += ['property uchar %s' % c for c in ('red', 'green', 'blue', 'alpha')]
            in_vertex = words[1] == 'vertex'
        header.append(line)
    with open(mesh_path, 'rb') as f:
        f.seek(offset + len(m) * m.dtype.itemsize)
        rest = f.read()
    with open(out_path, 'wb') as f:
        f.write(('\n'.join(header) + '\n').encode('ascii'))
        out.tofile(f)
        f.write(rest)


# ---------------------------------------------------------------------------------------------
# metrics
def read_rgb255(path):
    a = mpimg.imread(path)
    if a.dtype != np.uint8:
        a = np.round(a * 255.0)
    return a[:, :, :3].astype(np.float64)


def read_mask(path):
    a = mpimg.imread(path)
    if a.ndim == 3:
        a = a[:, :, 0]
    return a > 0.5


def dilate(mask):
    """3x3 (8-neighbour) dilation: one pixel of tolerance in every direction."""
    p = np.pad(mask, 1)
    out = np.zeros_like(mask)
    h, w = mask.shape
    for dy in (0, 1, 2):
        for dx in (0, 1, 2):
            out |= p[dy:dy + h, dx:dx + w]
    return out


def erode(mask):
    return ~dilate(~mask)


def luminance(rgb):
    return rgb @ np.array([0.2126, 0.7152, 0.0722])  # Rec. 709 weights, on 0..255 values


def psnr(a, b, where):
    if not where.any():
        return float('nan')
    mse = np.mean((a[where] - b[where]) ** 2)
    return float('inf') if mse == 0 else 10.0 * math.log10(255.0 ** 2 / mse)


def image_metrics(mesh_png, mesh_mask_png, png, mask_png):
    S = read_mask(mesh_mask_png)
    R = read_mask(mask_png)
    ref, img = read_rgb255(mesh_png), read_rgb255(png)
    core = erode(S)     # mesh silhouette less its 1-pixel rim: must be drawn
    halo = dilate(S)    # mesh silhouette plus a 1-pixel rim: may be drawn
    union = S | R
    rim = halo & ~core  # pixels within 1 px of the mesh's silhouette boundary
    yref, yimg = luminance(ref), luminance(img)
    err = (yref - yimg) ** 2
    return {
        'mesh_px': int(S.sum()),
        'drawn_px': int(R.sum()),
        'coverage': float((core & R).sum() / max(core.sum(), 1)),
        'coverage_strict': float((S & R).sum() / max(S.sum(), 1)),
        'holes_px': int((core & ~R).sum()),
        'outside': float((R & ~halo).sum() / max(R.sum(), 1)),
        'outside_strict': float((R & ~S).sum() / max(R.sum(), 1)),
        'psnr_y': psnr(yref, yimg, union),
        'psnr_y_inner': psnr(yref, yimg, core & R),
        'rim_error_share': float(err[union & rim].sum() / max(err[union].sum(), 1e-12)),
        'psnr_rgb': psnr(ref.reshape(-1, 3)[union.ravel()], img.reshape(-1, 3)[union.ravel()],
                         np.ones(int(union.sum()), dtype=bool)),
    }


MODE_ORDER = ['mesh', 'threepass', 'onepass', 'points']
COVERAGE_TARGET, OUTSIDE_TARGET = 0.995, 0.005


def metrics(workdir, csv_path, md_path):
    """runs.tsv: model surfels view mode variant png mask ms_per_frame (variant '' = defaults)."""
    rows = []
    with open(os.path.join(workdir, 'runs.tsv')) as f:
        runs = [line.rstrip('\n').split('\t') for line in f if line.strip()]
    meshes = {(r[0], r[2]): r for r in runs if r[3] == 'mesh'}
    for model, surfels, view, mode, variant, png, mask, ms in runs:
        ref = meshes[(model, view)]
        row = {'model': model, 'surfels': int(surfels), 'view': view, 'mode': mode, 'variant': variant,
               'ms_per_frame': float(ms) if ms else float('nan')}
        row.update(image_metrics(ref[5], ref[6], png, mask))
        rows.append(row)
    fields = ['model', 'surfels', 'view', 'mode', 'variant', 'coverage', 'coverage_strict', 'holes_px', 'outside',
              'outside_strict', 'psnr_y', 'psnr_y_inner', 'rim_error_share', 'psnr_rgb', 'ms_per_frame', 'mesh_px', 'drawn_px']
    with open(csv_path, 'w', newline='') as f:
        w = csv.DictWriter(f, fieldnames=fields)
        w.writeheader()
        for r in rows:
            w.writerow({k: ('%.6f' % r[k] if isinstance(r[k], float) else r[k]) for k in fields})
    write_markdown(rows, md_path, workdir)


def pct(x, digits=2):
    return '%.*f %%' % (digits, 100.0 * x)


def write_markdown(rows, md_path, workdir):
    models = sorted({r['model'] for r in rows}, key=lambda m: [r['model'] for r in rows].index(m))
    out = []
    meta_path = os.path.join(workdir, 'meta.md')
    if os.path.exists(meta_path):
        out.append(open(meta_path).read().rstrip() + '\n')
    base = [r for r in rows if r['variant'] == '']
    out.append('## Summary (default settings: splat scale 1, ε 1, point size 3 px), mean over views\n')
    out.append('| model | surfels | mode | coverage (1 px tol.) | worst view | outside (1 px tol.) | worst view '
               '| PSNR Y (dB) | PSNR RGB (dB) | PSNR Y inside (dB) | ms/frame |')
    out.append('|---|---|---|---|---|---|---|---|---|---|---|')
    verdicts = []
    for model in models:
        for mode in MODE_ORDER:
            rs = [r for r in base if r['model'] == model and r['mode'] == mode]
            if not rs:
                continue
            if mode == 'mesh':
                out.append('| %s | %d | mesh (reference) | | | | | | | | %.0f |' %
                           (model, rs[0]['surfels'], np.mean([r['ms_per_frame'] for r in rs])))
                continue
            cov = [r['coverage'] for r in rs]
            outs = [r['outside'] for r in rs]
            out.append('| %s | %d | %s | %s | %s | %s | %s | %.2f | %.2f | %.2f | %.0f |' % (
                model, rs[0]['surfels'], mode, pct(np.mean(cov)), pct(min(cov)), pct(np.mean(outs)), pct(max(outs)),
                np.mean([r['psnr_y'] for r in rs]), np.mean([r['psnr_rgb'] for r in rs]),
                np.mean([r['psnr_y_inner'] for r in rs]),
                np.mean([r['ms_per_frame'] for r in rs])))
        # Targets.
        for mode in ('threepass', 'onepass'):
            rs = [r for r in base if r['model'] == model and r['mode'] == mode]
            if rs:
                ok_cov = all(r['coverage'] >= COVERAGE_TARGET for r in rs)
                ok_out = all(r['outside'] <= OUTSIDE_TARGET for r in rs)
                verdicts.append('- %s, %s: coverage ≥ 99.5 %% in every view: **%s** (worst %s); outside ≤ 0.5 %% in '
                                'every view: **%s** (worst %s)' % (
                                    model, mode, 'holds' if ok_cov else 'MISSED', pct(min(r['coverage'] for r in rs)),
                                    'holds' if ok_out else 'MISSED', pct(max(r['outside'] for r in rs))))
        by = {(r['mode'], r['view']): r['psnr_y'] for r in base if r['model'] == model}
        views = sorted({r['view'] for r in base if r['model'] == model})
        if all((m, v) in by for m in ('threepass', 'onepass', 'points') for v in views):
            wins_one = sum(by[('threepass', v)] > by[('onepass', v)] for v in views)
            wins_pts = sum(by[('threepass', v)] > by[('points', v)] for v in views)
            verdicts.append('- %s: three-pass PSNR (Y) higher than one-pass in %d/%d views, than points in %d/%d views: '
                            '**%s**' % (model, wins_one, len(views), wins_pts, len(views),
                                        'holds' if wins_one == len(views) == wins_pts else 'MISSED'))
    out.append('')
    out.append('## Targets\n')
    out += verdicts
    out.append('')
    out.append('## Every view (default settings)\n')
    out.append('| model | view (azimuth/elevation) | mode | coverage | coverage (strict) | holes (px) | outside '
               '| outside (strict) | PSNR Y | PSNR RGB | PSNR Y inside | ms/frame |')
    out.append('|---|---|---|---|---|---|---|---|---|---|---|---|')
    for r in base:
        if r['mode'] == 'mesh':
            continue
        out.append('| %s | %s | %s | %s | %s | %d | %s | %s | %.2f | %.2f | %.2f | %.0f |' % (
            r['model'], r['view'], r['mode'], pct(r['coverage'], 3), pct(r['coverage_strict'], 3), r['holes_px'],
            pct(r['outside'], 3), pct(r['outside_strict'], 3), r['psnr_y'], r['psnr_rgb'], r['psnr_y_inner'],
            r['ms_per_frame']))
    variants = [r for r in rows if r['variant'] != '']
    if variants:
        out.append('')
        out.append('## Parameter variations (same views; mean over views, worst view in brackets)\n')
        out.append('| model | mode | settings | coverage | outside | PSNR Y | PSNR Y inside | ms/frame |')
        out.append('|---|---|---|---|---|---|---|---|')
        keys = []
        for r in rows:
            k = (r['model'], r['mode'], r['variant'])
            if r['mode'] != 'mesh' and k not in keys:
                keys.append(k)
        for model, mode, variant in keys:
            rs = [r for r in rows if (r['model'], r['mode'], r['variant']) == (model, mode, variant)]
            out.append('| %s | %s | %s | %s (%s) | %s (%s) | %.2f | %.2f | %.0f |' % (
                model, mode, variant or 'defaults', pct(np.mean([r['coverage'] for r in rs])),
                pct(min(r['coverage'] for r in rs)), pct(np.mean([r['outside'] for r in rs]), 3),
                pct(max(r['outside'] for r in rs), 3), np.mean([r['psnr_y'] for r in rs]),
                np.mean([r['psnr_y_inner'] for r in rs]), np.mean([r['ms_per_frame'] for r in rs])))
    notes_path = os.path.join(workdir, 'notes.md')
    if os.path.exists(notes_path):
        out.append('')
        out.append(open(notes_path).read().rstrip())
    with open(md_path, 'w') as f:
        f.write('\n'.join(out) + '\n')


# ---------------------------------------------------------------------------------------------
# montage: panels side by side with a title above each (matplotlib, Agg).
def montage(out_path, panels, crop=False, panel_px=640):
    images = [(title, mpimg.imread(path)[:, :, :3]) for title, path in panels]
    if crop:  # common crop to the union of the non-white areas, plus a margin, kept square
        non_white = np.zeros(images[0][1].shape[:2], dtype=bool)
        for _, im in images:
            non_white |= (im < 0.99).any(axis=2)
        ys, xs = np.nonzero(non_white)
        cy, cx = (ys.min() + ys.max()) / 2, (xs.min() + xs.max()) / 2
        half = int(max(ys.max() - ys.min(), xs.max() - xs.min()) * 0.54) + 1
        h, w = non_white.shape
        half = min(half, h // 2, w // 2)
        y0 = int(min(max(cy - half, 0), h - 2 * half))
        x0 = int(min(max(cx - half, 0), w - 2 * half))
        images = [(t, im[y0:y0 + 2 * half, x0:x0 + 2 * half]) for t, im in images]
    dpi = 100
    n = len(images)
    fig = plt.figure(figsize=(n * panel_px / dpi, (panel_px + 40) / dpi), dpi=dpi, facecolor='white')
    for k, (title, im) in enumerate(images):
        ax = fig.add_axes([k / n, 0, 1 / n, panel_px / (panel_px + 40)])
        ax.imshow(im, interpolation='lanczos' if im.shape[0] > panel_px else 'nearest')
        ax.set_axis_off()
        fig.text((k + 0.5) / n, 1 - 20 / (panel_px + 40), title, ha='center', va='center', fontsize=14)
    fig.savefig(out_path, dpi=dpi, facecolor='white')
    plt.close(fig)


def main(argv):
    if len(argv) >= 2 and argv[1] == 'frame' and len(argv) == 6:
        frame(*argv[2:])
    elif len(argv) >= 2 and argv[1] == 'colorize' and len(argv) == 5:
        colorize(*argv[2:])
    elif len(argv) >= 2 and argv[1] == 'metrics' and len(argv) == 5:
        metrics(*argv[2:])
    elif len(argv) >= 4 and argv[1] == 'montage':
        crop = '--crop' in argv
        sizes = [int(a.split('=', 1)[1]) for a in argv[3:] if a.startswith('--panel=')]
        panels = [a.split('=', 1) for a in argv[3:] if a != '--crop' and not a.startswith('--panel=')]
        montage(argv[2], panels, crop=crop, panel_px=sizes[-1] if sizes else 640)
    else:
        print(__doc__, file=sys.stderr)
        return 2
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))
