// zhf as a hostile or careless user meets it: every class of bad input, output target, injection
// attempt and interrupt, through the real binary. For each trial: the documented exit code,
// exactly one line on stderr for a refusal, no file created or changed in the sandbox (types,
// sizes and contents compared before and after), nothing left in the private TMPDIR, nothing run
// that was not asked for. At the end the suite prints its trials per class (docs/usage.md has the
// table). ZHF_TEST_BINARY runs it against another build of zhf.
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/syscall.h>
#include <sys/sysmacros.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <filesystem>
#include <functional>
#include <map>
#include <thread>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/io/limits.h"
#include "zhf/io/process.h"
#include "zhf/runtime/limits.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/product.h"
#include "zhf/runtime/rotator.h"
#include "zhf/runtime/zonal.h"


namespace zhf::test {
namespace {

namespace fs = std::filesystem;

const std::string kTable3 = source_path("generated/lobes/order_3.json");

// Trials per class, and how many were clean.
std::map<std::string, std::pair<int, int>>& tally() {
  static std::map<std::string, std::pair<int, int>> t;
  return t;
}

class Tally : public ::testing::Environment {
 public:
  void TearDown() override {
    int trials = 0, clean = 0;
    std::printf("\nhostile trials per class (clean / all):\n");
    for (const auto& [name, counts] : tally()) {
      std::printf("  %-60s %3d / %d\n", name.c_str(), counts.second, counts.first);
      trials += counts.first;
      clean += counts.second;
    }
    std::printf("  %-60s %3d / %d\n", "all", clean, trials);
  }
};
const auto* const kTally = ::testing::AddGlobalTestEnvironment(new Tally);

// One entry of a directory tree as a user would notice a change in it.
struct Entry {
  char type = '?';  // f file, d directory, l link, p FIFO, c device, s socket
  std::uintmax_t size = 0;
  std::string content;  // files: the bytes; links: the target
  bool operator==(const Entry& o) const { return type == o.type && size == o.size && content == o.content; }
};
using Snapshot = std::map<std::string, Entry>;

Snapshot snapshot(const std::string& dir) {
  Snapshot out;
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, ec); it != fs::recursive_directory_iterator(); it.increment(ec)) {
    struct stat st {};
    const std::string path = it->path().string();
    if (lstat(path.c_str(), &st) != 0) continue;
    Entry e;
    if (S_ISREG(st.st_mode)) {
      e.type = 'f';
      e.size = st.st_size;
      e.content = read_text(path);
    } else if (S_ISDIR(st.st_mode)) {
      e.type = 'd';
    } else if (S_ISLNK(st.st_mode)) {
      e.type = 'l';
      e.content = fs::read_symlink(path, ec).string();
      it.disable_recursion_pending();
    } else if (S_ISFIFO(st.st_mode)) {
      e.type = 'p';
    } else if (S_ISCHR(st.st_mode)) {
      e.type = 'c';
    }
    out[it->path().lexically_relative(dir).string()] = e;
  }
  return out;
}

// A private directory for one trial, with a TMPDIR of its own for zhf.
class Sandbox {
 public:
  Sandbox() : dir_(make_temp_dir()) { fs::create_directories(tmp()); }
  ~Sandbox() { remove_dir(dir_); }
  std::string path(const std::string& name) const { return dir_ + "/" + name; }
  std::string tmp() const { return dir_ + "/.tmp"; }
  const std::string& dir() const { return dir_; }
  std::string write(const std::string& name, const std::string& text) const {
    fs::create_directories(fs::path(path(name)).parent_path());
    write_text(path(name), text);
    return path(name);
  }
  RunResult run(const std::vector<std::string>& args, std::vector<std::string> environment = {}) const {
    bool tmpdir_given = false;
    for (const std::string& e : environment) tmpdir_given = tmpdir_given || e.rfind("TMPDIR=", 0) == 0;
    if (!tmpdir_given) environment.push_back("TMPDIR=" + tmp());
    return run_zhf(args, dir_, environment);
  }

 private:
  std::string dir_;
};

std::string leftovers(const Sandbox& box) {
  std::string found;
  for (const auto& [path, entry] : snapshot(box.dir()))
    if (path.rfind(".tmp/", 0) == 0 || path.find(".tmp.") != std::string::npos || path.find(".zhf-staging") != std::string::npos)
      found += " " + path;
  return found;
}

// A refusal: the code, one line naming what is wrong, and the sandbox exactly as it was.
bool refused(const std::string& what, const Sandbox& box, const std::vector<std::string>& args, int code,
             const std::string& needle, const std::vector<std::string>& environment = {}) {
  const Snapshot before = snapshot(box.dir());
  const RunResult r = box.run(args, environment);
  const Snapshot after = snapshot(box.dir());
  bool clean = true;
  auto check = [&](bool ok, const std::string& message) {
    EXPECT_TRUE(ok) << what << ": " << message;
    clean = clean && ok;
  };
  check(r.exit_code == code, "exit " + std::to_string(r.exit_code) + " (signal " + std::to_string(r.signal) + "), expected " +
                                 std::to_string(code) + "; stderr: " + r.err.substr(0, 400));
  check(line_count(r.err) == 1, "stderr is not one line: " + r.err.substr(0, 400));
  check(r.err.find(needle) != std::string::npos, "stderr lacks '" + needle + "': " + r.err.substr(0, 400));
  check(r.err.find("internal error") == std::string::npos, "an internal error: " + r.err.substr(0, 400));
  check(before == after, "the sandbox changed");
  check(leftovers(box).empty(), "left behind:" + leftovers(box));
  ++tally()[::testing::UnitTest::GetInstance()->current_test_info()->name()].first;
  tally()[::testing::UnitTest::GetInstance()->current_test_info()->name()].second += clean;
  return clean;
}

