#!/usr/bin/env python3
"""Regenerates the parameter tables of docs/stex-format.md from the models' declarations.

    scripts/update-parameter-tables.py [STEX]      (default: build/cli/stex)

Each model's table sits between '<!-- parameters NAME: ... -->' and '<!-- end parameters NAME -->';
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
tables = dict(re.findall(r"### (\S+)\n\n(.*?)(?=\n### |\Z)", text, re.S))
path = os.path.join(root, "docs", "stex-format.md")
with open(path, encoding="utf-8") as f:
    document = f.read()
for name, table in tables.items():
    pattern = re.compile(r"(<!-- parameters %s: [^\n]*-->\n).*?(<!-- end parameters %s -->)" % (name, name), re.S)
    if not pattern.search(document):
        sys.exit("%s: no marker for model %s" % (path, name))
    document = pattern.sub(lambda m: m.group(1) + table.rstrip("\n") + "\n" + m.group(2), document)
with open(path, "w", encoding="utf-8") as f:
    f.write(document)
print("updated %d tables in %s" % (len(tables), path))
