#!/usr/bin/env python3
"""Would a default rho that grows on small meshes serve users better? (issue 13, the bytes target)

    bench/default_rho.py [BUILD_DIR] [MESH_FILE ...]
      BUILD_DIR   a Release build with pcl_sparse_encode, pcl_sparse_resample, bench_format, bench_meshes
                  (default: build)
      MESH_FILE   names in ../shared/meshes or ../shared/extra-meshes (default: the 25 meshes of bench/meshes.sh)
    Environment: PCL_SPARSE_PATCH_VERTICES (default: 0 64 200), the rules measured.

At rho 0.001 a patch of an 11k-vertex mesh holds about 20 vertices and costs about 230 bits, so the default
file of a small mesh is patch-bound (bench/results/meshes.md: 3.7x Draco's bytes on spot). Rule N sets
rho = max(0.001, N / V): on meshes of fewer than 1000 N vertices a patch's area bound holds about N vertices;
N = 0 is today's default. Per mesh and rule, as bench/meshes.sh measures the default configuration:
`pcl_sparse_encode MESH -rho R -o FILE` (bytes), `bench_format model` (Chamfer / diag), `pcl_sparse_resample
-rho R -n 4V` and `bench_meshes` (p99 in spacings, flipped normals). Draco's bytes at our Chamfer are
interpolated over the Draco rows of bench/results/meshes.tsv (Draco is deterministic, so they are not rerun).
Writes bench/results/default_rho.md. The tools are seeded: the table does not depend on the thread count.
"""
import concurrent.futures
import csv
import json
import os
import subprocess
import sys
import tempfile

from bench_common import ROOT, mesh_path, run_stamp, write_result
from meshes_report import CAD, loglog

MESHES = ['anchor-dense.off', 'armadillo-43k.obj', 'blade.off', 'blub.obj', 'bunny-hr-closed.obj',
          'bunny-npm-1k.obj', 'cheese-cgal.off', 'couplingdown.off', 'fandisk.off', 'fandisk-large.off',
          'fertility.off', 'horse.ply', 'igea.ply', 'kitten-14k.obj', 'kitten-53k.obj', 'koala.obj',
          'koala-loop1-200k.ply', 'nefertiti-35k.obj', 'rocker-arm.obj', 'skull.obj', 'spot.obj',
          'stanford-bunny.obj', 'sword.obj', 'turbine.off', 'wingnut.obj']


def tool_json(args):
    return json.loads(subprocess.run(args, capture_output=True, text=True, check=True).stdout.splitlines()[-1])


def measure(build, name, vertices, rule, work):
    """One mesh under one rule: rho, patches, bytes, Chamfer / diag, p99 spacings, flipped points."""
    path = mesh_path(name)
    rho = '%.6g' % max(0.001, rule / vertices)
    stem = os.path.join(work, '%s_%d' % (os.path.splitext(name)[0], rule))
    encoded = tool_json([os.path.join(build, 'apps', 'pcl_sparse_encode'), path, '-rho', rho, '-o', stem + '.psm',
                         '--json', '-q'])
    chamfer = tool_json([os.path.join(build, 'bench', 'bench_format'), 'model', path, stem + '.psm'])['chamfer']
    subprocess.run([os.path.join(build, 'apps', 'pcl_sparse_resample'), path, stem + '.pcd', '-rho', rho,
                    '-n', str(4 * vertices), '-q'], check=True)
    cloud = tool_json([os.path.join(build, 'bench', 'bench_meshes'), path, stem + '.pcd'])
    return dict(rho=float(rho), patches=encoded['patches'], rmse=encoded['rmse_over_diag'],
                bytes=os.path.getsize(stem + '.psm'), chamfer=chamfer, p99=cloud['p99_spacings'],
                flipped=cloud['flipped'])


