#!/usr/bin/env python3
"""Fails when a thing that has one home is written somewhere else.

Run from anywhere: python3 scripts/check_one_place.py. The test suite runs it (ctest: one_place).
Each rule names its home; a finding prints file:line and the rule, and the exit code is 1.

- Limits (order ranges, counts, sizes): defined in a library's limits.h only, beside its readers:
  runtime/limits.h holds the runtime's, shared by every library (a test may name a bound of its
  own on what it measures). A bound given to a checked read (integer_option, orders_option, a
  JSON field's integer or items, read_text_file) is a name, not a literal above 16 or a shift; a
  range in an option's help (0..256) is built from the limit it states.
- The runtime's floor: each constant of runtime/limits.h and runtime/tolerances.h is named by the
  runtime itself (its code, or the accuracy a header states); one only the libraries above use
  belongs to their limits.h or to tolerances/tolerances.h.
- Tolerances: in C++ outside the tests, a literal in scientific notation with a negative
  exponent (1e-6, 2.5e-7) stands in the tolerance table (runtime/tolerances.h, the runtime's part;
  tolerances/tolerances.h, the rest) or a limits.h only (a line that
  uses one as an input, such as a tiny test angle, says "// an input, not a tolerance"); in the tests,
  the bound of EXPECT_NEAR / ASSERT_NEAR is a name, never a literal.
- Lobe table paths: "order_N.json" is built by runtime::table_path (runtime/table_io.h) only; design
  paths, "t_T.json", by frames::design_path (frames/designs.h) only.
- Threads (std::thread, std::async): the pool in runtime/parallel.h and the interrupt watchdog in
  io/src/signals.cc only (tests may start their own, e.g. to send signals).
- Random draws: no std::*_distribution (implementation-defined); sh/random.h draws from raw bits.
- Pi: runtime::kPi and kPiLong (runtime/sh_eval.h); no other digits of pi and no M_PI outside the
  tests.
- Enum names: an enumeration's names are written once, in its runtime::EnumName table
  (runtime/enum_names.h), which gives its names, parsing and choices; no switch returns a name
  per case.
- JSON reading: the tools parse JSON in io/src/json.cc only (io::json::parse, nlohmann-json with
  zhf's checks); the runtime's own parser (runtime::json) serves the runtime's lobe-table reader,
  its fuzzer and its tests only.
"""
import os
import re
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SKIP_DIRS = {"generated", "build", ".git", "node_modules", "fuzz_corpus", "data"}
LIMITS = re.compile(r"^\w+/include/zhf/\w+/limits\.h$")  # a library's limits.h
TOLERANCES = ("runtime/include/zhf/runtime/tolerances.h", "tolerances/include/zhf/tolerances/tolerances.h")
RUNTIME_FLOOR = ("runtime/include/zhf/runtime/limits.h", "runtime/include/zhf/runtime/tolerances.h")
RUNTIME = "runtime/include/zhf/runtime/"
TABLE_IO = "runtime/include/zhf/runtime/table_io.h"
DESIGNS = "frames/include/zhf/frames/designs.h"
PARALLEL = "runtime/include/zhf/runtime/parallel.h"
WATCHDOG = "io/src/signals.cc"
RANDOM = "sh/include/zhf/sh/random.h"
SH_EVAL = "runtime/include/zhf/runtime/sh_eval.h"


def sources():
    for folder, dirs, files in os.walk(ROOT):
        rel_folder = os.path.relpath(folder, ROOT)
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith("build")]
        for name in files:
            if name.endswith((".cc", ".h", ".py")):
                yield os.path.normpath(os.path.join(rel_folder, name))


def code_of(line):
    """The line without its // comment (a // inside a string literal is kept)."""
    quoted = False
    for i, c in enumerate(line):
        if c == '"' and (i == 0 or line[i - 1] != "\\"):
            quoted = not quoted
        if not quoted and line.startswith("//", i):
            return line[:i]
    return line


LIMIT_DEFINITION = re.compile(r"constexpr\s+[\w:]+\s+k(Max|Min)[A-Z]\w*\s*=")
SCIENTIFIC = re.compile(r"(?<![\w.])\d+(\.\d+)?[eE]-\d+[fFlL]?\b")
NEAR_LITERAL = re.compile(r"(EXPECT|ASSERT)_NEAR\(.*,\s*-?[\d.]+([eE]-?\d+)?\)\s*(<<|;)")
TABLE_NAME = re.compile(r"(order_\" \+ [^+]+ \+ \"\.json|order_\{\w+\}\.json)")
DESIGN_NAME = re.compile(r"t_\" \+ [^+]+ \+ \"\.json|t_\{\w+\}\.json")
THREAD = re.compile(r"std::thread\b(?!::hardware_concurrency)|std::async\b")
DISTRIBUTION = re.compile(r"std::\w+_distribution\b")
INPUT_MARK = "// an input, not a tolerance"
PI = re.compile(r"3\.14159|\bM_PI\b")
CHECKED_READ = re.compile(r"\b(integer_option|orders_option|integer|items|read_text_file|read_file)\((.*)")
LITERAL_BOUND = re.compile(r"(?<![\w.])(\d{3,}|[2-9]\d|1[7-9])(?![\w.])|<<")
HELP_RANGE = re.compile(r'add_(option|flag|subcommand)\(.*"[^"]*\b\d+\.\.\d{2,}')
NAME_SWITCH = re.compile(r'case [\w:]+:\s*return "[a-z][\w -]*";')
JSON_PARSE = re.compile(r"\b(nlohmann::(ordered_)?json|Json)::parse\b")
JSON_PARSER = "io/src/json.cc"
RUNTIME_JSON = re.compile(r"runtime::json::|zhf/runtime/json\.h")
RUNTIME_JSON_USERS = ("runtime/include/zhf/runtime/", "fuzz/json_fuzzer.cc", "tests/")


