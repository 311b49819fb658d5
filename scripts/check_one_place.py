#!/usr/bin/python3
"""Fails when a thing that has one home is written somewhere else.

Run with Debian's Python, which has libclang's bindings (python3-clang-14):
    /usr/bin/python3 scripts/check_one_place.py [--root DIR]
The test suite runs it (ctest: one_place) and its own tests (tests/scripts/check_one_place_test.py).
Each rule names its home; a finding prints file:line and the rule, and the exit code is 1.

C++ is read as clang's lexer reads it (libclang's tokens, comments apart), and the rules look at
tokens, calls with their whole argument lists and statements, so a line break, a comment or an alias
declared in the file or in a header does not hide a finding.

- Limits (order ranges, counts, sizes): defined in a library's limits.h only, beside its readers:
  runtime/limits.h holds the runtime's, shared by every library (a test may name a bound of its
  own on what it measures). Outside them: no constexpr k(Max|Min)... constant, no object of a
  ...Limits type filled with literals, no max_/min_ member set to a literal above 16 or a shift; a
  bound given to a checked read (integer_option, orders_option, a JSON field's integer or items,
  read_text_file, read_file) is a name, not a literal above 16 or a shift; a refusal (an if whose
  body throws) compares with a name, not a literal of 3 or more, and shifts nothing; a range in an
  option's help
  (0..256) is built from the limit it states.
- The runtime's floor: each constant of runtime/limits.h and runtime/tolerances.h is named by the
  runtime itself (its code, or the accuracy a header states); one only the libraries above use
  belongs to their limits.h or to tolerances/tolerances.h. Each entry of tolerances/tolerances.h
  is named by a library, each of tests/support/test_tolerances.h by a test: no entry is kept for
  nothing, and a tolerance only tests use lives with the tests.
- Tolerances: in C++ outside the tests, a literal in scientific notation with a negative exponent
  (1e-6, 2.5e-7) stands in the tolerance table (runtime/tolerances.h, tolerances/tolerances.h,
  tests/support/test_tolerances.h) or a limits.h only (a line that uses one as an input, such as a
  tiny test angle or a format's constant, says "// an input, not a tolerance"); in the tests, the
  bound of EXPECT_NEAR / ASSERT_NEAR is a name, never a literal.
- Lobe table paths: "order_N.json" is built by runtime::table_path (runtime/table_io.h) only; design
  paths, "t_T.json", by frames::design_path (frames/designs.h) only.
- Threads (std::thread, std::jthread, std::async, pthread_create, or an alias of them): the pool in
  runtime/parallel.h and the interrupt watchdog in io/src/signals.cc only (tests may start their
  own, e.g. to send signals).
- Random draws: no std::*_distribution (implementation-defined); sh/random.h draws from raw bits.
- Pi: runtime::kPi and kPiLong (runtime/sh_eval.h); no other digits of pi, no M_PI and no pi from
  an inverse trigonometric function of constants (acos(-1), 4 atan(1)) outside the tests.
- Enum names: an enumeration's names are written once, in its runtime::EnumName table
  (runtime/enum_names.h), which gives its names, parsing and choices; no case of a switch returns
  a name.
- JSON reading: the tools parse JSON in io/src/json.cc only (io::json::parse, nlohmann-json with
  zhf's checks), whatever nlohmann's type is called there (an alias, a using-declaration, a
  namespace alias); the runtime's own parser (runtime::json) serves the runtime's lobe-table reader,
  its fuzzer and its tests only.
"""
import argparse
import glob
import os
import re
import sys

import clang.cindex as ci

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SKIP_DIRS = {"generated", "build", ".git", "node_modules", "fuzz_corpus", "data", "tools"}
LIMITS = re.compile(r"^\w+/include/zhf/\w+/limits\.h$")  # a library's limits.h
TOLERANCES = ("runtime/include/zhf/runtime/tolerances.h", "tolerances/include/zhf/tolerances/tolerances.h",
              "tests/support/test_tolerances.h")
