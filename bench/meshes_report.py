#!/usr/bin/env python3
"""Writes bench/results/meshes.md from bench/meshes.sh's meshes.tsv (issue 13 point 5).

  meshes_report.py MESHES.tsv RUN_INFO > meshes.md

RUN_INFO: key=value lines written by bench/meshes.sh (date, seconds, load, cpus, commit, ...).
"""
import csv
import math
import sys

# The authors' implementation at rho 0.001 (issue 13 point 4): M, CR, RMSE/diag.
AUTHORS = {
    'anchor-dense': (527, 0.804, 1.29e-04), 'armadillo-43k': (2247, 0.433, 5.84e-04),
    'blade': (538, 0.364, 5.38e-04), 'blub': (658, 0.508, 3.97e-04), 'bunny-hr-closed': (1527, 0.426, 4.48e-04),
    'bunny-npm-1k': (298, 1.350, 5.84e-04), 'cheese-cgal': (735, 0.439, 5.94e-04),
    'couplingdown': (80, 0.342, 2.07e-04), 'fandisk': (713, 0.802, 2.25e-04), 'fandisk-large': (709, 0.363, 2.74e-04),
    'fertility': (725, 1.344, 4.54e-04), 'horse': (1225, 0.210, 3.12e-04), 'igea': (1459, 0.090, 4.97e-04),
    'kitten-14k': (763, 0.439, 3.13e-04), 'kitten-53k': (874, 0.137, 3.13e-04), 'koala': (1047, 0.174, 4.44e-04),
    'koala-loop1-200k': (1131, 0.047, 4.30e-04), 'nefertiti-35k': (1571, 0.374, 2.83e-04),
    'rocker-arm': (917, 0.761, 5.43e-04), 'skull': (1194, 0.199, 5.88e-04), 'spot': (918, 0.663, 2.68e-04),
    'stanford-bunny': (1483, 0.355, 4.29e-04), 'sword': (1373, 0.513, 1.12e-04), 'turbine': (629, 0.549, 2.58e-04),
    'wingnut': (206, 0.551, 3.57e-04),
}
# Variants of the paper preset swept for RMSE only (bench/meshes.sh's configurations): options, what they are.
VARIANTS = {
    'paper-cone72': ('-preset paper -cone 72', 'The paper with the authors\' normal cone'),
    'paper-nosamples': ('-preset paper -min-samples 0', 'The paper coding the vertices only, no extra samples'),
}
# CAD meshes (the CGAL models and the other machined parts: sharp edges, flat faces); the rest are smooth.
CAD = {'anchor-dense', 'blade', 'cheese-cgal', 'couplingdown', 'fandisk', 'fandisk-large', 'rocker-arm', 'turbine',
       'wingnut', 'sword'}


def loglog(points, x, envelope=False, reach=1.25):
    """Interpolates y at x over (x, y) points in log-log. With envelope, first keeps the lower envelope (points
    sorted by x whose y is below every y at smaller x). Outside the points' x range, extrapolates from the end
    segment when x is within a factor reach of the range. Returns (y, extrapolated) or (None, False)."""
    pts = sorted(p for p in points if p[0] > 0 and p[1] > 0)
    if envelope:
        kept = []
        for p in pts:
            if not kept or p[1] < kept[-1][1]:
                kept.append(p)
        pts = kept
    if len(pts) < 2:
        return None, False
    for (x0, y0), (x1, y1) in zip(pts, pts[1:]):
        if x0 <= x <= x1 and x1 > x0:
            w = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
            return math.exp((1 - w) * math.log(y0) + w * math.log(y1)), False
    if x < pts[0][0] / reach or x > pts[-1][0] * reach:
        return None, False
    (x0, y0), (x1, y1) = (pts[0], pts[1]) if x < pts[0][0] else (pts[-2], pts[-1])
    if x1 == x0:
        return None, False
    w = (math.log(x) - math.log(x0)) / (math.log(x1) - math.log(x0))
    return math.exp((1 - w) * math.log(y0) + w * math.log(y1)), True


