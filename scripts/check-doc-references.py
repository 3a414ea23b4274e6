#!/usr/bin/env python3
"""Every document a source comment cites exists in the repository, with the section it names.

Scans the sources (C++, CMake, Python, shell, case files) for `docs/NAME.md` (and bare
`NAME.md` of docs/) followed by a quoted section, `docs/theory.md, "The wall layer"`, and checks
the file and a heading of that title; flags citations of paths outside the repository (the
workplace's physics.md, build notes, ../shared/). Exit 1 on any miss, listing them.

usage: scripts/check-doc-references.py [REPO]
"""
import glob
import os
import re
import subprocess
import sys

root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
try:
    listed = subprocess.run(['git', '-C', root, 'ls-files'], capture_output=True, text=True,
                            check=True).stdout.split()
except (OSError, subprocess.CalledProcessError):
    listed = [os.path.relpath(p, root) for p in glob.glob(os.path.join(root, '**', '*'), recursive=True)]
suffixes = ('.cpp', '.hpp', '.tpp', '.h', '.c', '.py', '.sh', '.prm', '.lmp', 'CMakeLists.txt', '.cmake')
sources = [f for f in listed if f.endswith(suffixes) and not f.startswith('build/')]

docs = {os.path.basename(p): p for p in glob.glob(os.path.join(root, 'docs', '**', '*.md'), recursive=True)}


def headings(path):
    out = set()
    with open(path, encoding='utf-8') as f:
        for line in f:
            m = re.match(r'^#+\s+(.*?)\s*$', line)
            if m:
                out.add(m.group(1))
    return out


cite = re.compile(r'(?:docs/)?([a-z][a-z0-9_.-]*\.md)(?:,|:)?\s*(?:\n\s*(?://|#)\s*)?"([^"\n]+)"')
bare = re.compile(r'(?<![\w.-])(docs/[a-z][a-z0-9_/.-]*\.md)\b')
outside = re.compile(r'physics\.md|build-notes|\.\./shared/|shared/docs|shared/peers|shared/seeds')
bad = []
checked = 0
for rel in sources:
    if rel == 'scripts/check-doc-references.py':
        continue
    path = os.path.join(root, rel)
    try:
        text = open(path, encoding='utf-8').read()
    except (UnicodeDecodeError, FileNotFoundError):
        continue
    for m in outside.finditer(text):
        line = text.count('\n', 0, m.start()) + 1
        bad.append(f'{rel}:{line}: cites {m.group(0)}, outside the repository')
    for m in bare.finditer(text):
        checked += 1
        if not os.path.exists(os.path.join(root, m.group(1))):
            line = text.count('\n', 0, m.start()) + 1
            bad.append(f'{rel}:{line}: cites {m.group(1)}, which is not in docs/')
    for m in cite.finditer(text):
        name, section = os.path.basename(m.group(1)), m.group(2)
        if name not in docs or section.startswith(('Section/', 'Particle/', 'Scene/')):
            continue
        if not any(h == section or h.startswith(section + ' ') for h in headings(docs[name])):
            line = text.count('\n', 0, m.start()) + 1
            bad.append(f'{rel}:{line}: {name} has no section "{section}"')
for b in bad:
    print(b)
print(f'{checked} citations of docs/ in {len(sources)} sources checked, {len(bad)} broken')
sys.exit(1 if bad else 0)