RUNTIME_FLOOR = ("runtime/include/zhf/runtime/limits.h", "runtime/include/zhf/runtime/tolerances.h")
LIBRARY_TOLERANCES = "tolerances/include/zhf/tolerances/tolerances.h"
TEST_TOLERANCES = "tests/support/test_tolerances.h"
RUNTIME = "runtime/include/zhf/runtime/"
TABLE_IO = "runtime/include/zhf/runtime/table_io.h"
DESIGNS = "frames/include/zhf/frames/designs.h"
PARALLEL = "runtime/include/zhf/runtime/parallel.h"
WATCHDOG = "io/src/signals.cc"
RANDOM = "sh/include/zhf/sh/random.h"
SH_EVAL = "runtime/include/zhf/runtime/sh_eval.h"
JSON_PARSER = "io/src/json.cc"
RUNTIME_JSON_USERS = ("runtime/include/zhf/runtime/", "fuzz/json_fuzzer.cc", "tests/")
INPUT_MARK = "// an input, not a tolerance"

CHECKED_READS = {"integer_option", "orders_option", "integer", "items", "read_text_file", "read_file"}
OPTION_CALLS = {"add_option", "add_flag", "add_subcommand", "description"}
THREAD_NAMES = {"thread", "jthread", "async"}
INVERSE_TRIG = {"acos", "asin", "atan", "atan2", "acosl", "asinl", "atanl", "atan2l", "acosf", "asinf", "atanf", "atan2f"}
NLOHMANN_TYPES = {"json", "ordered_json", "basic_json"}
JSON_PARSES = {"parse", "sax_parse", "accept"}
SCIENTIFIC = re.compile(r"^\d+(\.\d*)?[eE]-\d+[fFlL]?$")
HELP_RANGE = re.compile(r"\b\d+\.\.\d{2,}\b")
RELATIONAL = {"<", ">", "<=", ">="}
NAME = re.compile(r"^[a-z][\w -]*$")  # a name as options and files spell them
STD_DISTRIBUTION = re.compile(r"^(uniform_(int|real)|normal|bernoulli|binomial|negative_binomial|poisson|exponential|gamma|weibull|"
                              r"extreme_value|discrete|piecewise_constant|piecewise_linear|lognormal|chi_squared|cauchy|fisher_f|"
                              r"student_t|geometric)_distribution$")


class Token:
    __slots__ = ("kind", "text", "line")

    def __init__(self, kind, text, line):
        self.kind, self.text, self.line = kind, text, line


_index = None


def libclang():
    """libclang, from Debian's LLVM 14 (python3-clang-14) or wherever the bindings find it."""
    global _index
    if _index is None:
        found = sorted(glob.glob("/usr/lib/llvm-*/lib/libclang-*.so.1") + glob.glob("/usr/lib/llvm-*/lib/libclang.so.1"))
        if found and not ci.Config.loaded:
            ci.Config.set_library_file(found[-1])
        _index = ci.Index.create()
    return _index


def tokens_of(path):
    """The file's tokens as clang's lexer makes them (no includes are read), comments dropped."""
    unit = libclang().parse(path, args=["-x", "c++", "-std=c++17", "-nostdinc", "-nostdinc++", "-fsyntax-only"],
                            options=ci.TranslationUnit.PARSE_SKIP_FUNCTION_BODIES)
    out = []
    for t in unit.cursor.get_tokens():
        if t.kind == ci.TokenKind.COMMENT or str(t.location.file) != path:
            continue
        out.append(Token(t.kind.name, t.spelling, t.location.line))
    return out


def integer_value(text):
    """A C++ integer literal's value, or None for any other token."""
    t = text.replace("'", "").rstrip("uUlL")
    try:
        if re.fullmatch(r"0[xX][0-9a-fA-F]+", t):
            return int(t, 16)
        if re.fullmatch(r"0[bB][01]+", t):
            return int(t, 2)
        if re.fullmatch(r"\d+", t):
            return int(t, 8) if len(t) > 1 and t[0] == "0" else int(t)
    except ValueError:
        return None
    return None