// A run that must succeed; what it may change is the caller's to check.
RunResult succeeded(const std::string& what, const Sandbox& box, const std::vector<std::string>& args,
                    const std::vector<std::string>& environment = {}) {
  const RunResult r = box.run(args, environment);
  const bool clean = r.exit_code == 0 && leftovers(box).empty();
  EXPECT_EQ(r.exit_code, 0) << what << ": " << r.err.substr(0, 400);
  EXPECT_EQ(leftovers(box), "") << what;
  ++tally()[::testing::UnitTest::GetInstance()->current_test_info()->name()].first;
  tally()[::testing::UnitTest::GetInstance()->current_test_info()->name()].second += clean;
  return r;
}

// Drains a FIFO on a thread while zhf writes into it.
class FifoReader {
 public:
  explicit FifoReader(const std::string& path) {
    mkfifo(path.c_str(), 0600);
    fd_ = ::open(path.c_str(), O_RDONLY | O_NONBLOCK);
    thread_ = std::thread([this] {
      char buffer[4096];
      while (true) {
        const ssize_t got = ::read(fd_, buffer, sizeof buffer);
        if (got > 0) {
          text_.append(buffer, static_cast<size_t>(got));
        } else if (done_.load()) {
          break;
        } else {
          std::this_thread::sleep_for(std::chrono::milliseconds(2));
        }
      }
    });
  }
  ~FifoReader() { finish(); }
  const std::string& finish() {
    if (thread_.joinable()) {
      done_ = true;
      thread_.join();
      ::close(fd_);
    }
    return text_;
  }

 private:
  int fd_ = -1;
  std::atomic<bool> done_{false};
  std::string text_;
  std::thread thread_;
};

std::string table_text(const std::function<void(nlohmann::json&)>& change, const std::string& source = kTable3) {
  nlohmann::json j = read_json(source);
  change(j);
  return j.dump();
}

std::string deep(char open, int depth) { return std::string(depth, open); }

}  // namespace

TEST(Hostile, OutputsThatAreNotRegularFilesAreWrittenThroughNeverReplaced) {
  {
    // As root, a private copy of /dev/null: a build that replaces devices must not break the machine.
    Sandbox box;
    std::string null_device = "/dev/null";
    if (geteuid() == 0 && mknod(box.path("null").c_str(), S_IFCHR | 0666, makedev(1, 3)) == 0) null_device = box.path("null");
    succeeded("--json a device", box, {"candidates", "--order", "3", "--json", null_device});
    struct stat st {};
    ASSERT_EQ(stat(null_device.c_str(), &st), 0);
    EXPECT_TRUE(S_ISCHR(st.st_mode)) << null_device << " is no longer a device";
  }
  {
    Sandbox box;
    FifoReader reader(box.path("pipe.json"));
    succeeded("--json FIFO", box, {"candidates", "--order", "3", "--json", box.path("pipe.json")});
    EXPECT_EQ(reader.finish().rfind("{", 0), 0u) << "the FIFO's reader got: " << reader.finish().substr(0, 80);
    EXPECT_EQ(snapshot(box.dir())["pipe.json"].type, 'p');
  }
  {
    Sandbox box;
    fs::create_directories(box.path("out"));
    FifoReader reader(box.path("out/zhf_order3.h"));
    succeeded("emit into a FIFO", box, {"emit", "--table", kTable3, "--lang", "cpp", "--out", box.path("out")});
    EXPECT_NE(reader.finish().find("Generated by zhf"), std::string::npos);
    EXPECT_EQ(snapshot(box.dir())["out/zhf_order3.h"].type, 'p');
  }
  {
    Sandbox box;
    box.write("real/out.json", "old\n");
    fs::create_symlink("real/out.json", box.path("link.json"));
    succeeded("--json through a symlink", box, {"candidates", "--order", "3", "--json", box.path("link.json")});
    const Snapshot s = snapshot(box.dir());
    EXPECT_EQ(s.at("link.json").type, 'l');
    EXPECT_EQ(s.at("real/out.json").content.rfind("{", 0), 0u);
  }
  if (geteuid() != 0 || zhf_binary() == ZHF_BINARY) {  // another build, as root, might replace /dev/stdout
    Sandbox box;
    const RunResult r = succeeded("--json /dev/stdout", box, {"candidates", "--order", "3", "--json", "/dev/stdout"});
    EXPECT_NE(r.out.find("\"zhf-candidates-1\""), std::string::npos);
  }
  Sandbox box;
  fs::create_directories(box.path("dir.json"));
  refused("--json a directory", box, {"candidates", "--order", "3", "--json", box.path("dir.json")}, 4, "is a directory");
  box.write("file", "x");
  refused("--json under a file", box, {"candidates", "--order", "3", "--json", box.path("file/c.json")}, 4, "file/c.json");
}

TEST(Hostile, DeeplyNestedJsonIsRefusedEverywhere) {
  Sandbox box;
  const std::string nested = deep('[', 100000);
  box.write("deep.json", nested);
  box.write("tables/order_3.json", nested);
  box.write("tables9/order_9.json", nested);
  std::string coeffs81 = "[[";
  for (int i = 0; i < 81; ++i) coeffs81 += std::string(i ? ", " : "") + "0.1";
  box.write("c9.json", coeffs81 + "]]");
  box.write("tree/manifest.json", "{\"format\": \"zhf-manifest-2\", \"files\": " + nested + "}");
  const std::string depth = "nested deeper than 64 levels";
  refused("emit --table", box, {"emit", "--table", box.path("deep.json"), "--lang", "cpp", "--out", box.path("out")}, 3, depth);
  refused("rotate --tables", box, {"rotate", "--coeffs", box.path("c9.json"), "--tables", box.path("tables9"), "--zyz", "1 2 3", "--out", box.path("r.json")}, 3, depth);
  refused("generate --tables", box, {"generate", "--tables", box.path("tables"), "--out", box.path("out")}, 3, depth);
  refused("generate --scene", box, {"generate", "--scene", box.path("deep.json"), "--out", box.path("out")}, 3, depth);
  refused("verify --generated", box, {"verify", "--generated", box.path("tree"), "--langs", "cpp"}, 3, depth);
  refused("analyze --coeffs", box, {"analyze", "--coeffs", box.path("deep.json")}, 3, depth);
  refused("product --lhs", box, {"product", "--lhs", box.path("deep.json"), "--rhs", box.path("c9.json"), "--out", box.path("p.json")}, 3, depth);
  refused("frame --directions", box, {"frame", "--directions", box.path("deep.json"), "--bands", "0..2"}, 3, depth);
  EXPECT_THROW(runtime::read_lobe_table(box.path("deep.json")), runtime::InputError);
}

