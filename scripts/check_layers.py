#!/usr/bin/env python3
"""Layering checks for the library sources (issue 11).

  check_layers.py includes  [ROOT]                       no include cycle between folders
  check_layers.py functions [ROOT] [--max N] [--allow F]  no function in src/ longer than N lines

includes: every file of include/pcl_sparse/<folder>/ and src/<folder>/ belongs to <folder>; an
  #include <pcl_sparse/X/...> in a file of folder Y is an edge Y -> X. Fails, printing each cycle, if
  the folder graph has one.
functions: a function body is a brace block at namespace or class scope whose head (the text since the
  previous ';', '{' or '}') has a parenthesis; its length counts the lines from its opening brace to its
  closing brace, both included. Comments, string and character literals and preprocessor lines are
  blanked first. Fails, listing them, on bodies longer than N (default 120) lines, except those named in
  the allow-list file (lines 'src/path.cpp function', '#' comments).
Exit status: 0 pass, 1 fail, 2 usage error.
"""

import argparse
import os
import re
import sys

INCLUDE_RE = re.compile(r'^\s*#\s*include\s*[<"]pcl_sparse/([A-Za-z0-9_]+)/', re.M)
SOURCE_EXTENSIONS = ('.h', '.hpp', '.cpp', '.cc')


def folder_files(root):
    """(folder, path) for every source file of include/pcl_sparse/<folder>/ and src/<folder>/."""
    for base in (os.path.join(root, 'include', 'pcl_sparse'), os.path.join(root, 'src')):
        if not os.path.isdir(base):
            continue
        for folder in sorted(os.listdir(base)):
            top = os.path.join(base, folder)
            if not os.path.isdir(top):
                continue
            for directory, _, names in os.walk(top):
                for name in sorted(names):
                    if name.endswith(SOURCE_EXTENSIONS):
                        yield folder, os.path.join(directory, name)


def include_graph(root):
    """{folder: {included folder: [files with such an include]}}."""
    graph = {}
    for folder, path in folder_files(root):
        graph.setdefault(folder, {})
        with open(path, encoding='utf-8', errors='replace') as f:
            text = f.read()
        for target in INCLUDE_RE.findall(text):
            if target != folder:
                graph[folder].setdefault(target, []).append(os.path.relpath(path, root))
    return graph


def find_cycles(graph):
    """One cycle (list of folders, first repeated at the end) per strongly connected component of size > 1."""
    index, low, on_stack, stack, components = {}, {}, set(), [], []

    def connect(v):
        index[v] = low[v] = len(index)
        stack.append(v)
        on_stack.add(v)
        for w in sorted(graph.get(v, {})):
            if w not in index:
                connect(w)
                low[v] = min(low[v], low[w])
            elif w in on_stack:
                low[v] = min(low[v], index[w])
        if low[v] == index[v]:
            component = []
            while True:
                w = stack.pop()
                on_stack.discard(w)
                component.append(w)
                if w == v:
                    break
            if len(component) > 1:
                components.append(set(component))

    for v in sorted(graph):
        if v not in index:
            connect(v)

    cycles = []
    for component in components:
        # Shortest path back to the start inside the component (breadth first).
        start = min(component)
        previous = {start: None}
        queue = [start]
        end = None
        while queue and end is None:
            v = queue.pop(0)
            for w in sorted(graph.get(v, {})):
                if w not in component:
                    continue
                if w == start:
                    end = v
                    break
                if w not in previous:
                    previous[w] = v
                    queue.append(w)
        path = [start]
        v = end
        while v != start:
            path.insert(1, v)
            v = previous[v]
        cycles.append(path + [start])
    return cycles


def check_includes(root):
    graph = include_graph(root)
    cycles = find_cycles(graph)
    if not cycles:
        print('include graph between folders has no cycle (%d folders)' % len(graph))
        return 0
    for cycle in cycles:
        print('include cycle: ' + ' -> '.join(cycle))
        for a, b in zip(cycle, cycle[1:]):
            for path in graph[a][b]:
                print('  %s -> %s: %s' % (a, b, path))
    return 1


def blank_non_code(text):
    """Replaces comments, string/character literals and preprocessor lines by spaces, keeping newlines."""
    out = []
    i, n = 0, len(text)
    at_line_start = True
    while i < n:
        c = text[i]
        if at_line_start and c == '#':
            # Preprocessor line, with backslash continuations.
            while i < n and text[i] != '\n':
                if text[i] == '\\' and i + 1 < n and text[i + 1] == '\n':
                    out.append(' \n')
                    i += 2
                    continue
                out.append(' ')
                i += 1
            continue
        if c == '\n':
            out.append(c)
            i += 1
            at_line_start = True
            continue
        if c in ' \t':
            out.append(c)
            i += 1
            continue
        at_line_start = False
        if text.startswith('//', i):
            while i < n and text[i] != '\n':
                out.append(' ')
                i += 1
            continue
        if text.startswith('/*', i):
            end = text.find('*/', i + 2)
            end = n if end < 0 else end + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:end]))
            i = end
            continue
        raw = re.match(r'(?:u8|u|U|L)?R"([^(\s]*)\(', text[i:i + 40])
        if raw and (i == 0 or not (text[i - 1].isalnum() or text[i - 1] == '_')):
            end = text.find(')' + raw.group(1) + '"', i + raw.end())
            end = n if end < 0 else end + len(raw.group(1)) + 2
            out.append(re.sub(r'[^\n]', ' ', text[i:end]))
            i = end
            continue
        if c in '"\'':
            # A digit separator (1'000) is not a character literal.
            if c == "'" and i > 0 and text[i - 1].isalnum() and i + 1 < n and text[i + 1].isalnum() \
                    and re.match(r'.*\b\d[\w\']*$', text[max(0, i - 40):i]):
                out.append(' ')
                i += 1
                continue
            j = i + 1
            while j < n and text[j] != c and text[j] != '\n':
                j += 2 if text[j] == '\\' else 1
            out.append(c + ' ' * (min(j, n) - i - 1) + (c if j < n else ''))
            i = j + 1
            continue
        out.append(c)
        i += 1
    return ''.join(out)


