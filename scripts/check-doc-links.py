#!/usr/bin/env python3
"""Every relative link in README.md and docs/**/*.md points at an existing file (and heading).

usage: scripts/check-doc-links.py [REPO]   (exit 1 if a link is broken)"""
import os, re, sys, glob
root = sys.argv[1] if len(sys.argv) > 1 else os.path.join(os.path.dirname(os.path.abspath(__file__)), "..")
files = [os.path.join(root, 'README.md')] + glob.glob(os.path.join(root, 'docs', '**', '*.md'), recursive=True)
link = re.compile(r'(?<!\!)\[[^\]]*\]\(([^)\s]+)\)')
def slugs(path):
    out = set()
    for line in open(path, encoding='utf-8'):
        m = re.match(r'^(#+)\s+(.*)$', line)
        if m:
            t = m.group(2).strip().lower()
            t = re.sub(r'[^\w\- ]', '', t)   # GitHub: drop punctuation, keep letters/digits/_/-/space
            out.add(t.replace(' ', '-'))
    return out
bad = 0; n = 0
for f in files:
    text = open(f, encoding='utf-8').read()
    text = re.sub(r'```.*?```', '', text, flags=re.S)
    for target in link.findall(text):
        if re.match(r'^[a-z]+://', target) or target.startswith('mailto:'):
            continue
        n += 1
        path, _, anchor = target.partition('#')
        dest = os.path.normpath(os.path.join(os.path.dirname(f), path)) if path else f
        if not os.path.exists(dest):
            print(f'{f}: broken link {target}'); bad += 1; continue
        if anchor:
            if os.path.isdir(dest) or anchor not in slugs(dest):
                print(f'{f}: missing anchor {target}'); bad += 1
print(f'{n} relative links checked in {len(files)} files, {bad} broken')
sys.exit(1 if bad else 0)