// 16 MiB of one object's distinct keys (about a million), fed to every JSON reader the CLI has:
// each refuses it (past the keys an object may have, or the file's size) in one line naming the
// file, with nothing written; none parses it quadratically.
TEST(Hostile, AMillionKeysAreRefusedEverywhere) {
  Sandbox box;
  std::string keys = "{";
  for (std::size_t k = 0; keys.size() < (std::size_t(16) << 20) - 32; ++k) keys += (k ? ",\"" : "\"") + std::to_string(k) + "\":0";
  keys += "}";
  box.write("keys.json", keys);
  box.write("tables/order_3.json", keys);
  box.write("tables9/order_9.json", keys);
  box.write("tree/manifest.json", keys);
  std::string coeffs81 = "[[";
  for (int i = 0; i < 81; ++i) coeffs81 += std::string(i ? ", " : "") + "0.1";
  box.write("c9.json", coeffs81 + "]]");
  refused("emit --table", box, {"emit", "--table", box.path("keys.json"), "--lang", "cpp", "--out", box.path("out")}, 3, "keys.json");
  refused("rotate --tables", box, {"rotate", "--coeffs", box.path("c9.json"), "--tables", box.path("tables9"), "--zyz", "1 2 3", "--out", box.path("r.json")}, 3, "order_9.json");
  refused("generate --tables", box, {"generate", "--tables", box.path("tables"), "--out", box.path("out")}, 3, "order_3.json");
  refused("generate --scene", box, {"generate", "--scene", box.path("keys.json"), "--out", box.path("out")}, 3, "keys.json");
  refused("verify --generated", box, {"verify", "--generated", box.path("tree"), "--langs", "cpp"}, 3, "manifest.json");
  refused("analyze --coeffs", box, {"analyze", "--coeffs", box.path("keys.json")}, 3, "keys.json");
  refused("rotate --coeffs", box, {"rotate", "--coeffs", box.path("keys.json"), "--zyz", "1 2 3", "--out", box.path("r.json")}, 3, "keys.json");
  refused("product --lhs", box, {"product", "--lhs", box.path("keys.json"), "--rhs", box.path("c9.json"), "--out", box.path("p.json")}, 3, "keys.json");
  refused("frame --directions", box, {"frame", "--directions", box.path("keys.json"), "--bands", "0..2"}, 3, "keys.json");
}

TEST(Hostile, WrongTablesAreRefused) {
  Sandbox box;
  std::string coeffs81 = "[[";
  for (int i = 0; i < 81; ++i) coeffs81 += std::string(i ? ", " : "") + "0.1";
  box.write("c9.json", coeffs81 + "]]");
  const std::string order9 = read_text(source_path("generated/lobes/order_9.json"));
  auto nan_at = [&](const std::string& key) {
    std::string text = order9;
    const size_t at = text.find(key) + key.size();
    return text.substr(0, at) + "NaN" + text.substr(text.find_first_of(",]", at));
  };
  box.write("nan_inverse/order_9.json", nan_at("\"inverse\": [\n        ["));
  box.write("nan_xyz/order_9.json", nan_at("\"xyz\": ["));
  box.write("misnamed/order_9.json", read_text(kTable3));
  box.write("truncated/order_9.json", order9.substr(0, order9.size() / 2));
  const std::vector<std::string> rotate = {"rotate", "--coeffs", box.path("c9.json"), "--zyz", "1 2 3", "--out", box.path("r.json"), "--tables"};
  auto with = [&](const std::string& dir) {
    std::vector<std::string> args = rotate;
    args.push_back(box.path(dir));
    return args;
  };
  refused("NaN in inverse", box, with("nan_inverse"), 3, "NaN and Infinity are not JSON numbers");
  refused("NaN in xyz", box, with("nan_xyz"), 3, "NaN and Infinity are not JSON numbers");
  refused("order_9.json holding order 3", box, with("misnamed"), 3, "order: is 3, but order 9 was expected");
  refused("a truncated table", box, with("truncated"), 3, "not valid JSON");
  box.write("short.json", table_text([](nlohmann::json& j) { j["order"] = 4; }));
  refused("order 4 with order 3's lobes", box, {"emit", "--table", box.path("short.json"), "--lang", "cpp", "--out", box.path("o")}, 3,
          "lobes: expected 7 entries, found 5");
}

TEST(Hostile, NoShellRunsAnything) {
  Sandbox box;
  const std::string evil = "x'; touch PWNED; echo '";
  succeeded("verify --work-dir with shell syntax", box,
            {"verify", "--orders", "3", "--langs", "cpp", "--rotations", "5", "--work-dir", box.path(evil)});
  EXPECT_FALSE(fs::exists(box.path("PWNED")));
  EXPECT_TRUE(fs::is_directory(box.path(evil)));
  // A tree at a path with spaces, quotes, $, ; and a newline verifies like any other.
  const std::string odd = "a b'c\"d$e;f\ng";
  const RunResult g = run_zhf({"generate", "--tables", source_path("generated/lobes"), "--out", box.path(odd)}, box.dir(),
                              {"TMPDIR=" + box.tmp()});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  const RunResult v = succeeded("verify --generated at an odd path", box,
                                {"verify", "--generated", box.path(odd), "--orders", "3", "--langs", "cpp", "--rotations", "5"});
  EXPECT_NE(v.out.find("verify: pass"), std::string::npos) << v.out;
  succeeded("bench --plot with shell syntax", box, {"bench", "--quick", "--orders", "2", "--plot", box.path("$(touch PWNED2)'q.svg")});
  EXPECT_FALSE(fs::exists(box.path("PWNED2")));
  EXPECT_FALSE(fs::exists(source_path("PWNED2")));
}