CONTAINER_RE = re.compile(r'\b(namespace|class|struct|union|enum)\b|\bextern\s*"')
CONTROL_RE = re.compile(r'\b(if|for|while|switch|catch|do|else|try)\s*$')


def function_name(head):
    """The name before the parameter list of a function head, e.g. 'Foo::compute'."""
    head = ' '.join(head.split())
    name = re.compile(r'((?:[A-Za-z_]\w*\s*(?:<[^()]*>)?\s*::\s*)*(?:operator\s*\(\s*\)|operator\s*[^\s(]+|~?[A-Za-z_]\w*))\s*$')
    for k, ch in enumerate(head):
        if ch == '(':
            m = name.search(head[:k])
            if m:
                return re.sub(r'\s+', '', m.group(1))
    return head[:60]


def long_functions(path, limit):
    """[(name, first line, lines)] for function bodies in \a path longer than \a limit lines."""
    with open(path, encoding='utf-8', errors='replace') as f:
        code = blank_non_code(f.read())
    found = []
    # Stack of scopes: True for containers (namespace/class), whose direct braces are examined.
    scopes = [True]
    head_start = 0
    line = 1
    open_line = {}
    body_depth = None  # depth of the function body being skipped, or None
    for k, ch in enumerate(code):
        if ch == '\n':
            line += 1
            continue
        if ch not in '{};':
            continue
        depth = len(scopes)
        if body_depth is not None:
            if ch == '{':
                scopes.append(False)
            elif ch == '}':
                scopes.pop()
                if len(scopes) == body_depth:
                    name, first = open_line.pop(body_depth)
                    lines = line - first + 1
                    if lines > limit:
                        found.append((name, first, lines))
                    body_depth = None
                    head_start = k + 1
            continue
        if ch == ';':
            head_start = k + 1
            continue
        if ch == '}':
            if len(scopes) > 1:
                scopes.pop()
            head_start = k + 1
            continue
        head = code[head_start:k]
        head_start = k + 1
        if CONTAINER_RE.search(head) and '(' not in head.split('=')[0].split(':')[0]:
            scopes.append(True)
            continue
        stripped = head.strip()
        is_function = ('(' in head and not stripped.endswith(('=', ',', '[')) and
                       not CONTROL_RE.search(head.split('(')[0]))
        if is_function:
            open_line[depth] = (function_name(head), line)
            body_depth = depth
            scopes.append(False)
        else:
            # An initialiser or other block at namespace scope: skip it like a body, without a length check.
            scopes.append(False)
            body_depth = depth
            open_line[depth] = (None, line)
    return [(name, first, lines) for name, first, lines in found if name is not None]


def read_allow_list(path):
    allowed = set()
    if not path:
        return allowed
    with open(path, encoding='utf-8') as f:
        for raw in f:
            entry = raw.split('#', 1)[0].split()
            if len(entry) == 2:
                allowed.add((entry[0], entry[1]))
            elif entry:
                raise SystemExit('%s: bad allow-list line: %s' % (path, raw.rstrip()))
    return allowed


def check_functions(root, limit, allow_path):
    allowed = read_allow_list(allow_path)
    failures, exempt = [], []
    src = os.path.join(root, 'src')
    for directory, _, names in sorted(os.walk(src)):
        for name in sorted(names):
            if not name.endswith(SOURCE_EXTENSIONS):
                continue
            path = os.path.join(directory, name)
            rel = os.path.relpath(path, root)
            for function, first, lines in long_functions(path, limit):
                short = function.split('::')[-1]
                if (rel, function) in allowed or (rel, short) in allowed:
                    exempt.append((rel, first, function, lines))
                else:
                    failures.append((rel, first, function, lines))
    for rel, first, function, lines in exempt:
        print('allowed: %s:%d %s, %d lines' % (rel, first, function, lines))
    for rel, first, function, lines in failures:
        print('too long: %s:%d %s, %d lines (at most %d)' % (rel, first, function, lines, limit))
    if failures:
        return 1
    print('no function in src/ is longer than %d lines' % limit)
    return 0


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('check', choices=('includes', 'functions'))
    parser.add_argument('root', nargs='?', default=os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
    parser.add_argument('--max', type=int, default=120, help='longest function body allowed, in lines')
    parser.add_argument('--allow', help='allow-list file of "src/path.cpp function" lines')
    args = parser.parse_args()
    root = os.path.abspath(args.root)
    if args.check == 'includes':
        return check_includes(root)
    return check_functions(root, args.max, args.allow)


if __name__ == '__main__':
    sys.exit(main())
