#!/usr/bin/env python3
"""Every measured figure in the prose of the performance docs is one its raw files hold.

The tables of docs/performance.md and docs/frames.md are generated from committed raw files
(benchmarks/performance_tables.py, checked by the test `performance_tables`); the sentences around
them quote figures by hand. This check reads each section below outside its generated blocks,
takes every measured figure (a number with a decimal point or an exponent, or one followed by x,
%, a time or a size) and requires it to be the rounding, at the digits the prose gives, of a number
in what its paragraph quotes: the generated tables just before and after the paragraph, and the raw
files (of the section's result folders) the paragraph names (a percentage also of a fraction
there; a ratio, followed by x, of a ratio written there). A figure no file holds (one derived
from two others, or not a measurement) is listed in DERIVED with the sentence it sits in and why;
an entry whose sentence is gone fails too. It catches a figure invented, mistyped or left from an
older run; one copied from the wrong row of the right files, where that row's number is the same,
passes.

    check_prose_figures.py            the check (exit 1 naming each figure not found)
"""
import math
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent

# (doc, the heading that opens the section or None for the whole file, raw result folders)
SECTIONS = [
    ("docs/performance.md", None, ["benchmarks/results/avx512"]),
    ("docs/frames.md", "## Needlets for precomputed radiance transfer", ["benchmarks/results/prt"]),
]

# Figures in prose that no raw file holds, each with a fragment of its sentence and why it may stay.
DERIVED = {
    ("docs/performance.md", "About 40 minutes on 2 cores"): "how long the run takes, not a result",
    ("docs/performance.md", "by 10 to\n30 %"): "the spread between runs and machines seen over the git history of the results",
    ("docs/performance.md", "to 1e-5 against the recurrence"): "a test's tolerance, not a measurement",
    ("docs/performance.md", "quarter turns alone take 5.6 MB"): "the size of zxzxz's tables at order 128, computed, not measured",
    ("docs/performance.md", "(below), 1.8x the"): "derived: rotate_soa's 2.19 ns (the bulk table) over the bound's 1.22 ns (fma_bound)",
    ("docs/performance.md", "248 MB\nbinary"): "the input's size",
    ("docs/frames.md", "SH sum to 1.5e-14 of the exact RMS"): "a test's tolerance (kParsevalShading), not a measurement",
    ("docs/frames.md", "(16 x 16 over [-1.5, 1.5]^2)"): "the scene's geometry, an input",
    ("docs/frames.md", "(two walls of height 1.5)"): "the scene's geometry, an input",
    ("docs/frames.md", "closed forms within 1e-10"): "a test's tolerance, not a measurement",
    ("docs/frames.md", "where the needlets are 9 % and 13 % ahead"): "derived: 1 - needlets / SH's K largest at K = 36 and 64 (corner_diffuse.txt)",
    ("docs/frames.md", "From 64 on the three are within 3x of each other"): "derived: the largest ratio of the three columns from K = 64 (the glossy files)",
    ("docs/frames.md", "SH's K largest best or within 3 %"): "derived: SH's K largest against the best of the three at K = 64 and 144 (the glossy files)",
    ("docs/frames.md", "(6 bytes a coefficient against 4)"): "the storage rule stated above, not a measurement",
    ("docs/frames.md", "64 needlets (384 bytes)"): "bytes: 6 K (the storage rule), K = 64",
    ("docs/frames.md", "(256 bytes)"): "bytes: 4 K (the storage rule), K = 64",
    ("docs/frames.md", "(576 bytes)"): "bytes: 4 K (the storage rule), K = 144",
    ("docs/frames.md", "measured bands at 384\n  bytes"): "bytes: the needlets' count above, for which no run has bands",
}

BLOCK = re.compile(r"<!-- table .*?<!-- end table -->", re.S)
NUMBER = re.compile(r"(?<![\w.])(-?\d+(?:\.\d+)?(?:e[-+]?\d+)?)")
# A ratio's x follows its number directly ("16 x 16" is a size); a unit may stand a space apart.
UNIT = re.compile(r"(x\b)|\s?(%|ns\b|µs|us\b|ms\b|s\b|MB\b|MiB\b|GB\b|GiB\b|KiB\b|minutes?\b)")


def section_text(doc, heading):
    text = (ROOT / doc).read_text()
    if heading is None:
        return text
    start = text.index(heading)
    end = text.find("\n## ", start + len(heading))
    return text[start:end if end >= 0 else len(text)]


