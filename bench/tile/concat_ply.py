#!/usr/bin/python3
"""Concatenates binary PLY point files of one layout (a single vertex element) into one:

    concat_ply.py OUTPUT.ply INPUT.ply...

The header is the first input's with the summed vertex count; the bodies are copied in order,
1 MiB at a time. For a scan larger than a generator can hold in memory: several samplings of the
same model, each generated with its own seed."""
import re
import shutil
import sys


def read_header(path):
    with open(path, "rb") as f:
        header = b""
        while not header.endswith(b"end_header\n"):
            line = f.readline()
            if not line:
                sys.exit(f"concat_ply: {path}: no end_header")
            header += line
    count = int(re.search(rb"element vertex (\d+)\n", header).group(1))
    return header, count


def main():
    output, inputs = sys.argv[1], sys.argv[2:]
    headers = [read_header(p) for p in inputs]
    layouts = {re.sub(rb"element vertex \d+\n", b"", h) for h, _ in headers}
    if len(layouts) != 1:
        sys.exit("concat_ply: the inputs' headers differ")
    total = sum(c for _, c in headers)
    with open(output, "wb") as out:
        out.write(re.sub(rb"element vertex \d+\n", b"element vertex %d\n" % total, headers[0][0]))
        for path, (header, _) in zip(inputs, headers):
            with open(path, "rb") as f:
                f.seek(len(header))
                shutil.copyfileobj(f, out, 1 << 20)
    print(f"wrote {total} points to {output}")


if __name__ == "__main__":
    main()