TEST(Hostile, NothingIsInjectedIntoEmittedSource) {
  Sandbox box;
  const std::string injected_path = box.write("t\n#error injected\n.json", read_text(kTable3));
  const std::string crlf_path = box.write("t\r#error cr.json", read_text(kTable3));
  auto no_injected_line = [](const std::string& text) {
    for (size_t at = text.find('\n'); at != std::string::npos; at = text.find('\n', at + 1))
      if (text.compare(at + 1, 6, "#error") == 0) return false;
    return text.find('\r') == std::string::npos;
  };
  succeeded("a table path with a newline", box, {"emit", "--table", injected_path, "--lang", "glsl", "--out", box.path("o1")});
  EXPECT_TRUE(no_injected_line(read_text(box.path("o1/zhf_order3.glsl"))));
  succeeded("a table path with a CR", box, {"emit", "--table", crlf_path, "--lang", "cpp", "--out", box.path("o2")});
  const std::string header = read_text(box.path("o2/zhf_order3.h"));
  EXPECT_TRUE(no_injected_line(header));
  succeeded("an out path with a newline", box, {"emit", "--table", kTable3, "--lang", "hlsl", "--out", box.path("o3\n#error x")});
  EXPECT_TRUE(no_injected_line(read_text(box.path("o3\n#error x/zhf_order3.hlsli"))));
  // The emitted header still compiles: nothing spliced or injected.
  const io::ProcessResult compiled = io::run_process({"c++", "-std=c++17", "-fsyntax-only", "-x", "c++", box.path("o2/zhf_order3.h")},
                                                     box.path("compile.log"));
  EXPECT_TRUE(compiled.ok()) << read_text(box.path("compile.log"));
  fs::remove(box.path("compile.log"));
  box.write("scene\n#error s.json", R"({"format": "zhf-scene-1", "targets": ["cpp"], "signals": [{"order": 3, "variants": ["standard"]}]})");
  succeeded("a scene name with a newline", box, {"generate", "--scene", box.path("scene\n#error s.json"), "--out", box.path("tree")});
  EXPECT_TRUE(no_injected_line(read_text(box.path("tree/cpp/zhf_order3.h"))));
  box.write("source_newline.json", table_text([](nlohmann::json& j) { j["lobes"][0]["source"] = "x\n#error y"; }));
  box.write("source_backslash.json", table_text([](nlohmann::json& j) { j["lobes"][0]["source"] = "x\\"; }));
  for (const std::string name : {"source_newline.json", "source_backslash.json"})
    refused(name, box, {"emit", "--table", box.path(name), "--lang", "cpp", "--out", box.path("o4")}, 3,
            "lobes[0].source: control characters and backslashes are not allowed");
  // Needlet evaluators: the prefix is refused unless it is an identifier; the command line is escaped.
  refused("needlets emit --prefix with a newline", box,
          {"needlets", "emit", "--lmax", "3", "--lang", "glsl", "--prefix", "a\n#error p", "--out", box.path("n.glsl")}, 2,
          "--prefix: must be an identifier");
  refused("needlets emit --binding out of range", box,
          {"needlets", "emit", "--lmax", "3", "--lang", "wgsl", "--binding", "1000", "--out", box.path("n.wgsl")}, 2,
          "--binding: must be 0..999");
  succeeded("needlets emit --out with a newline", box,
            {"needlets", "emit", "--lmax", "3", "--size", "16", "--lang", "cpp", "--out", box.path("n\n#error x.h")});
  EXPECT_TRUE(no_injected_line(read_text(box.path("n\n#error x.h"))));
}

TEST(Hostile, GenerateNeverOverwritesWhatItDidNotWrite) {
  Sandbox box;
  const std::string tables = source_path("generated/lobes");
  box.write("user/manifest.json", "{\"mine\": true}\n");
  refused("a user's manifest.json", box, {"generate", "--tables", tables, "--out", box.path("user")}, 4,
          "has a manifest.json zhf cannot read as its own");
  box.write("notes/notes.txt", "keep\n");
  refused("a user's directory", box, {"generate", "--tables", tables, "--out", box.path("notes")}, 4, "not empty and has no zhf manifest.json");
  const RunResult g = run_zhf({"generate", "--tables", tables, "--out", box.path("tree")}, box.dir(), {"TMPDIR=" + box.tmp()});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  write_text(box.path("tree/lobes/order_3.json"), read_text(box.path("tree/lobes/order_3.json")) + " ");
  refused("a zhf file the user edited", box, {"generate", "--tables", tables, "--out", box.path("tree")}, 4,
          "tree/lobes/order_3.json: exists and was not written by zhf (or was changed since)");
  write_text(box.path("tree/lobes/order_3.json"), read_text(kTable3));
  fs::remove(box.path("tree/cpp/zhf_order3.h"));
  fs::create_directories(box.path("tree/cpp/zhf_order3.h"));
  refused("a directory where a file goes", box, {"generate", "--tables", tables, "--out", box.path("tree")}, 4,
          "zhf_order3.h: exists and is not a regular file");
}

