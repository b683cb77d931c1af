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
    # Layouts the seeds above missed (binary_compressed PCD crashed PCL's reader before we checked its sizes).
    yield 'binary_be.ply', PLY, text([h.replace('ascii', 'binary_big_endian') for h in header]) + b''.join(
        struct.pack('>3f', *p) for p in VERTICES) + b''.join(struct.pack('>B3i', 3, *f) for f in FACES)
    yield 'points_be.ply', PLY + 6, text([h.replace('little', 'big') for h in points]) + b''.join(
        struct.pack('>3d3Bf', *p, 200, 100, 50, 0.5) for p in VERTICES)
    lists = ['ply', 'format binary_little_endian 1.0', 'comment lists everywhere', 'obj_info a b',
             'element vertex 4', 'property float x', 'property float y', 'property float z',
             'property list uchar float extra', 'property uchar red', 'element face 2',
             'property list uint uint vertex_index', 'property uchar flags', 'element edge 1',
             'property int vertex1', 'property int vertex2', 'end_header']
    body = b''.join(struct.pack('<3fBffB', *p, 2, 0.5, 0.25, 7) for p in VERTICES)
    body += struct.pack('<I4IB', 4, 0, 1, 2, 3, 1) + struct.pack('<I3IB', 3, 0, 2, 3, 0) + struct.pack('<2i', 0, 1)
    yield 'lists.ply', PLY, text(lists) + body
    lists_ascii = [h.replace('binary_little_endian', 'ascii') for h in lists]
    yield 'lists_ascii.ply', PLY + 6, text(lists_ascii + ['%s 2 0.5 0.25 7' % p for p in v] +
                                           ['4 0 1 2 3 1', '3 0 2 3 0', '0 1'])
    grid = ['ply', 'format binary_little_endian 1.0', 'obj_info num_cols 2', 'obj_info num_rows 2',
            'element vertex 3', 'property float x', 'property float y', 'property float z', 'property float confidence',
            'property float intensity', 'element range_grid 4', 'property list uchar int vertex_indices', 'end_header']
    body = b''.join(struct.pack('<5f', *p, 1.0, 0.5) for p in VERTICES[:3])
    body += struct.pack('<Bi', 1, 0) + struct.pack('<B', 0) + struct.pack('<Bi', 1, 1) + struct.pack('<Bi', 1, 2)
    yield 'range_grid.ply', PLY + 6, text(grid) + body
    yield 'normals.ply', PLY + 6, text(['ply', 'format ascii 1.0', 'element vertex 4'] +
                                       ['property float %s' % n for n in ('x', 'y', 'z', 'nx', 'ny', 'nz')] +
                                       ['property uchar intensity', 'end_header'] + ['%s 0 0 1 9' % p for p in v])
    yield 'binary_solid.stl', STL, b'solid binary header'.ljust(80, b' ') + struct.pack('<I', len(FACES)) + b''.join(
        struct.pack('<12fH', *normal(f), *(c for i in f for c in VERTICES[i]), 0) for f in FACES)
    yield 'crlf.stl', STL, text(['solid t'] + ['facet normal 0 0 0\r\nouter loop\r\n%s\r\nendloop\r\nendfacet' % (
        '\r\n'.join('vertex %g %g %g' % VERTICES[i] for i in f)) for f in FACES] + ['endsolid t'])
    yield 'full.obj', OBJ + 6, text(['# comment', 'mtllib x.mtl', 'o thing', 'g group'] + ['v %s 1' % p for p in v] +
                                    ['v 1 1 1 0.5 0.5 0.5', 'vt 0 0', 'vt 1 0 0', 'vn 0 0 1', 'usemtl m', 's 1',
                                     'f 1/1/1 2/2/1 3/1/1', 'f 1/1 3/2 4/1', 'f -1 -2 -3 -4', 'l 1 2']).replace(b'\n', b'\r\n')
    yield 'colors.off', OFF, text(['COFF', '# comment', '4 2 0'] + ['%s 255 0 0 255' % p for p in v] +
                                  ['4 0 1 2 3 1 0 0', '3 0 2 3'])
    yield 'inline.off', OFF + 6, text(['NOFF 4 1 0'] + ['%s 0 0 1' % p for p in v] + ['3 0 1 2'])
    yield 'stcn.off', OFF, text(['STCNOFF', '4 1 6'] + ['%s 0 0 1 1 0 0 1 0 0' % p for p in v] + ['3 0 1 2'])

    def lzf_literal(data):  # a valid LZF stream of literal runs only (at most 32 bytes each)
        return b''.join(bytes([len(data[i:i + 32]) - 1]) + data[i:i + 32] for i in range(0, len(data), 32))

    def compressed(columns):  # binary_compressed: the fields' columns one after the other, LZF, two sizes
        raw = b''.join(columns)
        packed = lzf_literal(raw)
        return b'DATA binary_compressed\n' + struct.pack('<II', len(packed), len(raw)) + packed
    columns = [struct.pack('<4f', *(p[k] for p in VERTICES)) for k in range(3)] + [struct.pack('<4f', *[1.0] * 4)]
    yield 'compressed.pcd', PCD, text(pcd) + compressed(columns)
    organized = ['VERSION 0.7', 'FIELDS x y z rgb', 'SIZE 4 4 4 4', 'TYPE F F F U', 'COUNT 1 1 1 1', 'WIDTH 2',
                 'HEIGHT 2', 'VIEWPOINT 1 2 3 1 0 0 0', 'POINTS 4']
    rgb = [0x00ff0000, 0x0000ff00, 0x000000ff, 0x00ffffff]
    nan = float('nan')
    opoints = VERTICES[:3] + [(nan, nan, nan)]
    yield 'organized.pcd', PCD + 6, text(organized + ['DATA binary']) + b''.join(
        struct.pack('<3fI', *p, c) for p, c in zip(opoints, rgb))
    columns = [struct.pack('<4f', *(p[k] for p in opoints)) for k in range(3)] + [struct.pack('<4I', *rgb)]
    yield 'organized_compressed.pcd', PCD, text(organized) + compressed(columns)
    yield 'organized_ascii.pcd', PCD + 6, text(organized + ['DATA ascii'] + ['%g %g %g %d' % (p + (c,))
                                                                             for p, c in zip(opoints, rgb)])
    padded = ['# .PCD v0.7', 'VERSION 0.7', 'FIELDS x y z _ normal_x normal_y normal_z intensity', 'SIZE 4 4 4 1 4 4 4 2',
              'TYPE F F F U F F F U', 'COUNT 1 1 1 3 1 1 1 1', 'WIDTH 4', 'HEIGHT 1', 'POINTS 4', 'DATA binary']
    yield 'padded.pcd', PCD + 6, text(padded) + b''.join(struct.pack('<3f3B3fH', *p, 0, 0, 0, 0, 0, 1, 3)
                                                       for p in VERTICES)
    yield 'counts.pcd', PCD, text(['VERSION .7', 'FIELDS x y z fpfh', 'SIZE 4 4 4 4', 'TYPE F F F F', 'COUNT 1 1 1 2',
                                   'WIDTH 4', 'HEIGHT 1', 'POINTS 4', 'DATA ascii'] + ['%s 0.5 0.25' % p for p in v])
    yield 'double_compressed.pcd', PCD + 6, text(double[:-1]) + compressed(
        [struct.pack('<4d', *(p[k] for p in VERTICES)) for k in range(3)])
    yield 'blanks.xyz', XYZ, text(['# header', '', '  %g\t%g   %g  # comment' % VERTICES[0]] +
                                  ['%s\r' % p for p in v[1:]] + ['+1e0 -0 .5'])
    yield 'normals.xyz', XYZ + 6, text(['%s 0 0 1' % p for p in v])


def main():
    out = sys.argv[1]
    os.makedirs(out, exist_ok=True)
    for name, selector, body in seeds():
        with open(os.path.join(out, name), 'wb') as f:
            f.write(bytes([selector]) + body)


if __name__ == '__main__':
    main()
