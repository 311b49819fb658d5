#!/usr/bin/python3
"""The rules of scripts/check_one_place.py, each on a small tree of its own: every way round the
line-by-line rules it replaced (a bound on the next line, a limits struct, pi from acos, a case and
its return on two lines, JSON parsed through a using-declaration or an alias, a bound in a
refusal) is a finding, and the same code written the house's way is not.
Run: /usr/bin/python3 tests/scripts/check_one_place_test.py
"""
import os
import subprocess
import sys
import tempfile
import unittest

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
CHECKER = os.path.join(ROOT, "scripts", "check_one_place.py")


def run_on(files):
    """The checker's exit code and output on a tree holding files {path: text}."""
    with tempfile.TemporaryDirectory() as root:
        for path, text in files.items():
            full = os.path.join(root, path)
            os.makedirs(os.path.dirname(full), exist_ok=True)
            with open(full, "w") as f:
                f.write(text)
        r = subprocess.run([sys.executable, CHECKER, "--root", root], capture_output=True, text=True)
        return r.returncode, r.stdout + r.stderr


class Bypasses(unittest.TestCase):
    def found(self, files, message, line=None):
        code, out = run_on(files)
        self.assertEqual(code, 1, out)
        self.assertIn(message, out)
        if line:
            self.assertIn(line, out)

    def clean(self, files):
        code, out = run_on(files)
        self.assertEqual(code, 0, out)

    def test_a_bound_on_the_next_line(self):
        self.found({"cli/count.cc": 'int f(const std::string& t) {\n  return integer_option("--count", t, 1,\n'
                                    '                        100000);\n}\n'},
                   "a limit written in a call to integer_option", "cli/count.cc:2")
        self.clean({"cli/count.cc": 'int f(const std::string& t) {\n  return integer_option("--count", t, 1,\n'
                                    '                        kMaxCount);\n}\n'})

    def test_a_limits_struct(self):
        self.found({"splat/src/glb.cc": "static constexpr io::json::Limits kJsonLimits{32, std::size_t(1) << 20, 1 << 16};\n"},
                   "a limits object filled with literals")
        self.found({"splat/src/glb.cc": "void f() {\n  io::json::Limits limits;\n  limits.max_depth =\n      32;\n}\n"},
                   "a limit assigned outside a library's limits.h")
        self.clean({"splat/src/glb.cc": "void f() {\n  io::json::Limits limits;\n  limits.max_depth = kMaxGlbJsonDepth;\n}\n"})

    def test_pi_from_acos(self):
        self.found({"frames/src/x.cc": "const double pi = std::acos(-1.0);\n"}, "pi from acos of constants")
        self.found({"frames/src/x.cc": "const double pi = 4 * atan(\n    1);\n"}, "pi from atan of constants")
        self.clean({"frames/src/x.cc": "double angle(double c) { return std::acos(c); }\n"})

    def test_a_case_and_its_return_on_two_lines(self):
        self.found({"codegen/src/x.cc": "const char* name(Path p) {\n  switch (p) {\n    case Path::kScalar:\n"
                                        "      return \"scalar\";\n    default: break;\n  }\n  return \"\";\n}\n"},
                   "a name returned per case", "codegen/src/x.cc:3")
        self.clean({"codegen/src/x.cc": "std::string code(Mode m) {\n  switch (m) {\n    case Mode::kA:\n"
                                        "      return \"f(r, c, &o);\";\n    default: break;\n  }\n  return \"\";\n}\n"})

    def test_json_parsed_after_a_using(self):
        self.found({"bench/src/x.cc": "using nlohmann::json;\nint f(const std::string& t) { return json::parse(t).size(); }\n"},
                   "JSON parsed outside io/src/json.cc")
        self.found({"bench/src/x.cc": "using Document = nlohmann::ordered_json;\nauto f(const std::string& t) {\n  return Document::\n"
                                      "      parse(t);\n}\n"},
                   "JSON parsed outside io/src/json.cc")
        # An alias made in a header, used elsewhere.
        self.found({"io/include/zhf/io/doc.h": "using Doc = nlohmann::json;\n",
                    "cli/x.cc": "#include \"zhf/io/doc.h\"\nauto f(const std::string& t) { return Doc::parse(t); }\n"},
                   "cli/x.cc:2: JSON parsed outside")
        self.clean({"cli/x.cc": "auto f(const std::string& t) { return io::json::parse(t, \"x\"); }\n"})

    def test_a_bound_in_a_refusal(self):
        self.found({"cli/x.cc": "void f(const std::vector<int>& sizes) {\n  if (sizes.size()\n      > 16) throw UsageError(\"too many\");\n}\n"},
                   "a bound written in a refusal")
        self.clean({"cli/x.cc": "void f(const std::vector<int>& s) {\n  if (s.size() > kMaxSizes) throw UsageError(\"too many\");\n"
                                "  if (s.size() < 2) throw UsageError(\"two at least\");\n  if (group<3>(s)) throw UsageError(\"x\");\n}\n"})

    def test_threads_and_random_draws_through_an_alias(self):
        self.found({"frames/src/x.cc": "using std::thread;\nvoid f() { thread t([] {}); t.join(); }\n"}, "an alias of std::thread")
        self.found({"frames/src/x.cc": "using namespace std;\nuniform_real_distribution<double> u(0, 1);\n"},
                   "uniform_real_distribution is implementation-defined")

    def test_a_tolerance_only_tests_use_lives_with_the_tests(self):
        table = "namespace zhf::tolerance {\ninline constexpr double kOnlyTests = 1e-9;\n}\n"
        self.found({"tolerances/include/zhf/tolerances/tolerances.h": table,
                    "tests/x/x_test.cc": "EXPECT_NEAR(a, b, tolerance::kOnlyTests);\n"},
                   "kOnlyTests is used by no library")
        self.clean({"tolerances/include/zhf/tolerances/tolerances.h": table,
                    "frames/src/x.cc": "bool close(double a) { return a < tolerance::kOnlyTests; }\n"})


if __name__ == "__main__":
    unittest.main()
