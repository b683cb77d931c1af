#!/usr/bin/env python3
"""How far the facets of each smooth shared mesh lie from a smooth surface through its vertices (issue 13
point 3: where the default file misses Draco's bytes).

  bench/facet_floor.py [BUILD_DIR]   (default: build; needs bench_format and bench/results/meshes.tsv)
  -> bench/results/facet_floor.md

A mesh is flat between its vertices; a code over smooth atoms is not. The smooth surface here is the PN
triangles' (Vlachos et al. 2001: per triangle a cubic Bezier patch from its corners and their area-weighted
normals; it interpolates the vertices), each triangle tessellated into LEVEL^2 flat ones (4, or 2 on meshes
of more than 120k faces). Its Chamfer distance to the mesh (`bench_format mesh`, 200k points a side, / bbox
diagonal) is about the least a smooth surface through the vertices can have: our model's distance cannot
go much below it, whatever its bytes, while Draco codes the facets themselves. Put beside the default file's
Chamfer distance and bytes against Draco from bench/results/meshes.tsv (bench/meshes.sh's run).
"""
import csv
import glob
import json
import math
import os
import subprocess
import sys
import tempfile

from bench_common import HERE, SHARED, run_stamp, write_result
from meshes_report import CAD, loglog


def load_obj(path):
    vertices, faces = [], []
    for line in open(path):
        p = line.split()
        if not p:
            continue
        if p[0] == 'v':
            vertices.append(tuple(float(x) for x in p[1:4]))
        elif p[0] == 'f':
            idx = [int(x.split('/')[0]) - 1 for x in p[1:]]
            faces.extend((idx[0], idx[k], idx[k + 1]) for k in range(1, len(idx) - 1))
    return vertices, faces


def sub(a, b):
    return (a[0] - b[0], a[1] - b[1], a[2] - b[2])


def add(a, b):
    return (a[0] + b[0], a[1] + b[1], a[2] + b[2])


def mul(a, s):
    return (a[0] * s, a[1] * s, a[2] * s)


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def cross(a, b):
    return (a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0])


def write_pn_triangles(vertices, faces, level, out):
    """Writes the PN triangles of the mesh, each tessellated into level^2 triangles, as OBJ to the file out."""
    normals = [(0.0, 0.0, 0.0)] * len(vertices)
    for a, b, c in faces:
        n = cross(sub(vertices[b], vertices[a]), sub(vertices[c], vertices[a]))  # twice the area, as weight
        for v in (a, b, c):
            normals[v] = add(normals[v], n)
    normals = [mul(n, 1.0 / max(1e-300, math.sqrt(dot(n, n)))) for n in normals]
    count = 0
    for face in faces:
        p = [vertices[v] for v in face]
        n = [normals[v] for v in face]

        def edge(i, j):  # the control point on edge i-j next to corner i, in corner i's tangent plane
            return mul(sub(add(mul(p[i], 2.0), p[j]), mul(n[i], dot(sub(p[j], p[i]), n[i]))), 1.0 / 3.0)

        b210, b120, b021, b012, b102, b201 = edge(0, 1), edge(1, 0), edge(1, 2), edge(2, 1), edge(2, 0), edge(0, 2)
        e = mul(add(add(add(b210, b120), add(b021, b012)), add(b102, b201)), 1.0 / 6.0)
        centre = mul(add(add(p[0], p[1]), p[2]), 1.0 / 3.0)
        b111 = add(e, mul(sub(e, centre), 0.5))
        index = {}
        for i in range(level + 1):
            for j in range(level + 1 - i):
                u, v = i / level, j / level
                w = 1.0 - u - v
                terms = ((p[0], u ** 3), (p[1], v ** 3), (p[2], w ** 3), (b210, 3 * u * u * v), (b120, 3 * u * v * v),
                         (b021, 3 * v * v * w), (b012, 3 * v * w * w), (b102, 3 * w * w * u), (b201, 3 * w * u * u),
                         (b111, 6 * u * v * w))
                q = (0.0, 0.0, 0.0)
                for point, weight in terms:
                    q = add(q, mul(point, weight))
                count += 1
                index[(i, j)] = count
                out.write('v %.9g %.9g %.9g\n' % q)
        for i in range(level):
            for j in range(level - i):
                out.write('f %d %d %d\n' % (index[(i, j)], index[(i + 1, j)], index[(i, j + 1)]))
                if i + j < level - 1:
                    out.write('f %d %d %d\n' % (index[(i + 1, j)], index[(i + 1, j + 1)], index[(i, j + 1)]))


