#!/usr/bin/env bash
# scripts/gstile_dask.py on a Dask scheduler and two worker processes over TCP on 127.0.0.1
# (dask-scheduler, dask-worker of Debian's python3-distributed), against the sequential tiled run
# of the same tile directory:
#   1. the output is identical (cmp);
#      With a target count the driver's first rounds probe the tiles and the shares follow; the
#      output is identical to the sequential probe, share, run, adjust (and runs again) and merge;
#   2. one worker killed (SIGKILL) in the middle of the run: its task runs again on the other
#      worker, and the output is still identical;
#   3. --resume runs only the tiles a stopped run left without a result, with the same output;
#   4. a tile whose core file is damaged stops the run with an error naming the tile.
# Each task runs gstile through a wrapper that sleeps 0.5 s first, and worker 1 is killed when the
# first tile is done: both workers are then busy with the next ones. Environment: GSTILE, DRIVER (scripts/gstile_dask.py), INPUT, WORK_DIR.
set -euo pipefail
rm -rf "$WORK_DIR" && mkdir -p "$WORK_DIR" && cd "$WORK_DIR"
pids=()
# SIGKILL: a worker told to stop gracefully waits for a scheduler that may be gone already.
cleanup() { for pid in "${pids[@]}"; do kill -9 "$pid" 2>/dev/null || true; done; }
trap cleanup EXIT

"$GSTILE" split "$INPUT" tiles --tile-points 20000 > split.log
for id in $("$GSTILE" tiles tiles); do "$GSTILE" run tiles "$id" > /dev/null; done
"$GSTILE" merge tiles sequential.surfel > /dev/null
printf '#!/bin/sh\nsleep 0.5\nexec %q "$@"\n' "$GSTILE" > slow_gstile && chmod +x slow_gstile

port=$(/usr/bin/python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
scheduler=tcp://127.0.0.1:$port
dask-scheduler --host 127.0.0.1 --port "$port" --no-dashboard > scheduler.log 2>&1 & pids+=($!)
start_worker() { # a worker without a nanny: killing it loses it, as a crashed machine would
  dask-worker "$scheduler" --host 127.0.0.1 --nthreads 1 --no-nanny --no-dashboard > "worker$1.log" 2>&1 &
  pids+=($!)
}
start_worker 1; worker1=${pids[-1]}
start_worker 2
for _ in $(seq 60); do grep -q "Registered to" worker1.log worker2.log 2>/dev/null &&
  [ "$(grep -l 'Registered to' worker1.log worker2.log | wc -l)" = 2 ] && break; sleep 0.5; done

run_driver() { # OUTPUT: the driver against the scheduler, each tile's result removed first
  rm -f tiles/tile_*.surfel tiles/tile_*.border tiles/tile_*.spare
  /usr/bin/python3 "$DRIVER" tiles "$1" --scheduler "$scheduler" --gstile "$PWD/slow_gstile"
}
failures=0
check() { if "${@:2}"; then echo "ok: $1"; else echo "FAILED: $1"; failures=$((failures + 1)); fi; }

run_driver two_workers.surfel > two_workers.log
check "two workers: identical to the sequential run" cmp sequential.surfel two_workers.surfel

"$GSTILE" split "$INPUT" target_tiles --tile-points 20000 --target 3000 > /dev/null
while ids=$("$GSTILE" tiles target_tiles --to-probe) && [ -n "$ids" ]; do
  for id in $ids; do "$GSTILE" probe target_tiles "$id" > /dev/null; done
done
"$GSTILE" share target_tiles > /dev/null
for id in $("$GSTILE" tiles target_tiles); do "$GSTILE" run target_tiles "$id" > /dev/null; done
while "$GSTILE" adjust target_tiles > /dev/null && [ -n "$("$GSTILE" tiles target_tiles --pending)" ]; do
  for id in $("$GSTILE" tiles target_tiles --pending); do "$GSTILE" run target_tiles "$id" > /dev/null; done
done
"$GSTILE" merge target_tiles target_sequential.surfel > /dev/null
rm -f target_tiles/tile_*.{surfel,border,spare,probe,kept} target_tiles/shares.json
/usr/bin/python3 "$DRIVER" target_tiles target_dask.surfel --scheduler "$scheduler" --gstile "$PWD/slow_gstile" > target.log
check "a target: the probe rounds, then identical to the sequential run" cmp target_sequential.surfel target_dask.surfel
check "a target: every tile probed" grep -q "probe $("$GSTILE" tiles target_tiles | wc -l)/.* done |" target.log
check "a target: tiles that missed their share ran again" grep -q "^\[adjust\] .* [1-9][0-9]* tile(s) to run again" target.log

run_driver killed.surfel > killed.log &
driver=$!
for _ in $(seq 200); do grep -q "done |" killed.log 2>/dev/null && break; sleep 0.1; done
kill -9 "$worker1"
echo "killed worker 1 (pid $worker1) after $(grep -c 'done |' killed.log) tile(s) done"
wait "$driver"
check "a worker killed mid-run: still identical" cmp sequential.surfel killed.surfel
check "the scheduler lost the worker" grep -q "Remove worker" scheduler.log
n=$("$GSTILE" tiles tiles | wc -l)
check "every tile done" grep -q "$n/$n done |" killed.log

# --resume: two results lost (a level run), one tile's outcome lost (a target run): only those run.
for id in $("$GSTILE" tiles tiles | sed -n '2p;4p'); do rm "tiles/tile_$(printf %06d "$id").surfel"; done
/usr/bin/python3 "$DRIVER" tiles resumed.surfel --resume --scheduler "$scheduler" --gstile "$PWD/slow_gstile" > resumed.log
check "--resume: identical" cmp sequential.surfel resumed.surfel
check "--resume: only the two tiles without a result ran" test "$(grep -c '^\[dask\] run ' resumed.log)" = 2
rm "target_tiles/tile_$(printf %06d "$("$GSTILE" tiles target_tiles | sed -n 3p)").kept"
/usr/bin/python3 "$DRIVER" target_tiles target_resumed.surfel --resume --scheduler "$scheduler" \
  --gstile "$PWD/slow_gstile" > target_resumed.log
check "--resume with a target: identical" cmp target_sequential.surfel target_resumed.surfel
check "--resume with a target: no probe again, one tile ran" \
  test "$(grep -c '^\[dask\] probe ' target_resumed.log) $(grep -c '^\[dask\] run ' target_resumed.log)" = "0 1"

first=$("$GSTILE" tiles tiles | sed -n 3p)
printf '\x7f' | dd of="tiles/tile_$(printf %06d "$first").core" bs=1 seek=40 conv=notrunc status=none
set +e
run_driver corrupt.surfel > corrupt.log 2> corrupt.err
status=$?
set -e
cat corrupt.err
check "a damaged tile fails the run" test "$status" -ne 0
check "the error names the tile" grep -q "tile $first failed: tile $first: .*corrupt" corrupt.err
exit $((failures > 0))
