#!/usr/bin/env python3
"""Regenerates the tables of docs/stex-format.md from the declarations: each model's parameters
and the blocks every file shares (scale, colour, histograms, provenance, image).

    scripts/update-parameter-tables.py [STEX]      (default: build/cli/stex)

Each model's table sits between '<!-- parameters NAME: ... -->' and '<!-- end parameters NAME -->',
each shared block's between '<!-- block PATH: ... -->' and '<!-- end block PATH -->';
`stex models --markdown` prints them (core: parameter_table_markdown). tests/model_registry_test.cpp
fails when the document and the declarations disagree.
"""
import os
import re
import subprocess
import sys

root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
stex = sys.argv[1] if len(sys.argv) > 1 else os.path.join(root, "build", "cli", "stex")
text = subprocess.run([stex, "models", "--markdown"], check=True, capture_output=True, text=True).stdout
# "### NAME" (a model's parameters) or "### block PATH" (a shared block).
tables = dict(re.findall(r"### ((?:block )?\S+)\n\n(.*?)(?=\n### |\Z)", text, re.S))
path = os.path.join(root, "docs", "stex-format.md")
with open(path, encoding="utf-8") as f:
    document = f.read()
for name, table in tables.items():
    kind, name = name.split(" ", 1) if name.startswith("block ") else ("parameters", name)
    pattern = re.compile(r"(<!-- %s %s: [^\n]*-->\n).*?(<!-- end %s %s -->)" % (kind, re.escape(name), kind, re.escape(name)), re.S)
    if not pattern.search(document):
        sys.exit("%s: no marker for %s %s" % (path, kind, name))
    document = pattern.sub(lambda m: m.group(1) + table.rstrip("\n") + "\n" + m.group(2), document)
with open(path, "w", encoding="utf-8") as f:
    f.write(document)
print("updated %d tables in %s" % (len(tables), path))