def mesh_file(name):
    for folder in ('meshes', 'extra-meshes'):
        found = sorted(glob.glob(os.path.join(SHARED, folder, name + '.*')))
        found = [f for f in found if f.endswith(('.obj', '.off', '.ply'))]
        if found:
            return found[0]
    return None


def main():
    build = sys.argv[1] if len(sys.argv) > 1 else os.path.join(HERE, '..', 'build')
    bench_format = os.path.join(build, 'bench', 'bench_format')
    rows = list(csv.DictReader(open(os.path.join(HERE, 'results', 'meshes.tsv')), delimiter='\t'))
    names = []
    for r in rows:
        if r['mesh'] not in names and r['mesh'] not in CAD:
            names.append(r['mesh'])
    table = []
    with tempfile.TemporaryDirectory() as work:
        for name in names:
            path = mesh_file(name)
            if not path:
                print('%s: not in %s, skipped' % (name, SHARED), file=sys.stderr)
                continue
            obj, pn = os.path.join(work, 'mesh.obj'), os.path.join(work, 'pn.obj')
            subprocess.run([bench_format, 'convert', path, obj], check=True, capture_output=True)
            vertices, faces = load_obj(obj)
            level = 4 if len(faces) <= 120000 else 2
            with open(pn, 'w') as out:
                write_pn_triangles(vertices, faces, level, out)
            measured = subprocess.run([bench_format, 'mesh', obj, pn], check=True, capture_output=True, text=True)
            floor = json.loads(measured.stdout.strip().split('\n')[-1])['chamfer']
            file_row = [r for r in rows if r['mesh'] == name and r['config'] == 'default' and r['kind'] == 'file'][0]
            draco = [(float(r['chamfer']), float(r['bytes'])) for r in rows
                     if r['mesh'] == name and r['config'] == 'draco' and r['kind'] == 'file']
            chamfer, size = float(file_row['chamfer']), int(file_row['bytes'])
            draco_bytes, _ = loglog(draco, chamfer, envelope=True)
            table.append((name, len(vertices), level, floor, chamfer, size, draco_bytes))
            print('%s: floor %.3e, file %.3e' % (name, floor, chamfer), file=sys.stderr)
    lines = ['# The facets\' own distance from a smooth surface through the vertices', '',
             'Generated by `bench/facet_floor.py` %s, from bench/results/meshes.tsv (the default files and Draco\'s'
             % run_stamp(),
             'points of bench/meshes.sh\'s run). PN: the Chamfer distance (/ bbox diagonal) between the mesh and its PN',
             'triangles (the smooth cubic surface through its vertices with their normals, each triangle tessellated into',
             'level^2); file: the default `-o` file\'s Chamfer distance to the mesh; x Draco: the file\'s bytes over',
             'Draco\'s at that distance. Smooth meshes only (CAD parts have sharp edges a smooth surface rounds off).', '',
             '| mesh | V | level | PN Chamfer | file Chamfer | file / PN | bytes | x Draco |', '|---|---|---|---|---|---|---|---|']
    for name, v, level, floor, chamfer, size, draco_bytes in sorted(table, key=lambda t: t[4] / t[3]):
        ratio = '%.2f' % (size / draco_bytes) if draco_bytes else '-'
        lines.append('| %s | %d | %d | %.2e | %.2e | %.2f | %d | %s |' % (name, v, level, floor, chamfer, chamfer / floor,
                                                                       size, ratio))
    write_result('facet_floor.md', lines)


if __name__ == '__main__':
    main()
