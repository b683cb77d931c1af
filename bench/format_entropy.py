#!/usr/bin/env python3
"""What the range coder takes off the default .psm file, and how far it is from the entropy floors (issue 13's
bytes target).

    bench/format_entropy.py [BUILD_DIR] [MESH_FILE ...]
      BUILD_DIR   a Release build with pcl_sparse_encode (default: build)
      MESH_FILE   names in ../shared/meshes or ../shared/extra-meshes (default: spot, horse, armadillo-43k,
                  stanford-bunny)

Per mesh: `pcl_sparse_encode MESH -o FILE` (default options: quantised at the derived tolerance, range-coded
fields) and the same with `--varint-layout` (zstd over varints, the layout before the range coder). The
varint file's ATOM and COEF sections are read back (docs/FORMAT.md) and set against two floors that an
adaptive coder would approach:
  - ATOM: each patch's atom set as one bit per atom rank, each rank with its own probability (the empirical
    entropy over the patches);
  - COEF: the quantised coefficients with the atom's rank as context (order-0 entropy per rank, ranks from
    40 up pooled).
Writes bench/results/format_entropy.md. The floors ignore the cost of adapting (a few hundred bytes); the
range-coded file also codes FRAM and FOOT adaptively, which the floors leave as they are.
"""
import math
import os
import struct
import subprocess
import sys
import tempfile
from collections import Counter, defaultdict

from bench_common import ROOT, mesh_path, run_stamp, write_result

DEFAULT_MESHES = ['spot.obj', 'horse.ply', 'armadillo-43k.obj', 'stanford-bunny.obj']
RANK_CONTEXTS = 40


def sections(data):
    """{tag: (stored bytes, raw payload)} of a version-1 .psm file (docs/FORMAT.md)."""
    count = struct.unpack_from('<I', data, 20)[0]
    offset, result = 52, {}
    for _ in range(count):
        tag = data[offset:offset + 4].decode()
        codec = data[offset + 4]
        size = struct.unpack_from('<Q', data, offset + 8)[0]
        payload = data[offset + 32:offset + 32 + size]
        if codec == 1:
            payload = subprocess.run(['zstd', '-d', '-c'], input=payload, capture_output=True, check=True).stdout
        result[tag] = (size, payload)
        offset += 32 + size
    return result


def varints(payload):
    values, i = [], 0
    while i < len(payload):
        value = shift = 0
        while True:
            byte = payload[i]
            i += 1
            value |= (byte & 0x7f) << shift
            shift += 7
            if byte < 0x80:
                break
        values.append(value)
    return values


def entropy_bits(counter):
    n = sum(counter.values())
    return -sum(c * math.log2(c / n) for c in counter.values())


def floors(data):
    """(patches, stored ATOM, ATOM floor, stored COEF, COEF floor) in bytes."""
    patches = struct.unpack_from('<I', data, 16)[0]
    parts = sections(data)
    atom_values = varints(parts['ATOM'][1])
    coefficients = [(v >> 1) ^ -(v & 1) for v in varints(parts['COEF'][1])]  # zigzag
    used, by_rank = Counter(), defaultdict(Counter)
    i = j = 0
    for _ in range(patches):
        n = atom_values[i]
        i += 1
        rank = -1
        for _ in range(n):
            rank += 1 + atom_values[i]  # quantised files store shell-rank deltas
            i += 1
            used[rank] += 1
            by_rank[min(rank, RANK_CONTEXTS)][coefficients[j]] += 1
            j += 1
    atom_bits = 0.0
    for count in used.values():
        q = count / patches
        if q < 1.0:
            atom_bits -= patches * (q * math.log2(q) + (1.0 - q) * math.log2(1.0 - q))
    coef_bits = sum(entropy_bits(c) for c in by_rank.values())
    return patches, parts['ATOM'][0], atom_bits / 8.0, parts['COEF'][0], coef_bits / 8.0


class AdaptiveCost:
    """Bits the file's range coder spends (docs/FORMAT.md, "Range-coded fields"), without coding: a probability
    per key in 1/4096 adapting by 1/16, signed integers as zero, sign, unary exponent, one modelled bit below
    the leading one, the rest at one bit each."""

    def __init__(self):
        self.p0 = defaultdict(lambda: 2048)
        self.bits = 0.0

    def bit(self, key, bit):
        p = self.p0[key]
        self.bits -= math.log2(1.0 - p / 4096.0 if bit else p / 4096.0)
        self.p0[key] = p - (p >> 4) if bit else p + ((4096 - p) >> 4)

    def signed(self, key, value):
        self.bit((key, 'nonzero'), value != 0)
        if value == 0:
            return
        self.bit((key, 'negative'), value < 0)
        magnitude = abs(value)
        e = magnitude.bit_length() - 1
        for i in range(e):
            self.bit((key, 'exponent', i), True)
        self.bit((key, 'exponent', e), False)
        if e >= 1:
            self.bit((key, 'below', e), (magnitude >> (e - 1)) & 1)
            self.bits += e - 1