def mean_error(row):
    """The row's mean vertex error / diag, or None (rows of runs before the column existed)."""
    value = row.get('mean_error_over_diag')
    return float(value) if value not in (None, '', '-') else None


def at_their_cr(rows, authors, key):
    """Our error (column key: RMSE or mean, / diag) at the authors' CR, interpolated over the rows of a rho sweep.
    Where their CR lies above the whole sweep (every model of ours is smaller than theirs), the smallest error
    of the sweep bounds ours at their CR from above, as the lower envelope assumes (a larger model is no less
    accurate). Returns (value, mark, ours / their figure); mark: '' interpolated, '*' extrapolated, '<=' that
    bound."""
    sweep = [(float(r['cr']), key(r)) for r in rows]
    sweep = [p for p in sweep if p[1] is not None]
    if not authors or not sweep:
        return None, '', None
    value, extrapolated = loglog(sweep, authors[1], envelope=True)
    mark = '*' if extrapolated else ''
    if value is None and authors[1] > max(p[0] for p in sweep):
        value, mark = min(p[1] for p in sweep), '<='
    return value, mark, value / authors[2] if value else None


def marked(text, mark):
    """text with its mark: '<=' before it, '*' after it."""
    return mark + text if mark == '<=' else text + mark


def fx(value):
    return '-' if value is None else '%.2fx' % value


