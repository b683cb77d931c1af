#!/usr/bin/env python3
"""Writes the seed corpus for fuzz_input_files: small valid mesh and scan files of every format and layout
the readers take, each behind the byte that picks its reader (format index; + 6 flips the loader option).

    make_input_corpus.py DIR
"""
import os
import struct
import sys

OBJ, OFF, PLY, STL, PCD, XYZ = range(6)
VERTICES = [(0.0, 0.0, 0.0), (1.0, 0.0, 0.0), (0.0, 1.0, 0.0), (0.0, 0.0, 1.0)]
FACES = [(0, 2, 1), (0, 1, 3), (0, 3, 2), (1, 2, 3)]


def normal(face):
    a, b, c = (VERTICES[i] for i in face)
    u = [b[k] - a[k] for k in range(3)]
    v = [c[k] - a[k] for k in range(3)]
    return (u[1] * v[2] - u[2] * v[1], u[2] * v[0] - u[0] * v[2], u[0] * v[1] - u[1] * v[0])


def text(lines):
    return ('\n'.join(lines) + '\n').encode()


def seeds():
    v = ['%g %g %g' % p for p in VERTICES]
    yield 'tetra.obj', OBJ, text(['v ' + p for p in v] + ['vn 0 0 1'] + ['f %d//1 %d//1 %d//1' % tuple(i + 1 for i in f)
                                                                        for f in FACES])
    yield 'quad.obj', OBJ, text(['v ' + p for p in v] + ['f 1 2 3 4', 'f -1 -2 -3'])
    yield 'tetra.off', OFF, text(['OFF', '4 4 0'] + v + ['3 %d %d %d' % f for f in FACES])
    header = ['ply', 'format ascii 1.0', 'element vertex 4', 'property float x', 'property float y',
              'property float z', 'element face 4', 'property list uchar int vertex_indices', 'end_header']
    yield 'ascii.ply', PLY, text(header + v + ['3 %d %d %d' % f for f in FACES])
    binary = [h.replace('ascii', 'binary_little_endian') for h in header]
    body = b''.join(struct.pack('<3f', *p) for p in VERTICES) + b''.join(struct.pack('<B3i', 3, *f) for f in FACES)
    yield 'binary.ply', PLY, text(binary) + body
    points = ['ply', 'format binary_little_endian 1.0', 'element vertex 4', 'property double x', 'property double y',
              'property double z', 'property uchar red', 'property uchar green', 'property uchar blue',
              'property float intensity', 'end_header']
    yield 'points.ply', PLY + 6, text(points) + b''.join(struct.pack('<3d3Bf', *p, 200, 100, 50, 0.5) for p in VERTICES)
    yield 'ascii.stl', STL, text(['solid t'] + ['facet normal %g %g %g\nouter loop\n%s\nendloop\nendfacet' % (
        normal(f) + ('\n'.join('vertex %g %g %g' % VERTICES[i] for i in f),)) for f in FACES] + ['endsolid t'])
    yield 'binary.stl', STL, b'\0' * 80 + struct.pack('<I', len(FACES)) + b''.join(
        struct.pack('<12fH', *normal(f), *(c for i in f for c in VERTICES[i]), 0) for f in FACES)
    pcd = ['VERSION .7', 'FIELDS x y z intensity', 'SIZE 4 4 4 4', 'TYPE F F F F', 'COUNT 1 1 1 1', 'WIDTH 4',
           'HEIGHT 1', 'VIEWPOINT 0 0 0 1 0 0 0', 'POINTS 4']
    yield 'ascii.pcd', PCD, text(pcd + ['DATA ascii'] + ['%s 1' % p for p in v])
    yield 'binary.pcd', PCD, text(pcd + ['DATA binary']) + b''.join(struct.pack('<4f', *p, 1.0) for p in VERTICES)
    double = ['VERSION .7', 'FIELDS x y z', 'SIZE 8 8 8', 'TYPE F F F', 'COUNT 1 1 1', 'WIDTH 2', 'HEIGHT 2',
              'VIEWPOINT 0 0 0 1 0 0 0', 'POINTS 4', 'DATA binary']
    yield 'organized_double.pcd', PCD + 6, text(double) + b''.join(struct.pack('<3d', *p) for p in VERTICES)
    yield 'points.xyz', XYZ, text(v + ['nan nan nan'])
    yield 'normals.xyz', XYZ + 6, text(['%s 0 0 1' % p for p in v])


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, selector, body in seeds():
        with open(os.path.join(out, name), 'wb') as f:
            f.write(bytes([selector]) + body)


if __name__ == '__main__':
    main()