def figures(prose):
    """(figure text, offset) of each measured figure in prose."""
    found = []
    for match in NUMBER.finditer(prose):
        token, after = match.group(1), prose[match.end():match.end() + 8]
        unit = UNIT.match(after)
        if "." in token or "e" in token or unit:
            found.append((token, unit.group(unit.lastindex) if unit else "", match.start()))
    return found


def numbers(text):
    out = set()
    for token in NUMBER.findall(text):
        try:
            out.add(float(token))
        except ValueError:
            pass
    return out


def paragraphs(prose):
    """(start, end) of each paragraph of prose: blank lines and list items split them."""
    bounds, start = [], 0
    for match in re.finditer(r"\n\s*\n|\n(?=- )", prose):
        bounds.append((start, match.start()))
        start = match.end()
    bounds.append((start, len(prose)))
    return bounds


def significant(token):
    mantissa = token.lstrip("-").split("e")[0].replace(".", "").lstrip("0")
    return max(1, len(mantissa))


def rounds_to(value, token):
    """Whether value, rounded as token is written, is token."""
    target = float(token)
    if "e" in token or "." in token and float(token) != 0 and abs(target) < 1:
        digits = significant(token)
        if value == 0:
            return target == 0
        scale = 10 ** (math.floor(math.log10(abs(value))) - digits + 1)
        return math.isclose(round(value / scale) * scale, target, rel_tol=1e-9, abs_tol=1e-300)
    decimals = len(token.split(".")[1]) if "." in token else 0
    return math.isclose(round(value, decimals), target, rel_tol=1e-12, abs_tol=10 ** -(decimals + 6))


def line_of(doc, heading, offset):
    text = (ROOT / doc).read_text()
    return text.count("\n", 0, (text.index(heading) if heading else 0) + offset) + 1


def check():
    failures = []
    for doc, heading, raw in SECTIONS:
        whole = (ROOT / doc).read_text()
        text = section_text(doc, heading)
        files = {p.name: p.read_text(errors="replace") for path in raw for p in sorted((ROOT / path).rglob("*")) if p.is_file()}
        blocks = [(m.start(), m.end(), m.group(0)) for m in BLOCK.finditer(text)]
        # Tables and code spans (options, commands) blanked out, offsets kept.
        prose = BLOCK.sub(lambda m: " " * len(m.group(0)), text)
        prose = re.sub(r"`[^`\n]*`", lambda m: " " * len(m.group(0)), prose)
        excused = []
        for (d, fragment), why in DERIVED.items():
            if d != doc:
                continue
            if fragment not in whole:
                failures.append(f"{doc}: the excused sentence '{fragment}' ({why}) is gone: remove it from DERIVED")
            elif prose.find(fragment) >= 0:
                excused.append((prose.find(fragment), fragment))
        for start, end in paragraphs(prose):
            # What the paragraph may quote: the tables just before and after it, and the raw files it names.
            before = [block for block in blocks if block[1] <= start][-1:]
            after = [block for block in blocks if block[0] >= end][:1]
            sources = [block[2] for block in before + after]
            sources += [content for name, content in files.items() if name in prose[start:end]]
            known = set().union(*(numbers(source) for source in sources)) if sources else set()
            ratios = {float(r) for source in sources for r in re.findall(r"(?<![\w.])(\d+(?:\.\d+)?)x\b", source)}
            for token, unit, offset in figures(prose[start:end]):
                offset += start
                if any(at <= offset < at + len(fragment) for at, fragment in excused):
                    continue
                if unit == "x":
                    found = any(rounds_to(v, token) for v in ratios)
                else:
                    candidates = known | ({100 * v for v in known} if unit == "%" else set())
                    found = any(rounds_to(v, token) for v in candidates)
                if not found:
                    failures.append(f"{doc}:{line_of(doc, heading, offset)}: {token}{(' ' + unit) if unit else ''} is in neither the "
                                    "tables beside its paragraph nor a raw file the paragraph names")
    return failures


def main():
    failures = check()
    for f in failures:
        print(f)
    if failures:
        print(f"check_prose_figures: {len(failures)} figure(s) not found (scripts/check_prose_figures.py)", file=sys.stderr)
        return 1
    print("check_prose_figures: every prose figure is in its raw files")
    return 0


if __name__ == "__main__":
    sys.exit(main())