def main():
    rows = list(csv.DictReader(open(sys.argv[1]), delimiter='\t'))
    info = dict(line.strip().split('=', 1) for line in open(sys.argv[2]) if '=' in line)
    meshes = []
    for r in rows:
        if r['mesh'] not in meshes:
            meshes.append(r['mesh'])

    def pick(mesh, config, kind):
        return [r for r in rows if r['mesh'] == mesh and r['config'] == config and r['kind'] == kind]

    summary = {}
    for m in meshes:
        draco = [(float(r['chamfer']), float(r['bytes'])) for r in pick(m, 'draco', 'file')]
        for config in ('default', 'paper'):
            f = pick(m, config, 'file')
            c = pick(m, config, 'cloud')
            if not f or not c:
                continue
            f, c = f[0], c[0]
            sweep = [(float(r['cr']), float(r['rmse_over_diag'])) for r in pick(m, config, 'encode') + [f]]
            authors = AUTHORS.get(m)
            at_cr, at_cr_mark, ratio_rmse = at_their_cr(pick(m, config, 'encode') + [f], authors,
                                                        lambda r: float(r['rmse_over_diag']))
            mean_at_cr, mean_mark, ratio_mean = at_their_cr(pick(m, config, 'encode') + [f], authors, mean_error)
            draco_bytes, draco_out = loglog(draco, float(f['chamfer']), envelope=True)
            summary[(m, config)] = dict(
                vertices=int(f['vertices']), M=int(f['patches']), cr=float(f['cr']), rmse=float(f['rmse_over_diag']),
                sweep=len(sweep), cr_range=(min(p[0] for p in sweep), max(p[0] for p in sweep)), at_cr=at_cr, at_cr_mark=at_cr_mark,
                ratio_rmse=ratio_rmse, ratio_mean=ratio_mean, mean_mark=mean_mark,
                bytes=int(f['bytes']), chamfer=float(f['chamfer']), draco_bytes=draco_bytes, draco_out=draco_out,
                ratio_draco=int(f['bytes']) / draco_bytes if draco_bytes else None,
                p99=float(c['p99_spacings']), pmax=float(c['max_spacings']), complete=float(c['completeness3']),
                flipped=int(c['flipped']), flipped_fraction=float(c['flipped_fraction']))

    # Variants of the paper preset, one option changed each: the error sweep only (what each is, in VARIANTS).
    variants = {}
    for config in VARIANTS:
        for m in meshes:
            rows_ = pick(m, config, 'encode')
            authors = AUTHORS.get(m)
            if not rows_ or not authors:
                continue
            at_cr, mark, ratio = at_their_cr(rows_, authors, lambda r: float(r['rmse_over_diag']))
            _, mean_mark, ratio_mean = at_their_cr(rows_, authors, mean_error)
            crs = [float(r['cr']) for r in rows_]
            variants[(m, config)] = dict(at_cr=at_cr, mark=mark, cr_range=(min(crs), max(crs)),
                                         ratio=ratio, ratio_mean=ratio_mean, mean_mark=mean_mark)

    def targets(config):
        s = [(m, summary[(m, config)]) for m in meshes if (m, config) in summary]
        n = len(s)
        p99_ok = [m for m, v in s if v['p99'] <= 3.0]
        flip_ok = [m for m, v in s if v['flipped'] == 0]
        cr_ok = [m for m, v in s if v['cr'] <= 1.0]
        draco_ok = [m for m, v in s if v['ratio_draco'] is not None and v['ratio_draco'] <= (1.5 if m in CAD else 1.0)]
        rmse_ok = [m for m, v in s if v['ratio_rmse'] is not None and v['ratio_rmse'] <= 1.05]
        mean_ok = [m for m, v in s if v['ratio_mean'] is not None and v['ratio_mean'] <= 1.05]
        worst = lambda key: max(((v[key], m) for m, v in s if v[key] is not None), default=(None, '-'))
        return n, p99_ok, flip_ok, cr_ok, draco_ok, rmse_ok, mean_ok, worst

    def verdict(ok, n):
        return '**met** (%d/%d)' % (len(ok), n) if len(ok) == n else '**missed** (%d/%d met)' % (len(ok), n)

    out = ['# All shared meshes: coverage, normals, CR, RMSE at the authors\' CR, bytes against Draco', '',
           'Generated by `bench/meshes.sh` (issue 13 point 5) in one run: %s, %s s on %s CPUs (%s), load average'
           ' %s before and %s after (the machine is shared with other builds and runs), commit %s.'
           % (info.get('date'), info.get('seconds'), info.get('cpus'), info.get('cpu'), info.get('load_before'),
              info.get('load_after'), info.get('commit')), '']
    for config in ('default', 'paper'):
        n, p99_ok, flip_ok, cr_ok, draco_ok, rmse_ok, mean_ok, worst = targets(config)
        if n == 0:
            continue
        out.append('Targets, %s (%s):' % (config, 'default options' if config == 'default' else '`-preset paper`'))
        out.append('- p99 surface-to-cloud distance within 3 spacings on every mesh: %s; worst %s %.2f'
                   % (verdict(p99_ok, n), worst('p99')[1], worst('p99')[0]))
        out.append('- 0 flipped normals on every mesh: %s; worst %s %d (%.3f %%)'
                   % (verdict(flip_ok, n), worst('flipped')[1], worst('flipped')[0],
                      100 * summary[(worst('flipped')[1], config)]['flipped_fraction']))
        out.append('- CR <= 1 at rho 0.001 on every mesh: %s; worst %s %.3f' % (verdict(cr_ok, n), worst('cr')[1], worst('cr')[0]))
        if config == 'default':
            out.append('- the `-o` file at most 1x Draco\'s bytes at equal Chamfer on smooth meshes, 1.5x on CAD ones: %s;'
                       ' worst %s %s; %d without a Draco value' % (verdict(draco_ok, n), worst('ratio_draco')[1], fx(worst('ratio_draco')[0]),
                          sum(1 for m in meshes if (m, config) in summary and summary[(m, config)]['ratio_draco'] is None)))
        else:
            out.append('- RMSE/diag at the authors\' CR within 1.05x of theirs: %s; worst %s %s; %d with their CR below our sweep'
                       % (verdict(rmse_ok, n), worst('ratio_rmse')[1], fx(worst('ratio_rmse')[0]),
                          sum(1 for m in meshes if (m, config) in summary and summary[(m, config)]['ratio_rmse'] is None)))
            if worst('ratio_mean')[0] is not None:
                out.append('- the same with our mean vertex error, if their figure is the mean |v - v^| their code prints'
                           ' (gproshan\'s msparse_coding::mesh_reconstruction sums the distances and divides by the vertex'
                           ' count; no square, no root): within 1.05x on %d of %d meshes with a value; worst %s %s'
                           % (len(mean_ok), sum(1 for m, v in summary.items() if m[1] == config and v['ratio_mean'] is not None),
                              worst('ratio_mean')[1], fx(worst('ratio_mean')[0])))
        out.append('')
    for config, (options, what) in VARIANTS.items():
        measured = {m: v for (m, c), v in variants.items() if c == config}
        if not measured:
            continue
        ok = [m for m, v in measured.items() if v['ratio'] is not None and v['ratio'] <= 1.05]
        mean_ok = [m for m, v in measured.items() if v['ratio_mean'] is not None and v['ratio_mean'] <= 1.05]
        out.append('%s (`%s`, table at the end): RMSE/diag at their CR within 1.05x of theirs on %d of %d meshes with'
                   ' a value (%d with their CR below our sweep); the mean error within 1.05x on %d.'
                   % (what, options, len(ok), sum(1 for v in measured.values() if v['ratio'] is not None),
                      sum(1 for v in measured.values() if v['ratio'] is None), len(mean_ok)))
    if variants:
        out.append('')
    out += ['How each column is measured:',
            '- M, CR, RMSE/diag: `pcl_sparse_encode MESH [-preset paper] -rho 0.001 --json` (patches, cr, rmse_over_diag).'
            ' "authors": their implementation at rho 0.001, from issue 13 point 4.',
            '- RMSE at the authors\' CR: our rho swept over %s (meshes over %s vertices: rho 0.001 only, so no value),'
            ' RMSE/diag interpolated at their CR in log-log over the lower envelope of our (CR, RMSE) points (CR is not'
            ' monotone in rho on every mesh); `*` = their CR lies outside our sweep by at most 1.25x and the value is'
            ' extrapolated from the end segment; `<=` = their CR lies above our whole sweep (every model of ours is'
            ' smaller than theirs) and the value is the sweep\'s smallest error, a bound on ours at their CR as the'
            ' lower envelope assumes (a larger model is no less accurate; it counts toward the target); further out'
            ' below our sweep (their model smaller than all of ours): "CR a-b" gives our sweep\'s CR range and no ratio.'
            ' "x theirs" = ours / their RMSE. "mean x theirs": the same with our mean vertex error / diag'
            ' (`mean_error_over_diag`) against the same figure of theirs, which their code computes as a mean error'
            ' (see the targets above).'
            % (info.get('rhos'), info.get('sweep_max')),
            '- p99, max: `pcl_sparse_resample MESH CLOUD.pcd [-preset paper] -n 4V` (the encoder\'s default rho),'
            ' then `bench_meshes`: max(200k, #points) probes drawn uniformly by area on the input mesh (seed 1),'
            ' distance from each probe to its nearest cloud point in spacings sqrt(area / #points); 99th percentile'
            ' and largest. "<=3" = fraction of probes within 3 spacings.',
            '- flipped: cloud points whose normal is more than 120 degrees from the normal of the nearest input face'
            ' (`evaluateCloudQuality`), count and % of the cloud.',
            '- bytes: the `-o` file of the rho-0.001 run (default: quantised at the derived tolerance; paper preset: as the'
            ' preset writes it). Chamfer: `bench_format model MESH FILE` (as bench/rate_distortion.sh: mean'
            ' point-to-surface distance both ways over 200k points a side, averaged, / bbox diagonal).'
            ' Draco: `draco_encoder -cl 7 -qp Q` for Q in %s on the mesh, decoded, `bench_format mesh`; its bytes'
            ' interpolated log-log at our Chamfer ("x Draco" = ours / Draco; `*` = our Chamfer is outside Draco\'s'
            ' range by at most 1.25x, extrapolated; - = further out). CAD meshes (limit 1.5x): %s.' % (info.get('qps'), ', '.join(sorted(CAD))),
            '- Determinism: our tools are seeded and give the same output single- and multi-threaded; Draco is'
            ' deterministic too. Only the seconds in the .tsv vary.', '']
    header = ('| mesh | V | M | authors M | CR | authors CR | RMSE/diag | authors RMSE | RMSE at their CR | x theirs |'
              ' mean x theirs | p99 (spacings) | max | <=3 | flipped | bytes | Chamfer/diag | Draco bytes | x Draco |')
    for config in ('default', 'paper'):
        out += ['## %s' % ('Default options' if config == 'default' else '`-preset paper`'), '', header,
                '|' + '---|' * 19]
        for m in meshes:
            v = summary.get((m, config))
            if not v:
                continue
            a = AUTHORS.get(m, (None, None, None))
            out.append('| %s | %d | %d | %s | %.3f | %s | %.2e | %s | %s | %s | %s | %.2f | %.1f | %.4f | %d (%.3f %%) | %d | %.2e | %s | %s |' % (
                m, v['vertices'], v['M'], a[0], v['cr'], a[1], v['rmse'], '%.2e' % a[2] if a[2] else '-',
                marked('%.2e' % v['at_cr'], v['at_cr_mark']) if v['at_cr'] else 'CR %.2f-%.2f' % v['cr_range'],
                marked('**%.2f**' % v['ratio_rmse'], v['at_cr_mark']) if v['ratio_rmse'] else '-',
                marked('%.2f' % v['ratio_mean'], v['mean_mark']) if v['ratio_mean'] else '-',
                v['p99'], v['pmax'], v['complete'], v['flipped'], 100 * v['flipped_fraction'], v['bytes'], v['chamfer'],
                '%.0f%s' % (v['draco_bytes'], '*' if v['draco_out'] else '') if v['draco_bytes'] else '-',
                '**%.2f**%s' % (v['ratio_draco'], '*' if v['draco_out'] else '') if v['ratio_draco'] else '-'))
        out.append('')
    if variants:
        out += ['## The paper preset with one option changed: RMSE and mean error at the authors\' CR', '',
                'The same rho sweep and interpolation as above; each cell "x theirs": RMSE / mean error. ' +
                '; '.join('%s: `%s`' % (config, options) for config, (options, what) in VARIANTS.items()) + '.', '',
                '| mesh | authors CR | authors RMSE | paper preset | ' + ' | '.join(VARIANTS) + ' |',
                '|---|---|---|---|' + '---|' * len(VARIANTS)]
        for m in meshes:
            if not any((m, config) in variants for config in VARIANTS):
                continue
            a = AUTHORS[m]
            paper = summary.get((m, 'paper'))
            cells = []
            both = lambda rmse, rmse_mark, mean, mean_mark: '%s / %s' % (
                marked('%.2f' % rmse, rmse_mark) if rmse else '-', marked('%.2f' % mean, mean_mark) if mean else '-')
            for config in VARIANTS:
                v = variants.get((m, config))
                cells.append('-' if not v else (both (v['ratio'], v['mark'], v['ratio_mean'], v['mean_mark'])
                                                if v['ratio'] or v['ratio_mean'] else 'CR %.2f-%.2f' % v['cr_range']))
            out.append('| %s | %s | %.2e | %s | %s |' % (
                m, a[1], a[2],
                both(paper['ratio_rmse'], paper['at_cr_mark'], paper['ratio_mean'], paper['mean_mark'])
                if paper and (paper['ratio_rmse'] or paper['ratio_mean']) else '-',
                ' | '.join(cells)))
        out.append('')
    missing = [m for m in AUTHORS if m not in meshes]
    if missing:
        out += ['**Partial run**: not measured: %s.' % ', '.join(sorted(missing)), '']
    print('\n'.join(out))


if __name__ == '__main__':
    main()