TEST(Hostile, ConcurrentGeneratesIntoOneNewDirectoryLeaveOneWinner) {
  for (int trial = 0; trial < 4; ++trial) {
    Sandbox box;
    const std::string out = box.path("new");
    std::vector<io::Process> runs;
    for (int k = 0; k < 2; ++k)
      runs.push_back(start_zhf({"generate", "--tables", source_path("generated/lobes"), "--out", out}, box.path("err" + std::to_string(k))));
    int winners = 0;
    bool clean = true;
    for (size_t k = 0; k < runs.size(); ++k) {
      const int code = exit_code_of(runs[k]);
      const std::string err = read_text(box.path("err" + std::to_string(k)));
      if (code == 0) {
        ++winners;
      } else {
        const bool ok = code == 4 && line_count(err) == 1 && err.find("another zhf generate is writing") != std::string::npos;
        EXPECT_TRUE(ok) << "trial " << trial << ": exit " << code << ", " << err;
        clean = clean && ok;
      }
    }
    EXPECT_GE(winners, 1) << "trial " << trial;
    // The tree is whole: every file has the bytes the manifest records.
    const nlohmann::json manifest = read_json(out + "/manifest.json");
    for (const auto& f : manifest["files"]) EXPECT_TRUE(fs::exists(out + "/" + f["path"].get<std::string>())) << f["path"];
    EXPECT_EQ(leftovers(box), "");
    ++tally()["ConcurrentGeneratesIntoOneNewDirectoryLeaveOneWinner"].first;
    tally()["ConcurrentGeneratesIntoOneNewDirectoryLeaveOneWinner"].second += clean && winners >= 1;
  }
}

// Starts zhf in the sandbox, sends it `sig` after `delay_ms`, and returns its exit code; its
// stderr goes to stderr_path when given.
int interrupted_exit(const Sandbox& box, const std::vector<std::string>& args, int sig, int delay_ms,
                     const std::string& stderr_path = "") {
  io::Process zhf = start_zhf(args, stderr_path, {"TMPDIR=" + box.tmp()});
  std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
  zhf.signal(sig);
  return exit_code_of(zhf);
}

TEST(Hostile, InterruptsStopChildrenAndLeaveThePreviousOutputs) {
  for (const auto& [sig, code] : {std::pair<int, int>{SIGINT, 130}, {SIGTERM, 143}}) {
    Sandbox box;
    box.write("report.json", "previous report\n");
    const Snapshot before = snapshot(box.dir());
    const int exit = interrupted_exit(box, {"verify", "--langs", "cpp", "--json", box.path("report.json")}, sig, 1500);
    const bool clean = exit == code && snapshot(box.dir()) == before && leftovers(box).empty();
    EXPECT_EQ(exit, code) << "verify, signal " << sig;
    EXPECT_EQ(read_text(box.path("report.json")), "previous report\n");
    EXPECT_EQ(leftovers(box), "") << "verify, signal " << sig;
    ++tally()[::testing::UnitTest::GetInstance()->current_test_info()->name()].first;
    tally()[::testing::UnitTest::GetInstance()->current_test_info()->name()].second += clean;
  }
  Sandbox box;
  box.write("b.json", "previous\n");
  const Snapshot before = snapshot(box.dir());
  const int exit = interrupted_exit(box, {"bench", "--quick", "--json", box.path("b.json"), "--plot", box.path("p.svg")}, SIGINT, 1500);
  EXPECT_EQ(exit, 130) << "bench";
  EXPECT_TRUE(snapshot(box.dir()) == before) << "bench changed the sandbox";
  EXPECT_EQ(leftovers(box), "") << "bench";
  ++tally()[::testing::UnitTest::GetInstance()->current_test_info()->name()].first;
  tally()[::testing::UnitTest::GetInstance()->current_test_info()->name()].second +=
      exit == 130 && snapshot(box.dir()) == before && leftovers(box).empty();
}

// One start of a free design search on many points (L-BFGS on the energy of 514 points, t = 31)
// runs for about a minute without polling (orbit searches poll every step): the watchdog ends it a
// grace period after the signal, its temporary output gone and the previous file as it was.
TEST(Hostile, WorkThatCannotPollIsEndedByTheWatchdog) {
  Sandbox box;
  box.write("design.json", "previous design\n");
  const Snapshot before = snapshot(box.dir());
  const test::TempDir errors_dir;
  const std::string errors = errors_dir.string() + "/stderr.txt";
  const int exit = interrupted_exit(box, {"designs", "--t", "31", "--count", "514", "--starts", "1", "--quiet", "--out", box.path("design.json")},
                                    SIGTERM, 1500, errors);
  EXPECT_EQ(exit, 143);
  // The watchdog's own line: the search did not poll, so the watchdog ended it (not the search's end).
  EXPECT_NE(read_text(errors).find("did not stop, ended it"), std::string::npos) << read_text(errors);
  EXPECT_TRUE(snapshot(box.dir()) == before) << "the sandbox changed";
  EXPECT_EQ(leftovers(box), "");
  ++tally()["WorkThatCannotPollIsEndedByTheWatchdog"].first;
  tally()["WorkThatCannotPollIsEndedByTheWatchdog"].second += exit == 143 && snapshot(box.dir()) == before && leftovers(box).empty();
}

// SIGTERM sent to each thread of a run in turn (tgkill), the watchdog's first: a run that cannot
// poll must still be ended by the watchdog, which takes no signal, within the grace period.
TEST(Hostile, SignalsToEveryThreadStillEndTheRun) {
  Sandbox box;
  box.write("design.json", "previous design\n");
  const Snapshot before = snapshot(box.dir());
  io::Process zhf = start_zhf({"designs", "--t", "31", "--count", "514", "--starts", "1", "--quiet", "--out", box.path("design.json")}, "",
                              {"TMPDIR=" + box.tmp()});
  std::this_thread::sleep_for(std::chrono::milliseconds(1500));
  std::vector<int> threads;
  for (const auto& task : fs::directory_iterator("/proc/" + std::to_string(zhf.pid()) + "/task"))
    threads.push_back(std::stoi(task.path().filename().string()));
  ASSERT_GE(threads.size(), 2u) << "no watchdog thread";
  std::sort(threads.begin(), threads.end(), std::greater<int>());  // the watchdog starts before the work's threads
  std::rotate(threads.begin(), threads.end() - 2, threads.end());  // so: the watchdog, the main thread, the rest
  const auto sent = std::chrono::steady_clock::now();
  for (int thread : threads) syscall(SYS_tgkill, zhf.pid(), thread, SIGTERM);
  const int exit = exit_code_of(zhf);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - sent).count();
  EXPECT_EQ(exit, 143) << threads.size() << " threads";
  EXPECT_LT(seconds, io::kInterruptGraceSeconds + 2.0);
  EXPECT_TRUE(snapshot(box.dir()) == before) << "the sandbox changed";
  EXPECT_EQ(leftovers(box), "");
  ++tally()["SignalsToEveryThreadStillEndTheRun"].first;
  tally()["SignalsToEveryThreadStillEndTheRun"].second += exit == 143 && snapshot(box.dir()) == before && leftovers(box).empty();
}

