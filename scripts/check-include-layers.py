#!/usr/bin/env python3
"""Checks that the core's includes point one way: down the layer order of docs/architecture.md.

    usage: scripts/check-include-layers.py [--core DIR] [--layers FILE]

The order is the fenced ```layers block of docs/architecture.md (the one place it is written):
one layer per line, top first, folders relative to core/; a line's folders are siblings, and an
entry ending in /* stands for each subfolder. A file may include files of its own folder and of
every layer below its own; it may not include a layer above it, nor a sibling folder of its own
layer (so `src/models/*`, the models' folders, do not include each other). A `*` stands for any
one folder, also inside an entry (`src/models/*/front_ends`: each model's front-end forms). A
line `private FOLDER...` names folders no other folder includes, whatever its layer, except the
folders inside them: the models' folders are reached through the registry (src/models/model.h),
not into, but a model's own front-end forms use its folder. Every file of core/src
and core/include/stochtex must belong to a layer, so a new folder is placed in the order before
it is used. Exits 1 naming each include that breaks a rule (file, line, rule). Python 3
standard library only: the test command runs it (CTest `IncludeLayers`).
"""
import argparse
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent
INCLUDE = re.compile(r'^\s*#\s*include\s*(?:"([^"]+)"|<(stochtex/[^>]+)>)')
SOURCE_SUFFIXES = {".h", ".hpp", ".cpp", ".cc", ".inc"}


def read_layers(document):
    """The ```layers block of `document` as its lines, top first, each a list of words: a layer's
    folders (relative to core/; `src/models/*` stands for each subfolder), or `private` and the
    folders it names."""
    text = Path(document).read_text(encoding="utf-8")
    match = re.search(r"^```layers\n(.*?)^```", text, re.S | re.M)
    if not match:
        raise SystemExit(f"{document}: no ```layers block")
    layers = []
    for line in match.group(1).splitlines():
        line = line.split("#", 1)[0].strip()
        if line:
            layers.append(line.split())
    return layers


class LayerOrder:
    def __init__(self, lines):
        self.rank = {}  # unit pattern -> rank (0 = top)
        self.private = set()  # unit patterns only their own files include
        layers = []
        for words in lines:
            if words[0] == "private":
                self.private.update(words[1:])
            else:
                layers.append(words)
        for pattern in self.private:
            if not any(pattern in units for units in layers):
                raise SystemExit(f"layers: private {pattern} is in no layer")
        for rank, units in enumerate(layers):
            for unit in units:
                if unit in self.rank:
                    raise SystemExit(f"layers: {unit} is listed twice")
                self.rank[unit] = rank

    def unit_of(self, path):
        """(unit, rank, pattern) of a path relative to core/: the longest entry it lies under; a `*`
        in an entry stands for any one folder, so `src/models/*` is one unit per subfolder (files
        directly in the parent are not in it) and `src/models/*/front_ends` one per model."""
        best = None
        parts = path.split("/")
        for pattern, rank in self.rank.items():
            words = pattern.split("/")
            if len(parts) <= len(words):
                continue  # a file must lie inside the entry's folder
            if not all(word == "*" or word == part for word, part in zip(words, parts)):
                continue
            unit = "/".join(parts[:len(words)])
            if best is None or len(unit) > len(best[0]):
                best = (unit, rank, pattern)
        return best


def sources(core):
    for top in ("src", "include/stochtex"):
        for path in sorted((core / top).rglob("*")):
            if path.is_file() and path.suffix in SOURCE_SUFFIXES:
                yield path


def resolve(core, including, name, quoted):
    """The file under core/ an include names, or None (a system or third-party header)."""
    candidates = []
    if quoted:
        candidates += [including.parent / name, core / "src" / name]
    candidates.append(core / "include" / name)
    for candidate in candidates:
        if candidate.is_file():
            return candidate.resolve()
    return None


def check(core, layers):
    """The broken rules, as 'file:line: message' strings."""
    core = Path(core).resolve()
    order = LayerOrder(layers)
    problems = []
    for path in sources(core):
        relative = path.relative_to(core).as_posix()
        placed = order.unit_of(relative)
        if placed is None:
            problems.append(f"core/{relative}:1: in no layer of the ```layers order (docs/architecture.md)")
            continue
        unit, rank, _ = placed
        for number, line in enumerate(path.read_text(encoding="utf-8", errors="replace").splitlines(), 1):
            match = INCLUDE.match(line)
            if not match:
                continue
            name = match.group(1) or match.group(2)
            target = resolve(core, path, name, match.group(1) is not None)
            if target is None or core not in target.parents:
                continue
            target_relative = target.relative_to(core).as_posix()
            target_placed = order.unit_of(target_relative)
            if target_placed is None:
                continue  # reported as a file of its own
            target_unit, target_rank, target_pattern = target_placed
            if target_unit == unit:
                continue
            if target_pattern in order.private:
                if unit.startswith(target_unit + "/"):
                    continue  # a folder inside a private one is its own files (a model's front-end forms)
                rule = f"{target_unit} is private: only its own files include it; others reach it through a layer below it"
            elif target_rank > rank:
                continue
            elif target_rank == rank:
                rule = f"{unit} and {target_unit} are siblings in one layer: neither includes the other"
            else:
                rule = f"{unit} is below {target_unit}: includes point down the layer order"
            problems.append(f"core/{relative}:{number}: includes {name}: {rule}")
    return problems


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--core", default=ROOT / "core", help="the core folder (src/, include/)")
    parser.add_argument("--layers", default=ROOT / "docs" / "architecture.md",
                        help="the document holding the ```layers block")
    arguments = parser.parse_args()
    problems = check(arguments.core, read_layers(arguments.layers))
    for problem in problems:
        print(problem)
    if problems:
        print(f"{len(problems)} include(s) against the layer order of docs/architecture.md", file=sys.stderr)
        return 1
    print(f"includes of {arguments.core} follow the layer order of {arguments.layers}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