def morton_seed_bytes(data):
    """Bytes of SEED if the patches were in Morton order of their seeds and each seed were coded as its
    difference from the previous one (signed integers, one model set per axis): what a canonical patch order
    would save. The file's order carries about log2(M) bits a patch that the model does not need."""
    patches = struct.unpack_from('<I', data, 16)[0]
    parts = sections(data)
    seed_bytes = parts['QUAN'][1][32]  # after seed_min (3 f64) and the seed step (f64)
    planes = parts['SEED'][1]
    axes = []
    for axis in range(3):
        values = [0] * patches
        for b in range(seed_bytes):
            plane = planes[(axis * seed_bytes + b) * patches:(axis * seed_bytes + b + 1) * patches]
            for i in range(patches):
                values[i] |= plane[i] << (8 * b)
        axes.append(values)
    seeds = list(zip(*axes))

    def morton(seed):
        code = 0
        for b in range(32):
            for axis in range(3):
                code |= ((seed[axis] >> b) & 1) << (3 * b + axis)
        return code

    cost, previous = AdaptiveCost(), (0, 0, 0)
    for seed in sorted(seeds, key=morton):
        for axis in range(3):
            cost.signed(axis, seed[axis] - previous[axis])
        previous = seed
    return parts['SEED'][0], cost.bits / 8.0


def load_ms(info, path):
    """Best of 5 `pcl_sparse_info --json` seconds (reading, checking and decoding the file), in ms."""
    import json
    runs = [json.loads(subprocess.run([info, path, '--json'], capture_output=True, check=True, text=True).stdout)
            for _ in range(5)]
    return 1000.0 * min(run['seconds'] for run in runs)


def main():
    args = sys.argv[1:]
    build = os.path.abspath(args[0]) if args else os.path.join(ROOT, 'build')
    meshes = args[1:] or DEFAULT_MESHES
    encode = os.path.join(build, 'apps', 'pcl_sparse_encode')
    info = os.path.join(build, 'apps', 'pcl_sparse_info')
    lines = [
        '# The range coder against the varint layout and the entropy floors',
        '',
        'Generated by `bench/format_entropy.py` %s. `pcl_sparse_encode MESH -o FILE` with default' % run_stamp(),
        'options (range-coded fields), and with `--varint-layout` (zstd over varints, the layout before the range',
        'coder): the same model in both. "varint" columns: the varint file; "range" columns: the default file. Floors:',
        'the varint file\'s ATOM and COEF at the entropy of a static model, atom sets as one bit per atom rank with',
        'its own probability, coefficients with their atom\'s rank as context (the script says how); "varint file at',
        'the floors" = the varint file with both sections at their floor (FRAM and FOOT as stored). "SEED in Morton',
        'order": the seeds delta-coded with the range coder\'s integer coding, patches sorted by the Morton code of',
        'their seeds (not implemented: the encoder\'s patch order would have to become canonical). "load ms": best',
        'of 5 `pcl_sparse_info --json` runs (reading, checking and decoding the file), the price of the range coder.',
        '',
        '| mesh | patches | varint file | range file | saved | ATOM varint / range / floor | COEF varint / range / floor | FRAM varint / range | FOOT varint / range | varint file at the floors | SEED / in Morton order | range file with it | load ms varint / range |',
        '|---|---|---|---|---|---|---|---|---|---|---|---|---|',
    ]
    with tempfile.TemporaryDirectory() as work:
        for name in meshes:
            path = os.path.join(work, 'model.psm')
            subprocess.run([encode, mesh_path(name), '-q', '-o', path, '--varint-layout'], capture_output=True, check=True)
            data = open(path, 'rb').read()
            varint_ms = load_ms(info, path)
            subprocess.run([encode, mesh_path(name), '-q', '-o', path], capture_output=True, check=True)
            coded = open(path, 'rb').read()
            coded_ms = load_ms(info, path)
            stored = {tag: size for tag, (size, _) in sections(data).items()}
            coded_sizes = {tag: size for tag, (size, _) in sections(coded).items()}
            patches, atom, atom_floor, coef, coef_floor = floors(data)
            total = len(data)
            floor_total = total - atom - coef + atom_floor + coef_floor
            seed, morton_seed = morton_seed_bytes(coded)
            lines.append('| %s | %d | %d | %d | %.1f %% | %d / %d / %.0f | %d / %d / %.0f | %d / %d | %d / %d | %.0f | %d / %.0f | %.1f %% smaller | %.1f / %.1f |' % (
                os.path.splitext(name)[0], patches, total, len(coded), 100.0 * (1.0 - len(coded) / total),
                atom, coded_sizes['ATOM'], atom_floor, coef, coded_sizes['COEF'], coef_floor,
                stored['FRAM'], coded_sizes['FRAM'], stored['FOOT'], coded_sizes['FOOT'], floor_total,
                seed, morton_seed, 100.0 * (seed - morton_seed) / len(coded), varint_ms, coded_ms))
            print(lines[-1], file=sys.stderr, flush=True)
    write_result('format_entropy.md', lines)


if __name__ == '__main__':
    main()
