#!/usr/bin/env python3
"""The dependency rule holds: every #include "room/..." in a room's sources is allowed by
scripts/include-rules.txt, and docs/architecture.md's rule table is the one the rules give.

usage: scripts/check-include-rules.py [REPO] [--print-table]   (exit 1 on a violation)
"""
import glob
import os
import re
import sys

args = [a for a in sys.argv[1:] if not a.startswith('--')]
root = args[0] if args else os.path.join(os.path.dirname(os.path.abspath(__file__)), '..')
rules = {}
with open(os.path.join(root, 'scripts', 'include-rules.txt')) as f:
    for line in f:
        line = line.split('#', 1)[0].strip()
        if not line:
            continue
        room, _, allowed = line.partition(':')
        rules[room.strip()] = allowed.split()


def table():
    rows = ['| room | may include |', '|---|---|']
    for room, allowed in rules.items():
        rows.append(f'| `{room}/` | ' + (', '.join(f'`{a}`' for a in allowed) or 'nothing') + ' |')
    return '\n'.join(rows) + '\n'


if '--print-table' in sys.argv:
    sys.stdout.write(table())
    sys.exit(0)

include = re.compile(r'^\s*#\s*include\s+"([a-z_]+)/([^"]+)"', re.M)
bad = []
checked = 0
for room, allowed in rules.items():
    for path in glob.glob(os.path.join(root, room, '**', '*'), recursive=True):
        if not path.endswith(('.cpp', '.hpp', '.tpp', '.h')):
            continue
        text = open(path, encoding='utf-8').read()
        for m in include.finditer(text):
            other, header = m.group(1), m.group(2)
            if other not in rules:
                continue  # not a room (a generated header's folder, say)
            checked += 1
            if other == room or other in allowed or f'{other}/{header}' in allowed:
                continue
            line = text.count('\n', 0, m.start()) + 1
            bad.append(f'{os.path.relpath(path, root)}:{line}: {room}/ includes {other}/{header}, '
                       f'which scripts/include-rules.txt does not allow')
doc = open(os.path.join(root, 'docs', 'architecture.md'), encoding='utf-8').read()
m = re.search(r'<!-- include-rules -->\n(.*?)<!-- /include-rules -->', doc, re.S)
if not m:
    bad.append('docs/architecture.md: no <!-- include-rules --> table')
elif m.group(1) != table():
    bad.append('docs/architecture.md: its include-rules table differs from scripts/include-rules.txt '
               '(scripts/check-include-rules.py --print-table gives the one to paste)')
for b in bad:
    print(b)
print(f'{checked} includes across rooms checked, {len(bad)} violations')
sys.exit(1 if bad else 0)