// Several outputs are one result, committed together or not at all: a SIGTERM while the commit
// waits for a reader of one output (a FIFO, written through first) leaves the other, a regular
// file, as it was, and the one line says so. (Committed one by one, the report was replaced before
// the FIFO was opened, and the line said it was not.)
TEST(Hostile, ASignalBetweenTwoOutputsChangesNeither) {
  const struct {
    std::string what;
    std::vector<std::string> args;
    std::string file;
  } runs[] = {
      {"analyze --out --scene-out", {"analyze", "--coeffs", source_path("examples/light.json"), "--out", "report.json", "--scene-out", "out.fifo"},
       "report.json"},
      {"needlets emit --out --data", {"needlets", "emit", "--order", "9", "--lang", "glsl", "--out", "kernel.glsl", "--data", "out.fifo"},
       "kernel.glsl"},
  };
  for (const auto& run : runs) {
    Sandbox box;
    box.write(run.file, "previous output\n");
    ASSERT_EQ(mkfifo(box.path("out.fifo").c_str(), 0600), 0);
    std::vector<std::string> args = run.args;
    for (std::string& a : args)
      if (a == run.file || a == "out.fifo") a = box.path(a);
    const Snapshot before = snapshot(box.dir());
    const test::TempDir errors_dir;
    const std::string errors = errors_dir.string() + "/stderr.txt";
    const int exit = interrupted_exit(box, args, SIGTERM, 2500, errors);
    const std::string err = read_text(errors);
    EXPECT_EQ(exit, 143) << run.what << ": " << err;
    EXPECT_EQ(read_text(box.path(run.file)), "previous output\n") << run.what;
    EXPECT_TRUE(snapshot(box.dir()) == before) << run.what << ": the sandbox changed";
    EXPECT_NE(err.find("previous outputs are as they were"), std::string::npos) << run.what << ": " << err;
    EXPECT_EQ(line_count(err), 1) << run.what << ": " << err;
    EXPECT_EQ(leftovers(box), "") << run.what;
    ++tally()["ASignalBetweenTwoOutputsChangesNeither"].first;
    tally()["ASignalBetweenTwoOutputsChangesNeither"].second +=
        exit == 143 && snapshot(box.dir()) == before && leftovers(box).empty();
  }
}

// A signal after the work's last check, while the output is being committed: here the commit
// waits in open(2) for a reader of the FIFO it writes through. Nothing reaches the FIFO, the
// run ends with 143 within the grace period, nothing is left behind.
TEST(Hostile, ASignalDuringTheCommitWritesNothing) {
  Sandbox box;
  const std::string fifo = box.path("out.fifo");
  ASSERT_EQ(mkfifo(fifo.c_str(), 0600), 0);
  const Snapshot before = snapshot(box.dir());
  const test::TempDir errors_dir;
  const std::string errors = errors_dir.string() + "/stderr.txt";
  const auto started = std::chrono::steady_clock::now();
  const int exit = interrupted_exit(box, {"designs", "--t", "5", "--quiet", "--out", fifo}, SIGTERM, 1500, errors);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  EXPECT_EQ(exit, 143) << read_text(errors);
  EXPECT_LT(seconds, 1.5 + io::kInterruptGraceSeconds + 2.0);
  const int reader = ::open(fifo.c_str(), O_RDONLY | O_NONBLOCK);  // nothing was written into it
  char byte = 0;
  EXPECT_LE(::read(reader, &byte, 1), 0);
  ::close(reader);
  EXPECT_TRUE(snapshot(box.dir()) == before) << "the sandbox changed";
  EXPECT_EQ(leftovers(box), "");
  ++tally()["ASignalDuringTheCommitWritesNothing"].first;
  tally()["ASignalDuringTheCommitWritesNothing"].second += exit == 143 && snapshot(box.dir()) == before && leftovers(box).empty();
}

TEST(Hostile, BenchLeavesUserFilesAloneAndReportsGnuplotFailing) {
  Sandbox box;
  box.write("p.csv", "a user's data\n");
  refused("--plot beside a user's CSV", box, {"bench", "--quick", "--quiet", "--orders", "2", "--plot", box.path("p.svg")}, 4,
          "p.csv: exists and was not written by zhf bench");
  box.write("bin/gnuplot", "#!/bin/sh\necho 'gnuplot: broken' >&2\nexit 1\n");
  fs::permissions(box.path("bin/gnuplot"), fs::perms::owner_all);
  const char* path = std::getenv("PATH");
  refused("--plot without gnuplot", box, {"bench", "--quick", "--quiet", "--orders", "2", "--json", box.path("b.json"), "--plot", box.path("q.svg")}, 4,
          "gnuplot is not installed", {"PATH=" + box.path("no-programs")});
  refused("gnuplot failing", box, {"bench", "--quick", "--quiet", "--orders", "2", "--json", box.path("b.json"), "--plot", box.path("q.svg")}, 4,
          "gnuplot failed", {"PATH=" + box.path("bin") + ":" + (path ? path : "/usr/bin:/bin")});
}

TEST(Hostile, AnOutputRefusedMeansNoOutputWritten) {
  Sandbox box;
  std::string order13 = "[[";
  for (int i = 0; i < 169; ++i) order13 += std::string(i ? ", " : "") + (i < 150 ? "0.5" : "0.25");
  box.write("c13.json", order13 + "]]");
  refused("analyze --scene-out beyond order 12", box,
          {"analyze", "--coeffs", box.path("c13.json"), "--tolerance", "1e-12", "--json", box.path("a.json"), "--scene-out", box.path("s.json")},
          2, "--scene-out: the data needs order 13");
}

