"""What the Python bench scripts share: where the shared meshes are, the commit, writing a result file."""
import datetime
import os
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
SHARED = os.path.join(ROOT, '..', 'shared')


def mesh_path(name):
    """The path of mesh NAME in ../shared/meshes or ../shared/extra-meshes; exits when it is in neither."""
    for folder in ('meshes', 'extra-meshes'):
        path = os.path.join(SHARED, folder, name)
        if os.path.isfile(path):
            return path
    sys.exit('%s: no mesh %s in %s/meshes or extra-meshes' % (os.path.basename(sys.argv[0]), name, SHARED))


def run_stamp():
    """'on <UTC time>, commit <short hash>' for a result's first line."""
    commit = subprocess.run(['git', '-C', ROOT, 'rev-parse', '--short', 'HEAD'], capture_output=True,
                            text=True).stdout.strip()
    now = datetime.datetime.now(datetime.timezone.utc).strftime('%Y-%m-%dT%H:%MZ')
    return 'on %s, commit %s' % (now, commit)


def write_result(name, lines):
    """Writes LINES to bench/results/NAME through a temporary file (no half-written result), keeping the old
    file's hand-written text from its "## Notes" line on (as bench_setup.sh's write_keeping_notes)."""
    out = os.path.join(HERE, 'results', name)
    notes = []
    if os.path.exists(out):
        with open(out) as f:
            old = f.read().split('\n')
        starts = [i for i, line in enumerate(old) if line.startswith('## Notes')]
        if starts:
            notes = [''] + old[starts[0]:]
            while notes and notes[-1] == '':
                notes.pop()
    with open(out + '.tmp', 'w') as f:
        f.write('\n'.join(list(lines) + notes) + '\n')
    os.replace(out + '.tmp', out)
    print('wrote %s' % out, file=sys.stderr)