def is_string(tok):
    return tok.kind == "LITERAL" and (tok.text.startswith('"') or re.match(r'^(u8|u|U|L|R|u8R|uR|UR|LR)"', tok.text))


def string_value(tok):
    text = tok.text
    start = text.index('"')
    return text[start + 1:-1]


class Source:
    def __init__(self, root, path):
        self.path = path
        self.full = os.path.join(root, path)
        with open(self.full, encoding="utf-8") as f:
            self.lines = f.read().split("\n")
        self.cpp = path.endswith((".cc", ".h"))
        self.test = path.startswith("tests/")
        self.limits_file = bool(LIMITS.match(path))
        self.tokens = tokens_of(self.full) if self.cpp else []

    def close(self, i):
        """The index of the bracket closing the one at i."""
        pairs = {"(": ")", "[": "]", "{": "}"}
        opening, depth = self.tokens[i].text, 0
        for k in range(i, len(self.tokens)):
            t = self.tokens[k].text
            if t == opening:
                depth += 1
            elif t == pairs[opening]:
                depth -= 1
                if depth == 0:
                    return k
        return len(self.tokens) - 1

    def statement(self, i):
        """The tokens from i to the end of the statement (a ; at the depth of i)."""
        depth = 0
        for k in range(i, len(self.tokens)):
            t = self.tokens[k].text
            if t in "([{":
                depth += 1
            elif t in ")]}":
                depth -= 1
                if depth < 0:
                    return self.tokens[i:k]
            elif t == ";" and depth == 0:
                return self.tokens[i:k + 1]
        return self.tokens[i:]

    def text(self, i):
        return self.tokens[i].text if 0 <= i < len(self.tokens) else ""


def sources(root):
    for folder, dirs, files in os.walk(root):
        rel_folder = os.path.relpath(folder, root)
        dirs[:] = [d for d in dirs if d not in SKIP_DIRS and not d.startswith("build")]
        for name in files:
            if name.endswith((".cc", ".h", ".py")):
                yield os.path.normpath(os.path.join(rel_folder, name))


def large(tokens):
    """A literal above 16 or a shift among tokens: a bound that should have a name."""
    return any(t.text == "<<" or (t.kind == "LITERAL" and (integer_value(t.text) or 0) > 16) for t in tokens)


def template_bracket(tokens, k):
    """Whether the < or > at k encloses a template argument (group<3>(...)), not a comparison."""
    text = lambda j: tokens[j].text if 0 <= j < len(tokens) else ""
    if text(k) == "<":
        return k > 0 and tokens[k - 1].kind == "IDENTIFIER" and text(k + 2) == ">"
    return text(k - 2) == "<" and k >= 3 and tokens[k - 3].kind == "IDENTIFIER"


def json_aliases(all_sources):
    """Names that stand for nlohmann's JSON type anywhere (type aliases, typedefs, using-
    declarations), and per file the names a using-directive or namespace alias makes."""
    global_names, per_file = set(), {}
    changed = True
    while changed:
        changed = False
        for s in all_sources:
            local = per_file.setdefault(s.path, set())
            toks = s.tokens
            for i, t in enumerate(toks):
                if t.text == "using" and s.text(i + 2) == "=":
                    rhs = {x.text for x in s.statement(i + 3)}
                    if ("nlohmann" in rhs and rhs & NLOHMANN_TYPES) or rhs & global_names:
                        if toks[i + 1].text not in global_names:
                            global_names.add(toks[i + 1].text)
                            changed = True
                elif t.text == "typedef":
                    stmt = s.statement(i)
                    names = {x.text for x in stmt}
                    if ("nlohmann" in names and names & NLOHMANN_TYPES) or names & global_names:
                        alias = stmt[-2].text if len(stmt) >= 2 else ""
                        if alias and alias not in global_names:
                            global_names.add(alias)
                            changed = True
                elif t.text == "using" and s.text(i + 1) == "nlohmann" and s.text(i + 2) == "::":
                    local.add(s.text(i + 3))
                elif t.text == "using" and s.text(i + 1) == "namespace" and s.text(i + 2) == "nlohmann":
                    local.update(NLOHMANN_TYPES)
                elif t.text == "namespace" and s.text(i + 2) == "=" and s.text(i + 3) == "nlohmann":
                    local.update({s.text(i + 1) + "::" + n for n in NLOHMANN_TYPES})
    return global_names, per_file