TEST(Hostile, InputFaultsAreNeverInternalErrors) {
  Sandbox box;
  const RunResult g = run_zhf({"generate", "--tables", source_path("generated/lobes"), "--out", box.path("tree")}, box.dir(),
                              {"TMPDIR=" + box.tmp()});
  ASSERT_EQ(g.exit_code, 0) << g.err;
  nlohmann::json manifest = read_json(box.path("tree/manifest.json"));
  manifest["files"][1]["order"] = "three";
  write_text(box.path("tree/manifest.json"), manifest.dump());
  refused("a malformed manifest field", box, {"verify", "--generated", box.path("tree"), "--langs", "cpp"}, 3, "files[1].order: expected a number");
  box.write("afile", "x");
  refused("--work-dir naming a file", box, {"verify", "--orders", "3", "--langs", "cpp", "--work-dir", box.path("afile")}, 4, "--work-dir must be a directory");
  refused("a missing TMPDIR", box, {"verify", "--orders", "3", "--langs", "cpp"}, 4, "TMPDIR", {"TMPDIR=" + box.path("nowhere")});
}

TEST(Hostile, UnboundedWorkIsRefusedBeforeItStarts) {
  Sandbox box;
  refused("candidates --order 64", box, {"candidates", "--order", "64"}, 2, "--order: must be 3..32");
  refused("candidates --json beyond order 16", box, {"candidates", "--order", "17", "--json", box.path("c.json")}, 2, "up to order 16");
  refused("verify --orders 2..2147483647", box, {"verify", "--orders", "2..2147483647"}, 2, "--orders: must be 2..12");
  refused("optimize --threads 1000", box, {"optimize", "--order", "4", "--threads", "1000"}, 2, "--threads: must be 0..256");
  refused("needlets --B 1", box, {"needlets", "window", "--B", "1", "--lmax", "4096"}, 2, "--B: must be in [1.05, 64]");
  refused("needlets profile --B 64 --level 16", box, {"needlets", "profile", "--B", "64", "--level", "16"}, 2, "--level: level 16 of B = 64 reaches past band 1023");
  refused("needlets --lmax 64", box, {"needlets", "tables", "--lmax", "64"}, 2, "--lmax: must be 1..63");
  refused("needlets --sizes 3..1048576", box, {"needlets", "tables", "--lmax", "8", "--sizes", "3..1048576"}, 2, "--sizes: at most 16 sizes");
  refused("analyze /dev/zero", box, {"analyze", "--coeffs", "/dev/zero"}, 3, "larger than the limit of 67108864 bytes");
  box.write("big.txt", std::string((64 << 20) + 10, '1'));
  refused("a 64 MiB coefficient file", box, {"analyze", "--coeffs", box.path("big.txt")}, 3, "larger than the limit");
  box.write("huge.json", "[[" + std::string(10 << 20, '7') + "]]");
  const Snapshot before = snapshot(box.dir());
  const RunResult r = box.run({"emit", "--table", box.path("huge.json"), "--lang", "cpp", "--out", box.path("o")});
  EXPECT_EQ(r.exit_code, 3);
  EXPECT_LT(r.err.size(), 400u) << "a 10 MB token is echoed";
}

TEST(Hostile, OptionsAndNumbersAreReadExactly) {
  Sandbox box;
  box.write("c.json", "[[1, 0, 0, 0]]");
  refused("--tolerance nan", box, {"analyze", "--coeffs", box.path("c.json"), "--tolerance", "nan"}, 2, "--tolerance: 'nan' is not finite");
  refused("--max-condition nan", box, {"optimize", "--order", "3", "--max-condition", "nan"}, 2, "--max-condition: 'nan' is not finite");
  refused("--time-limit nan", box, {"optimize", "--order", "3", "--time-limit", "nan"}, 2, "--time-limit: 'nan' is not finite");
  refused("--seed -1", box, {"optimize", "--order", "3", "--seed", "-1"}, 2, "--seed: '-1' is not an integer in 0..18446744073709551615");
  refused("--orders 3x", box, {"verify", "--orders", "3x"}, 2, "--orders: '3x' is not an integer");
  refused("--order 4294967299", box, {"candidates", "--order", "4294967299"}, 2, "--order: must be 3..32");
  box.write("wrap.json", table_text([](nlohmann::json& j) { j["order"] = 4294967299ull; }));
  refused("a table's order 4294967299", box, {"emit", "--table", box.path("wrap.json"), "--lang", "cpp", "--out", box.path("o")}, 3,
          "order: must be 2..32 (got 4294967299)");
  std::string dup = read_text(kTable3);
  dup.insert(dup.find("\"order\""), "\"order\": 3,\n  ");
  box.write("dup.json", dup);
  refused("a duplicate key", box, {"emit", "--table", box.path("dup.json"), "--lang", "cpp", "--out", box.path("o")}, 3,
          "the key 'order' appears twice");
  box.write("nul.txt", std::string("1 0 0 0.2\0garbage\n", 18));
  refused("a NUL byte in a number", box, {"analyze", "--coeffs", box.path("nul.txt")}, 3, "line 1: '0.2\\x00garbage' is not a number");
  box.write("array.json", "[]");
  refused("a table that is an array", box, {"emit", "--table", box.path("array.json"), "--lang", "cpp", "--out", box.path("o")}, 3,
          "array.json: top level: expected an object, found an array");
  box.write("e308.json", "[[1e308, 0, 0, 0]]");
  refused("1e308 coefficients", box, {"analyze", "--coeffs", box.path("e308.json"), "--json", box.path("a.json")}, 3,
          "is beyond the largest coefficient magnitude");
  std::string binary;
  for (int i = 0; i < 300; ++i) binary += static_cast<char>((i * 37) & 0xff);
  box.write("binary.json", binary);
  refused("raw binary as a table", box, {"emit", "--table", box.path("binary.json"), "--lang", "cpp", "--out", box.path("o")}, 3,
          "binary.json: not valid JSON");
  refused("a singular matrix", box, {"rotate", "--coeffs", box.path("c.json"), "--matrix", "1 0 0 0 1 0 0 0 0", "--out", box.path("r.json")}, 2,
          "--matrix: rotation matrix is not orthonormal");
}

