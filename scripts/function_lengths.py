#!/usr/bin/env python3
"""Function lengths across the project, C++ and Python.

  function_lengths.py                 # every function of at least $MIN lines (default 80), longest first
  function_lengths.py FILE...         # the same for the given files
  function_lengths.py --check         # exit 1 if a function is over its folder's limit (a ctest test)

The limits (issue 43): 60 lines in the new world/, methods/ and run/ code, 100 everywhere else.
C++: brace matching on comment- and string-stripped text, lambdas counting toward the function that
holds them. Python: the ast's function spans (nested functions count toward the outer one too).
Every tracked folder is covered, except build folders and results/.
"""
import ast
import os
import re
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), '..'))
STRICT = {'world': 60, 'methods': 60, 'run': 60}
DEFAULT_LIMIT = 100
SKIP_DIRS = {'.git', 'results', 'node_modules', '__pycache__', 'data'}


def limit_of(path):
    top = os.path.relpath(path, ROOT).split(os.sep)[0]
    return STRICT.get(top, DEFAULT_LIMIT)


def strip(src):
    out = []
    i, n = 0, len(src)
    while i < n:
        c = src[i]
        if src.startswith('//', i):
            j = src.find('\n', i)
            j = n if j < 0 else j
            out.append(' ' * (j - i))
            i = j
        elif src.startswith('/*', i):
            j = src.find('*/', i) + 2
            out.append(re.sub(r'[^\n]', ' ', src[i:j]))
            i = j
        elif src.startswith('R"(', i):
            j = src.find(')"', i) + 2
            out.append(re.sub(r'[^\n]', ' ', src[i:j]))
            i = j
        elif c == "'" and i > 0 and src[i - 1].isdigit():  # a digit separator: 100'000
            out.append(c)
            i += 1
        elif c in '"\'':
            j = i + 1
            while j < n and src[j] != c:
                j += 2 if src[j] == '\\' else 1
            out.append(c + ' ' * (j - i - 1) + c)
            i = j + 1
        else:
            out.append(c)
            i += 1
    return ''.join(out)


def cpp_functions(path):
    s = strip(open(path, encoding='utf-8').read())
    stack, res = [], []
    line, last = 1, 0
    for i, c in enumerate(s):
        if c == '\n':
            line += 1
        elif c == '{':
            head = s[last:i]
            kind = 'blk'
            infn = any(k == 'fn' for k, _ in stack)
            if not infn and ')' in head and not re.search(r'\b(namespace|struct|class|enum)\b',
                                                          head.split(';')[-1]):
                kind = 'fn'
            stack.append((kind, line))
            last = i + 1
        elif c == '}':
            k, st = stack.pop()
            last = i + 1
            if k == 'fn':
                res.append((line - st + 1, path, st))
        elif c == ';':
            last = i + 1
    return res


def py_functions(path):
    tree = ast.parse(open(path, encoding='utf-8').read(), path)
    res = []

    def visit(node, inside):
        for child in ast.iter_child_nodes(node):
            if isinstance(child, (ast.FunctionDef, ast.AsyncFunctionDef)) and not inside:
                res.append((child.end_lineno - child.lineno + 1, path, child.lineno))
                visit(child, True)
            else:
                visit(child, inside)

    visit(tree, False)
    return res


def project_files():
    files = []
    for dp, dns, fs in os.walk(ROOT):
        dns[:] = sorted(d for d in dns if d not in SKIP_DIRS and not d.startswith('build'))
        files += [os.path.join(dp, f) for f in sorted(fs) if f.endswith(('.cpp', '.hpp', '.py'))]
    return files


def lengths(files):
    res = []
    for f in files:
        res += py_functions(f) if f.endswith('.py') else cpp_functions(f)
    return sorted(res, reverse=True)


def main(args):
    if args[:1] == ['--check']:
        res = lengths(project_files())
        long = [r for r in res if r[0] > limit_of(r[1])]
        for n, f, st in long:
            print('%d lines (over %d): %s:%d' % (n, limit_of(f), os.path.relpath(f, ROOT), st))
        print('%d functions, %d over their folder\'s limit (60 in %s, %d elsewhere)' %
              (len(res), len(long), ', '.join(sorted(STRICT)), DEFAULT_LIMIT))
        return 1 if long else 0
    res = lengths(args or project_files())
    for n, f, st in res:
        if n >= int(os.environ.get('MIN', '80')):
            print(n, os.path.relpath(f, ROOT), st)
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv[1:]))
