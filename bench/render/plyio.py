"""Minimal binary little-endian PLY vertex reader/writer (numpy only) for the render benchmark."""
import numpy as np

_TYPES = {'float': 'f4', 'float32': 'f4', 'double': 'f8', 'float64': 'f8', 'uchar': 'u1', 'uint8': 'u1',
          'char': 'i1', 'int8': 'i1', 'short': 'i2', 'int16': 'i2', 'ushort': 'u2', 'uint16': 'u2',
          'int': 'i4', 'int32': 'i4', 'uint': 'u4', 'uint32': 'u4'}


def read_header(path):
    with open(path, 'rb') as f:
        lines = []
        while True:
            line = f.readline()
            if not line:
                raise ValueError(path + ': no end_header')
            line = line.decode('ascii').strip()
            lines.append(line)
            if line == 'end_header':
                return lines, f.tell()


def read_vertices(path):
    """The first element, 'vertex', as a numpy structured array (binary little endian only)."""
    lines, offset = read_header(path)
    if 'format binary_little_endian 1.0' not in lines:
        raise ValueError(path + ': only binary little-endian PLY is supported')
    count, fields, in_vertex = None, [], False
    for line in lines:
        words = line.split()
        if words[:1] == ['element']:
            if in_vertex:
                break
            in_vertex = words[1] == 'vertex'
            if in_vertex:
                count = int(words[2])
        elif words[:1] == ['property'] and in_vertex:
            if words[1] == 'list':
                raise ValueError(path + ': list property in vertex element')
            fields.append((words[2], '<' + _TYPES[words[1]]))
    return np.fromfile(path, dtype=np.dtype(fields), count=count, offset=offset), lines


def write_vertices(path, vertices, header_lines):
    """Writes `vertices` (same dtype as read) with the original header, vertex count replaced; no other element."""
    out = []
    for line in header_lines:
        if line.startswith('element vertex'):
            line = 'element vertex %d' % len(vertices)
        out.append(line)
    with open(path, 'wb') as f:
        f.write(('\n'.join(out) + '\n').encode('ascii'))
        vertices.tofile(f)
