"""The records of a binary .surfel file written by the resampler (version 3: 68 bytes each, 16
floats then the colour), for the filter tests: x y z nx ny nz radius major(3) minor(3) quality
blend_scale fit_offset (docs/surfel_format.md)."""
import struct

BLEND_SCALE, FIT_OFFSET = 14, 15


def records(path):
    data = open(path, "rb").read()
    assert b"comment gaussphere-surfel 3\n" in data, path
    body = data[data.index(b"end_header\n") + 11:]
    return [struct.unpack_from("<16f", body, r) for r in range(0, len(body), 68)]
