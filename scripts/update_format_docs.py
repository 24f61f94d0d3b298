#!/usr/bin/env python3
"""Rewrites the field tables of docs/formats.md from `beamid formats TAG`.

Usage: python3 scripts/update_format_docs.py [path/to/beamid]
(default build/release/beamid). Each section between
"<!-- fields: TAG -->" and "<!-- end fields -->" gets the table that the
format's declaration gives; tests/solver/format_docs_test.cc checks them.
"""
import pathlib
import re
import subprocess
import sys

root = pathlib.Path(__file__).resolve().parent.parent
beamid = sys.argv[1] if len(sys.argv) > 1 else str(root / "build/release/beamid")
doc_path = root / "docs/formats.md"
doc = doc_path.read_text()
for tag in re.findall(r"<!-- fields: (\S+) -->", doc):
    table = subprocess.run([beamid, "formats", tag], capture_output=True, text=True, check=True).stdout
    pattern = r"(<!-- fields: " + re.escape(tag) + r" -->\n).*?(<!-- end fields -->)"
    doc = re.sub(pattern, lambda m: m.group(1) + table + m.group(2), doc, flags=re.S)
doc_path.write_text(doc)
