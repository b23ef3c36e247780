#!/usr/bin/python3
"""Tiled resampling on a Dask cluster: one task per tile of a tile directory, then the merge.

    scripts/gstile_dask.py TILEDIR OUTPUT.surfel|OUTPUT.ply [--scheduler ADDRESS]
                           [--input INPUT.ply [--split-args "..."] | --resume] [--gstile PATH]

With --input the input is split into TILEDIR first (`gstile split`, on this machine); else
TILEDIR holds a split already. With a target count in the split, rounds of tasks run `gstile
probe TILEDIR ID` on the tiles `gstile tiles TILEDIR --to-probe` lists until it lists none (the
level search, then the splits' priorities at the level), this machine `gstile share TILEDIR`,
and after the runs `gstile adjust TILEDIR` shares the rounds of exchanges (the first time), the
crease fit limits (the second), takes the seam step (once no tile is left to run: every tile runs
again beside the surfels its neighbours keep) and gives the tiles that missed their share a new
count; the tiles it lists run again (docs/tiling.md). Each task runs `gstile run TILEDIR ID` on a worker, which must see
TILEDIR and the gstile binary at the same paths (a shared folder). Without --scheduler a local
cluster of --workers processes is started. A worker lost in the middle of a task is replaced by
the scheduler, which runs the task again elsewhere (a tile's result appears only once complete,
so a lost run leaves nothing half-written, and a run is deterministic, so the output does not
change). A tile that fails (bad data, a tile file damaged) stops the run with an error naming the
tile. --resume continues a run that stopped (the driver's machine lost, the cluster shut down):
it probes only what the probes on disk lack, keeps the shares if written, and runs only the tiles
`gstile tiles TILEDIR --pending` lists; a finished tile is not run again. Without it, a target run
over a split already there starts over from the probes. Debian's python3-distributed
(scripts/setup.sh installs it); /usr/bin/python3 is Debian's.
"""
import argparse
import json
import os
import shlex
import subprocess
import sys

from distributed import Client, LocalCluster, as_completed

HERE = os.path.dirname(os.path.abspath(__file__))
DEFAULT_GSTILE = os.path.join(HERE, "..", "build", "tools", "gstile", "gstile")


class TileFailed(Exception):
    """A tile's run ended with an error; the message names the tile."""


def run_tile(gstile, command, tile_dir, tile_id, threads):
    """The task: one `gstile run` (or `probe`), its figures line on success."""
    env = dict(os.environ, OMP_NUM_THREADS=str(threads))
    proc = subprocess.run([gstile, command, tile_dir, str(tile_id)], capture_output=True, text=True, env=env)
    if proc.returncode != 0:
        reason = proc.stderr.strip().replace("gstile: error: ", "") or f"exit status {proc.returncode}"
        raise TileFailed(f"tile {tile_id} failed: {reason}")
    return proc.stdout.strip()


def parse_arguments():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("tile_dir")
    parser.add_argument("output")
    parser.add_argument("--scheduler", help="address of a running scheduler, e.g. tcp://127.0.0.1:8786")
    parser.add_argument("--workers", type=int, default=2, help="local cluster: worker processes (2)")
    parser.add_argument("--threads", type=int, default=1, help="OpenMP threads of each tile's run (1)")
    parser.add_argument("--input", help="split this PLY into TILE_DIR first")
    parser.add_argument("--split-args", default="", help='options of `gstile split`, e.g. "--tile-points 2000000"')
    parser.add_argument("--gstile", default=DEFAULT_GSTILE, help="the gstile binary (the build's)")
    parser.add_argument("--resume", action="store_true",
                        help="run only what a stopped run left undone in TILE_DIR (no split)")
    return parser.parse_args()


def check_call(command):
    if subprocess.run(command).returncode != 0:
        sys.exit(f"gstile_dask: error: {' '.join(map(shlex.quote, command))} failed")


def read_manifest(tile_dir):
    with open(os.path.join(tile_dir, "manifest.json")) as manifest:
        return json.load(manifest)


def run_tiles(client, gstile, command, tile_dir, ids, threads, round_number=0):
    """Submits every tile, prints each one's line as it completes; stops at the first failure.
    A tile probed or run again (the next probe round, after `gstile adjust`) is a new task (its
    round in the key)."""
    if not ids:
        return
    futures = [client.submit(run_tile, gstile, command, tile_dir, i, threads, key=f"gstile-{command}-{i}-{round_number}",
                             pure=False)
               for i in ids]
    done = 0
    for future in as_completed(futures):
        try:
            line = future.result()
        except TileFailed as failure:
            client.cancel(futures)
            sys.exit(f"gstile_dask: error: {failure}")
        done += 1
        print(f"[dask] {command} {done}/{len(ids)} done | {line}", flush=True)


def listed_tiles(gstile, tile_dir, which):
    """`gstile tiles TILEDIR --pending` (the tiles whose result is missing or out of date: after
    `gstile adjust`, those to run again) or `--to-probe` (those whose probe lacks what the share needs)."""
    proc = subprocess.run([gstile, "tiles", tile_dir, which], capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f"gstile_dask: error: {proc.stderr.strip()}")
    return [int(line) for line in proc.stdout.split()]


def main():
    args = parse_arguments()
    if args.resume and args.input:
        sys.exit("gstile_dask: error: --resume continues the split already in TILE_DIR; --input would split anew")
    gstile = os.path.abspath(args.gstile)
    tile_dir = os.path.abspath(args.tile_dir)
    if args.input:
        check_call([gstile, "split", args.input, tile_dir] + shlex.split(args.split_args))
    manifest = read_manifest(tile_dir)
    ids = [tile["id"] for tile in manifest["tiles"]]
    cluster = None
    if args.scheduler:
        client = Client(args.scheduler)
    else:
        cluster = LocalCluster(n_workers=args.workers, threads_per_worker=1, processes=True, dashboard_address=None)
        client = Client(cluster)
    print(f"[dask] {len(ids)} tiles on {len(client.scheduler_info()['workers'])} worker(s) of {client.scheduler.address}",
          flush=True)
    try:
        if manifest["target_count"] > 0:
            if not args.resume:
                for name in [f"tile_{i:06d}.probe" for i in ids] + ["shares.json"]:
                    if os.path.exists(os.path.join(tile_dir, name)):
                        os.remove(os.path.join(tile_dir, name))
            probe_round = 0
            while to_probe := listed_tiles(gstile, tile_dir, "--to-probe"):
                run_tiles(client, gstile, "probe", tile_dir, to_probe, args.threads, probe_round)
                probe_round += 1
            check_call([gstile, "share", tile_dir])
        run_tiles(client, gstile, "run", tile_dir, listed_tiles(gstile, tile_dir, "--pending") if args.resume else ids,
                  args.threads)
        round_number = 0
        while manifest["target_count"] > 0:
            check_call([gstile, "adjust", tile_dir])
            ids = listed_tiles(gstile, tile_dir, "--pending")
            if not ids:
                break
            round_number += 1
            run_tiles(client, gstile, "run", tile_dir, ids, args.threads, round_number)
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
    check_call([gstile, "merge", tile_dir, args.output])


if __name__ == "__main__":
    main()