def main():
    args = sys.argv[1:]
    build = os.path.abspath(args.pop(0)) if args and os.path.isdir(args[0]) else os.path.join(ROOT, 'build')
    meshes = args or MESHES
    rules = [int(n) for n in os.environ.get('PCL_SPARSE_PATCH_VERTICES', '0 64 200').split()]
    rows = list(csv.DictReader(open(os.path.join(ROOT, 'bench', 'results', 'meshes.tsv')), delimiter='\t'))
    vertices = {r['mesh']: int(r['vertices']) for r in rows}
    draco = {}
    for r in rows:
        if r['config'] == 'draco':
            draco.setdefault(r['mesh'], []).append((float(r['chamfer']), float(r['bytes'])))
    subprocess.run(['cmake', '--build', build, '--target', 'pcl_sparse_encode', 'pcl_sparse_resample',
                    'bench_format', 'bench_meshes', '-j2'], check=True, stdout=subprocess.DEVNULL)
    results = {}
    with tempfile.TemporaryDirectory() as work, concurrent.futures.ThreadPoolExecutor(2) as pool:
        jobs = {(name, rule): pool.submit(measure, build, name, vertices[os.path.splitext(name)[0]], rule, work)
                for name in meshes for rule in rules}
        for key, job in jobs.items():
            results[key] = job.result()
            print('%s N %d: %s' % (key[0], key[1], results[key]), file=sys.stderr)

    met = {rule: 0 for rule in rules}
    flipped = {rule: [0, 0] for rule in rules}  # meshes with a flipped point, flipped points in all
    growth = {rule: [] for rule in rules}
    table = []
    for name in meshes:
        base = os.path.splitext(name)[0]
        limit = 1.5 if base in CAD else 1.0
        for rule in rules:
            r = results[(name, rule)]
            draco_bytes, _ = loglog(draco.get(base, []), r['chamfer'], envelope=True)
            ratio = r['bytes'] / draco_bytes if draco_bytes else None
            met[rule] += bool(ratio and ratio <= limit)
            flipped[rule][0] += r['flipped'] > 0
            flipped[rule][1] += r['flipped']
            growth[rule].append(r['chamfer'] / results[(name, rules[0])]['chamfer'])
            table.append('| %s | %d | %d | %.3g | %d | %d | %.2e | %.2fx | %s | %.2f | %d |' % (
                base, vertices[base], rule, r['rho'], r['patches'], r['bytes'], r['chamfer'], growth[rule][-1],
                '-' if ratio is None else '**%.2f**' % ratio if ratio <= limit else '%.2f' % ratio, r['p99'],
                r['flipped']))

    lines = ['# A default rho that grows on small meshes: rho = max(0.001, N / V)', '',
             'Generated by `bench/default_rho.py` %s. Each rule N: the default options with -rho max(0.001, N / V); '
             'N %d is the default. x Draco: our `-o` file\'s bytes over Draco\'s at our Chamfer (bold: within the '
             'target, 1x on smooth meshes, 1.5x on CAD ones; - : our Chamfer outside Draco\'s range). "Chamfer x": '
             'the Chamfer over rule N %d\'s. p99: surface-to-cloud distance in spacings of a 4V-point cloud; flipped: '
             'its points more than 120 degrees from the surface normal (bench/meshes.sh\'s measures).'
             % (run_stamp(), rules[0], rules[0]), '']
    lines += ['- N %d: the bytes target met on %d of %d meshes; Chamfer %.2f-%.2fx (median %.2fx); flipped points on '
              '%d meshes, %d in all' % (rule, met[rule], len(meshes), min(growth[rule]), max(growth[rule]),
                                        sorted(growth[rule])[len(growth[rule]) // 2], flipped[rule][0],
                                        flipped[rule][1]) for rule in rules]
    lines += ['', '| mesh | V | N | rho | M | bytes | Chamfer/diag | Chamfer x | x Draco | p99 | flipped |',
              '|---|---|---|---|---|---|---|---|---|---|---|'] + table
    write_result('default_rho.md', lines)


if __name__ == '__main__':
    main()