def check_cpp(s, findings, json_names):
    toks = s.tokens
    line_of = lambda i: toks[i].line if i < len(toks) else toks[-1].line
    add = lambda i, message: findings.append(f"{s.path}:{line_of(i)}: {message}")
    raw = lambda i: s.lines[line_of(i) - 1] if line_of(i) - 1 < len(s.lines) else ""
    library = not s.test
    for i, t in enumerate(toks):
        text = t.text
        # Limits outside a library's limits.h.
        if library and not s.limits_file:
            if text == "constexpr":
                stmt = s.statement(i)
                names = [x.text for x in stmt]
                end = next((k for k, x in enumerate(names) if x in ("=", "{", ";", "(")), len(names))
                declared = names[:end]
                if any(re.match(r"^k(Max|Min)[A-Z]", n) for n in declared):
                    add(i, "a limit defined outside a library's limits.h")
                elif any(n.endswith("Limits") for n in declared) and large(stmt[end:]):
                    add(i, "a limits object filled with literals outside a library's limits.h")
            if text in (".", "->") and re.match(r"^(max|min)_\w+$", s.text(i + 1)) and s.text(i + 2) == "=":
                if large(s.statement(i + 3)):
                    add(i, "a limit assigned outside a library's limits.h")
            if text in CHECKED_READS and s.text(i + 1) == "(":
                if large(toks[i + 2:s.close(i + 1)]):
                    add(i, f"a limit written in a call to {text}; name it in a limits.h")
            if text == "if" and s.text(i + 1) == "(":
                end = s.close(i + 1)
                after = s.text(end + 1)
                throws = after == "throw" or (after == "{" and s.text(end + 2) == "throw")
                condition = toks[i + 2:end]
                if throws and any(x.text == "<<" for x in condition) or throws and any(
                        condition[k].text in RELATIONAL and not template_bracket(condition, k) and any(
                            (integer_value(condition[j].text) or 0) >= 3 for j in (k - 1, k + 1) if 0 <= j < len(condition))
                        for k in range(len(condition))):
                    add(i, "a bound written in a refusal; name it in a limits.h")
        if library and text in OPTION_CALLS and s.text(i + 1) == "(":
            for x in toks[i + 2:s.close(i + 1)]:
                if is_string(x) and HELP_RANGE.search(string_value(x)):
                    add(i, "a range written in a help text; build it from its limit")
                    break
        # Tolerance literals.
        if library and not s.limits_file and s.path not in TOLERANCES and t.kind == "LITERAL" and SCIENTIFIC.match(text) \
                and INPUT_MARK not in raw(i):
            add(i, f"a tolerance literal outside the tolerance table ({text})")
        if s.test and text in ("EXPECT_NEAR", "ASSERT_NEAR") and s.text(i + 1) == "(":
            args, depth, current = [], 0, []
            for x in toks[i + 2:s.close(i + 1)]:
                if x.text in "([{":
                    depth += 1
                elif x.text in ")]}":
                    depth -= 1
                if x.text == "," and depth == 0:
                    args.append(current)
                    current = []
                else:
                    current.append(x)
            args.append(current)
            bound = [x for x in args[-1] if x.text not in ("-", "+")]
            if len(args) == 3 and len(bound) == 1 and bound[0].kind == "LITERAL":
                add(i, "a NEAR bound that is a literal, not a named tolerance")
        # Table and design paths.
        if is_string(t):
            value = string_value(t)
            for home, stem in ((TABLE_IO, "order_"), (DESIGNS, "t_")):
                if s.path == home:
                    continue
                built = False
                if value.endswith(stem):
                    rest = s.statement(i)
                    built = any(is_string(x) and string_value(x).startswith(".json") for x in rest[1:])
                elif re.search(re.escape(stem) + r"(\{\w*\}|%\w+)\.json", value):
                    built = True
                if built:
                    add(i, f"a {'lobe table' if stem == 'order_' else 'design'} path built outside its one builder ({home})")
        # Threads, random distributions, pi.
        if library and s.path not in (PARALLEL, WATCHDOG):
            if text == "std" and s.text(i + 1) == "::" and s.text(i + 2) in THREAD_NAMES and \
                    not (s.text(i + 3) == "::" and s.text(i + 4) == "hardware_concurrency"):
                add(i, f"threads started outside {PARALLEL}")
            if text == "pthread_create":
                add(i, f"threads started outside {PARALLEL}")
        if t.kind == "IDENTIFIER" and text.endswith("_distribution") and (s.text(i - 2) == "std" or STD_DISTRIBUTION.match(text)):
            add(i, f"{text} is implementation-defined; use {RANDOM}")
        if library and s.path != SH_EVAL:
            if text == "M_PI" or (t.kind == "LITERAL" and text.startswith("3.14159")):
                add(i, f"pi written out; use runtime::kPi or kPiLong ({SH_EVAL})")
            if text in INVERSE_TRIG and s.text(i + 1) == "(":
                args = toks[i + 2:s.close(i + 1)]
                if args and all(x.kind == "LITERAL" or x.text in ("-", "+", ",", ".") for x in args):
                    add(i, f"pi from {text} of constants; use runtime::kPi or kPiLong ({SH_EVAL})")
        # A name returned per case.
        if library and text in ("case", "default"):
            k = i + 1
            while k < len(toks) and not (toks[k].text == ":" and s.text(k + 1) != ":" and s.text(k - 1) != ":"):
                k += 1
            k += 1
            while s.text(k) == "{":
                k += 1
            if s.text(k) == "return" and k + 1 < len(toks) and is_string(toks[k + 1]) and NAME.match(string_value(toks[k + 1])) \
                    and s.text(k + 2) == ";":
                add(i, "a name returned per case; write the names in a runtime::EnumName table")
        # JSON parsed outside io/src/json.cc; the runtime's parser outside the runtime.
        if library and s.path != JSON_PARSER and text in JSON_PARSES and s.text(i - 1) == "::":
            qualifier = s.text(i - 2)
            qualified = s.text(i - 4) + "::" + qualifier if s.text(i - 3) == "::" else qualifier
            names_here = json_names[1].get(s.path, set())
            if qualifier in json_names[0] or qualified in names_here or qualifier in names_here or \
                    (qualifier in NLOHMANN_TYPES and s.text(i - 4) == "nlohmann"):
                add(i, f"JSON parsed outside {JSON_PARSER}; read it with io::json (io/json.h)")
        if not s.path.startswith(RUNTIME_JSON_USERS):
            if text == "runtime" and s.text(i + 1) == "::" and s.text(i + 2) == "json" and s.text(i + 3) == "::":
                add(i, "the runtime's JSON parser outside the runtime; read JSON with io::json (io/json.h)")
            if is_string(t) and string_value(t) == "zhf/runtime/json.h":
                add(i, "the runtime's JSON parser outside the runtime; read JSON with io::json (io/json.h)")
    # Aliases of threads and distributions are findings themselves where threads may not start.
    for i, t in enumerate(toks):
        if t.text == "using" and s.text(i + 1) == "std" and s.text(i + 2) == "::":
            if s.text(i + 3) in THREAD_NAMES and library and s.path not in (PARALLEL, WATCHDOG):
                add(i, f"an alias of std::{s.text(i + 3)} outside {PARALLEL}")