// Every malformed document, fed to every reader the CLI has: each one is refused with exit 3 and
// one line naming the file, and nothing is written.
TEST(Hostile, EveryReaderRefusesEveryMalformedDocument) {
  const std::string table = read_text(kTable3);
  std::string binary;
  for (int i = 0; i < 300; ++i) binary += static_cast<char>((i * 37 + 11) & 0xff);
  std::string duplicate = table;
  duplicate.insert(duplicate.find('{') + 1, "\"order\": 3, ");
  const std::vector<std::pair<std::string, std::string>> documents = {
      {"empty", ""},
      {"truncated", table.substr(0, table.size() / 2)},
      {"trailing garbage", table + " }x"},
      {"NaN", "[[NaN, 0, 0, 0]]"},
      {"-Infinity", "{\"order\": -Infinity}"},
      {"1e400", "[[1e400, 0, 0, 0]]"},
      {"duplicate key", duplicate},
      {"NUL byte", std::string("{\"order\"\0: 3}", 13)},
      {"raw binary", binary},
      {"a bare string", "\"hello\""},
      {"a 10 MB string", "[\"" + std::string(10 << 20, 'a') + "\"]"},
      {"100000 brackets", deep('[', 100000)},
      {"a lone surrogate", "[\"\\udc00\"]"},
      {"a number with a leading zero", "[[01, 0, 0, 0]]"},
  };
  for (const auto& [what, text] : documents) {
    Sandbox box;
    std::string coeffs9 = "[[";
    for (int i = 0; i < 81; ++i) coeffs9 += std::string(i ? ", " : "") + "0.1";
    box.write("c9.json", coeffs9 + "]]");
    box.write("bad.json", text);
    box.write("tables9/order_9.json", text);  // rotate reads tables only above the compiled orders
    box.write("tree/manifest.json", text);
    for (int order = 2; order <= 12; ++order)
      box.write(runtime::table_path("tables", order),
                order == 3 ? text : read_text(test::checked_in_table(order)));
    const std::vector<std::pair<std::string, std::vector<std::string>>> readers = {
        {"emit --table", {"emit", "--table", box.path("bad.json"), "--lang", "cpp", "--out", box.path("o")}},
        {"generate --tables", {"generate", "--tables", box.path("tables"), "--out", box.path("o")}},
        {"generate --scene", {"generate", "--scene", box.path("bad.json"), "--out", box.path("o")}},
        {"verify --generated", {"verify", "--generated", box.path("tree"), "--langs", "cpp"}},
        {"analyze --coeffs", {"analyze", "--coeffs", box.path("bad.json"), "--json", box.path("a.json")}},
        {"rotate --coeffs", {"rotate", "--coeffs", box.path("bad.json"), "--zyz", "1 2 3", "--out", box.path("r.json")}},
        {"rotate --tables", {"rotate", "--coeffs", box.path("c9.json"), "--tables", box.path("tables9"), "--zyz", "1 2 3", "--out", box.path("r.json")}},
        {"product --lhs", {"product", "--lhs", box.path("bad.json"), "--rhs", box.path("c9.json"), "--out", box.path("p.json")}},
        {"product --rhs", {"product", "--lhs", box.path("c9.json"), "--rhs", box.path("bad.json"), "--out", box.path("p.json")}},
        {"frame --directions", {"frame", "--directions", box.path("bad.json"), "--bands", "0..2", "--json", box.path("f.json")}},
    };
    for (const auto& [reader, args] : readers) {
      const std::string file = reader == "verify --generated" ? "manifest.json"
                               : reader == "generate --tables" ? "order_3.json"
                               : reader == "rotate --tables"   ? "order_9.json"
                                                               : "bad.json";
      refused(reader + " given " + what, box, args, 3, file);
    }
  }
}

TEST(Hostile, RuntimeEntryPointsRefuseWhatTheyCannotUse) {
  auto refuses = [](const char* what, auto&& call) {
    bool thrown = false;
    try {
      call();
    } catch (const std::invalid_argument&) {
      thrown = true;
    }
    EXPECT_TRUE(thrown) << what;
    ++tally()["RuntimeEntryPointsRefuseWhatTheyCannotUse"].first;
    tally()["RuntimeEntryPointsRefuseWhatTheyCannotUse"].second += thrown;
  };
  refuses("ZonalRotator(-3)", [] { runtime::ZonalRotator<float>{-3}; });
  refuses("ZonalRotator(0)", [] { runtime::ZonalRotator<float>{0}; });
  for (int order : {0, -3, 100}) {
    runtime::LobeTable table = runtime::read_lobe_table(kTable3);
    table.order = order;
    refuses("from_table with a bad order", [&] { runtime::Rotator<double>::from_table(table); });
  }
  runtime::LobeTable bands = runtime::read_lobe_table(source_path("generated/lobes/order_5.json"));
  bands.order = 4;
  refuses("from_table with bands of another order", [&] { runtime::Rotator<double>::from_table(bands); });
  refuses("a NaN token", [] { runtime::json::parse("[NaN]", "t"); });
  refuses("a lone surrogate", [] { runtime::json::parse("\"\\ud800\"", "t"); });
  refuses("ShProduct(0)", [] { runtime::ShProduct{0}; });
  refuses("ShProduct(17)", [] { runtime::ShProduct{runtime::kMaxGauntOrder + 1}; });
  refuses("a triple coupling beyond its order", [] {
    const runtime::ZhfBasis* slots[3] = {nullptr, nullptr, nullptr};
    runtime::triple_coupling(runtime::kMaxTripleCouplingOrder + 1, slots);
  });
}

}  // namespace zhf::test