def check(path, findings):
    cpp = path.endswith((".cc", ".h"))
    test = path.startswith("tests/")
    with open(os.path.join(ROOT, path), encoding="utf-8") as f:
        lines = f.read().split("\n")
    for number, raw in enumerate(lines, 1):
        line = code_of(raw) if cpp else raw.split("#")[0]
        where = f"{path}:{number}"
        limits_file = bool(LIMITS.match(path))
        if cpp and not test and not limits_file and LIMIT_DEFINITION.search(line):
            findings.append(f"{where}: a limit defined outside a library's limits.h")
        if cpp and not test and not limits_file and path not in TOLERANCES and SCIENTIFIC.search(line) and INPUT_MARK not in raw:
            findings.append(f"{where}: a tolerance literal outside the tolerance table ({SCIENTIFIC.search(line).group(0)})")
        if cpp and test and NEAR_LITERAL.search(line):
            findings.append(f"{where}: a NEAR bound that is a literal, not a named tolerance")
        if path != TABLE_IO and TABLE_NAME.search(line):
            findings.append(f"{where}: a lobe table path built outside runtime::table_path ({TABLE_IO})")
        if path != DESIGNS and DESIGN_NAME.search(line):
            findings.append(f"{where}: a design path built outside frames::design_path ({DESIGNS})")
        if cpp and not test and path not in (PARALLEL, WATCHDOG) and THREAD.search(line):
            findings.append(f"{where}: threads started outside {PARALLEL}")
        if cpp and DISTRIBUTION.search(line):
            findings.append(f"{where}: {DISTRIBUTION.search(line).group(0)} is implementation-defined; use {RANDOM}")
        read = CHECKED_READ.search(line) if cpp and not test and not limits_file else None
        if read and LITERAL_BOUND.search(read.group(2)):
            findings.append(f"{where}: a limit written in a call to {read.group(1)}; name it in a limits.h")
        if cpp and not test and HELP_RANGE.search(line):
            findings.append(f"{where}: a range written in a help text; build it from its limit")
        if cpp and not test and path != SH_EVAL and PI.search(line):
            findings.append(f"{where}: pi written out; use runtime::kPi or kPiLong ({SH_EVAL})")
        if cpp and not test and NAME_SWITCH.search(line):
            findings.append(f"{where}: a name returned per case; write the names in a runtime::EnumName table")
        if cpp and not test and path != JSON_PARSER and JSON_PARSE.search(line):
            findings.append(f"{where}: JSON parsed outside {JSON_PARSER}; read it with io::json (io/json.h)")
        if cpp and RUNTIME_JSON.search(line) and not path.startswith(RUNTIME_JSON_USERS):
            findings.append(f"{where}: the runtime's JSON parser outside the runtime; read JSON with io::json (io/json.h)")


FLOOR_ENTRY = re.compile(r"^inline (?:constexpr [\w: ]+?|double) (k\w+|\w+)(?: =|\()")


def check_runtime_floor(findings):
    """Every entry of the runtime's limits.h and tolerances.h is named in the runtime beyond its definition."""
    texts = {}
    for folder, _, files in os.walk(os.path.join(ROOT, RUNTIME)):
        for name in files:
            path = os.path.relpath(os.path.join(folder, name), ROOT)
            with open(os.path.join(ROOT, path), encoding="utf-8") as f:
                texts[path] = f.read()
    for home in RUNTIME_FLOOR:
        for number, line in enumerate(texts[home].split("\n"), 1):
            entry = FLOOR_ENTRY.match(line)
            if not entry:
                continue
            name = re.compile(r"\b" + entry.group(1) + r"\b")
            if sum(len(name.findall(text)) for text in texts.values()) < 2:
                findings.append(f"{home}:{number}: {entry.group(1)} is not named by the runtime; "
                                "it belongs to its readers' limits.h or to tolerances/tolerances.h")


def main():
    findings = []
    check_runtime_floor(findings)
    for path in sorted(sources()):
        if path == "scripts/check_one_place.py":
            continue
        check(path, findings)
    for finding in findings:
        print(finding)
    if findings:
        print(f"check_one_place: {len(findings)} finding(s)", file=sys.stderr)
        return 1
    print("check_one_place: limits, tolerances, the runtime's floor, table and design paths, threads, random draws, enum names, JSON reading and pi each in one place")
    return 0


if __name__ == "__main__":
    sys.exit(main())