PY_TABLE_NAME = re.compile(r"(order_\" \+ [^+]+ \+ \"\.json|order_\{\w+\}\.json)")
PY_DESIGN_NAME = re.compile(r"t_\" \+ [^+]+ \+ \"\.json|t_\{\w+\}\.json")


def check_python(s, findings):
    for number, raw in enumerate(s.lines, 1):
        line = raw.split("#")[0]
        if PY_TABLE_NAME.search(line):
            findings.append(f"{s.path}:{number}: a lobe table path built outside runtime::table_path ({TABLE_IO})")
        if PY_DESIGN_NAME.search(line):
            findings.append(f"{s.path}:{number}: a design path built outside frames::design_path ({DESIGNS})")


FLOOR_ENTRY = re.compile(r"^inline (?:constexpr [\w: ]+?|double) (k\w+|\w+)(?: =|\()")
SECOND_ENTRY = re.compile(r", (k\w+) =")


def entries(text):
    out = []
    for number, line in enumerate(text.split("\n"), 1):
        m = FLOOR_ENTRY.match(line)
        if m:
            out.append((number, m.group(1)))
            out.extend((number, e) for e in SECOND_ENTRY.findall(line))
    return out


def check_tables(root, all_paths, findings):
    """The runtime's floor, and every tolerance named where its table says it is used."""
    def read(path):
        with open(os.path.join(root, path), encoding="utf-8") as f:
            return f.read()
    runtime_texts = {p: read(p) for p in all_paths if p.startswith(RUNTIME)}
    for home in RUNTIME_FLOOR:
        if home not in runtime_texts:
            continue
        for number, entry in entries(runtime_texts[home]):
            name = re.compile(r"\b" + entry + r"\b")
            if sum(len(name.findall(text)) for text in runtime_texts.values()) < 2:
                findings.append(f"{home}:{number}: {entry} is not named by the runtime; "
                                "it belongs to its readers' limits.h or to tolerances/tolerances.h")
    texts = {p: read(p) for p in all_paths if p.endswith((".cc", ".h", ".py"))}
    for home, users, elsewhere in ((LIBRARY_TOLERANCES, lambda p: not p.startswith("tests/"), "tests/support/test_tolerances.h"),
                                   (TEST_TOLERANCES, lambda p: p.startswith("tests/"), "nowhere: remove it")):
        if home not in texts:
            continue
        for number, entry in entries(texts[home]):
            name = re.compile(r"\b" + entry + r"\b")
            inside = len(name.findall(texts[home]))
            used = any(name.search(text) for path, text in texts.items() if path != home and users(path))
            if not used and inside < 2:
                findings.append(f"{home}:{number}: {entry} is used {'by no library' if home == LIBRARY_TOLERANCES else 'by no test'}; "
                                f"it belongs in {elsewhere}")


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--root", default=ROOT, help="the tree to check (default: this checkout)")
    args = parser.parse_args()
    root = os.path.abspath(args.root)
    paths = sorted(p for p in sources(root) if p != "scripts/check_one_place.py")
    all_sources = [Source(root, p) for p in paths]
    json_names = json_aliases([s for s in all_sources if s.cpp])
    findings = []
    check_tables(root, paths, findings)
    for s in all_sources:
        if s.cpp:
            check_cpp(s, findings, json_names)
        else:
            check_python(s, findings)
    for finding in findings:
        print(finding)
    if findings:
        print(f"check_one_place: {len(findings)} finding(s)", file=sys.stderr)
        return 1
    print("check_one_place: limits, tolerances, the runtime's floor, table and design paths, threads, random draws, "
          "enum names, JSON reading and pi each in one place")
    return 0


if __name__ == "__main__":
    sys.exit(main())
