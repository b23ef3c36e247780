# The shipped resample-then-reconstruct script on the bunny: the resampling, then MeshLab's
# Screened Poisson on the surfels. The result is a surface of thousands of triangles within the bunny's box grown by a tenth of its
# size (a reconstruction that ignored the samples would fill Screened Poisson's cube, 1.1 times
# larger).
source "$E2E_COMMON"
"$RUN_MESHLABSERVER" -i "$SAMPLE_DIR/bunny.ply" -s "$SAMPLE_DIR/resample_and_reconstruct.mlx" \
  -o reconstructed.ply > reconstruct.log 2>&1
grep -q "34834 points -> [0-9]* surfels" reconstruct.log
# The bunny is open at its base: the surfels along that rim stay unfitted, and the log counts them.
grep -q "point(s) on or beside the rim of an open surface: their surfels are not fitted" reconstruct.log
python3 - "$SAMPLE_DIR/bunny.ply" reconstructed.ply <<'PY'
import struct, sys

def read_vertices(path):
    data = open(path, "rb").read()
    head, body = data.split(b"end_header\n", 1)
    lines = head.decode().split("\n")
    count, props, faces, in_vertex = 0, [], 0, False
    for line in lines:
        words = line.split()
        if words[:2] == ["element", "vertex"]:
            count, in_vertex = int(words[2]), True
        elif words[:1] == ["element"]:
            in_vertex = False
            if words[1] == "face":
                faces = int(words[2])
        elif words[:1] == ["property"] and in_vertex:
            props.append(words[1])
    assert all(p in ("float", "uchar") for p in props), props
    size = sum(4 if p == "float" else 1 for p in props)
    fmt = "<" + "".join("f" if p == "float" else "B" for p in props)
    points = [struct.unpack_from(fmt, body, i * size)[:3] for i in range(count)]
    return points, faces

bunny, _ = read_vertices(sys.argv[1])
mesh, faces = read_vertices(sys.argv[2])
low = [min(p[a] for p in bunny) for a in range(3)]
high = [max(p[a] for p in bunny) for a in range(3)]
margin = [0.1 * (h - l) for l, h in zip(low, high)]
outside = sum(any(p[a] < low[a] - margin[a] or p[a] > high[a] + margin[a] for a in range(3)) for p in mesh)
print(f"reconstruction: {len(mesh)} vertices, {faces} triangles, {outside} vertices outside the bunny's grown box")
sys.exit(0 if faces > 5000 and outside == 0 else 1)
PY
