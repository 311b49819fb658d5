// runtime/lobe_table.h: the one reader and validator, which the runtime and every command share.
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "test_support.h"
#include "zhf/io/lobe_table_writer.h"
#include "zhf/runtime/table_io.h"
#include "zhf/runtime/rotator.h"

namespace zhf::runtime {
namespace {

const std::string kTable4 = test::source_path("generated/lobes/order_4.json");

std::string refusal(const std::string& text, const std::string& source = "t.json") {
  try {
    parse_lobe_table(text, source);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// The checked-in order-4 table with one change (nlohmann edits the text: an independent writer).
std::string table_with(const std::function<void(nlohmann::json&)>& change) {
  nlohmann::json j = test::read_json(kTable4);
  change(j);
  return j.dump();
}

void moved_lobe(nlohmann::json& lobe, double theta, double phi) {
  lobe = {{"theta", theta},
          {"phi", phi},
          {"xyz", {std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)}},
          {"source", "x"}};
}

// The checked-in table with its first theta's number turned into a NaN token.
std::string with_nan_theta() {
  std::string text = test::read_text(kTable4);
  const size_t at = text.find("\"theta\": ") + 9;
  return text.substr(0, at) + "NaN" + text.substr(text.find(',', at));
}

struct BadTable {
  std::string name;
  std::string text;
  std::string field;  // the message names it: "t.json: <field>"
};

std::vector<BadTable> bad_tables() {
  return {
      {"format", table_with([](nlohmann::json& j) { j["format"] = "zhf-lobes-0"; }), "format"},
      {"no order", table_with([](nlohmann::json& j) { j.erase("order"); }), "order"},
      {"order as text", table_with([](nlohmann::json& j) { j["order"] = "four"; }), "order"},
      {"order 0", table_with([](nlohmann::json& j) { j["order"] = 0; }), "order"},
      {"order 100", table_with([](nlohmann::json& j) { j["order"] = 100; }), "order"},
      {"order wraps", table_with([](nlohmann::json& j) { j["order"] = 4294967300ull; }), "order"},
      {"order 3 with order 4 bands", table_with([](nlohmann::json& j) { j["order"] = 3; }), "lobes"},
      {"lobe missing", table_with([](nlohmann::json& j) { j["lobes"].erase(6); }), "lobes"},
      {"theta moved", table_with([](nlohmann::json& j) { j["lobes"][1]["theta"] = j["lobes"][1]["theta"].get<double>() + 1e-6; }),
       "lobes[1].xyz"},
      {"short xyz", table_with([](nlohmann::json& j) { j["lobes"][2]["xyz"] = {0, 0}; }), "lobes[2].xyz"},
      {"source with a newline", table_with([](nlohmann::json& j) { j["lobes"][0]["source"] = "a\n#error"; }), "lobes[0].source"},
      {"source with a backslash", table_with([](nlohmann::json& j) { j["lobes"][0]["source"] = "a\\"; }), "lobes[0].source"},
      {"inverse tampered", table_with([](nlohmann::json& j) { j["bands"][1]["inverse"][3][2] = 0.125; }), "bands[1]"},
      {"inverse row missing", table_with([](nlohmann::json& j) { j["bands"][0]["inverse"].erase(0); }), "bands[0].inverse"},
      {"zeros wrong", table_with([](nlohmann::json& j) { j["bands"][0]["zeros"] = 1; }), "bands[0].zeros"},
      {"condition wrong", table_with([](nlohmann::json& j) { j["bands"][1]["condition"] = 1e3; }), "bands[1].condition"},
      {"total zeros wrong", table_with([](nlohmann::json& j) { j["zeros"] = 1; }), "zeros"},
      {"lobe index out of range", table_with([](nlohmann::json& j) { j["bands"][0]["lobes"][0] = 99; }), "bands[0].lobes[0]"},
      {"unknown field", table_with([](nlohmann::json& j) { j["extra"] = 1; }), "extra"},
      // A lobe moved consistently (theta, phi and xyz): the inverse no longer fits.
      {"lobe moved", table_with([](nlohmann::json& j) { moved_lobe(j["lobes"][0], 0.3, 0.2); }), "bands[0].inverse"},
      // Two lobes 1e-7 apart: Y_2 is near-singular (condition ~1e7).
      {"near-singular", table_with([](nlohmann::json& j) {
         moved_lobe(j["lobes"][1], j["lobes"][0]["theta"].get<double>() + 1e-7, j["lobes"][0]["phi"].get<double>());
       }),
       "bands[0]: lobe matrix Y_2 is near-singular (condition"},
      {"NaN token", with_nan_theta(), "not valid JSON"},
      {"truncated", test::read_text(kTable4).substr(0, 1000), "not valid JSON"},
      {"nested", std::string(100000, '['), "not valid JSON at line 1, column 65: nested deeper than 64 levels"},
  };
}

TEST(LobeTable, ChecksInTablesReadAndRewriteByteForByte) {
  for (const std::string name : {"order_3.json", "order_8.json", "order_16.json", "order_32.json", "lanes_order_8.json"}) {
    const std::string path = test::source_path("generated/lobes/" + name);
    const LobeTable table = read_lobe_table(path);
    EXPECT_EQ(io::lobe_table_text(table, path), test::read_text(path)) << name;
  }
}

TEST(LobeTable, RefusesBadTablesNamingTheField) {
  ASSERT_EQ(refusal(test::read_text(kTable4)), "");
  for (const BadTable& bad : bad_tables()) {
    const std::string message = refusal(bad.text);
    EXPECT_NE(message.find("t.json: " + bad.field), std::string::npos) << bad.name << ": " << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << bad.name << ": " << message;
  }
}

TEST(LobeTable, TheFileNameStatesTheOrder) {
  const test::TempDir temp;
  const std::string dir = temp.string();
  test::write_text(dir + "/order_9.json", test::read_text(test::source_path("generated/lobes/order_3.json")));
  try {
    read_lobe_table(dir + "/order_9.json");
    ADD_FAILURE() << "an order-3 table read as order 9";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("order_9.json: order: is 3, but order 9 was expected"), std::string::npos) << e.what();
  }
}

// The runtime's table loading and the CLI read tables with the same code: the same malformed
// table gets the same verdict, word for word, from both.
TEST(LobeTable, TheRuntimeAndTheCliGiveTheSameVerdict) {
  if (test::zhf_binary().empty()) GTEST_SKIP() << "this build has no zhf binary (the runtime alone)";
  const test::TempDir temp;
  const std::string dir = temp.string();
  for (const BadTable& bad : bad_tables()) {
    const std::string path = dir + "/t.json";
    test::write_text(path, bad.text);
    std::string runtime_verdict;
    try {
      Rotator<double>::from_table(read_lobe_table(path));
    } catch (const InputError& e) {
      runtime_verdict = e.what();
    }
    const test::RunResult cli = test::run_zhf({"emit", "--table", path, "--lang", "cpp", "--out", dir + "/out"});
    EXPECT_EQ(cli.exit_code, 3) << bad.name << ": " << cli.err;
    EXPECT_EQ(cli.err, "zhf: " + runtime_verdict + "\n") << bad.name;
  }
}

TEST(LobeTable, FromTableChecksTheShapeOfAHandMadeTable) {
  LobeTable table = read_lobe_table(kTable4);
  table.bands.pop_back();
  EXPECT_THROW(Rotator<float>::from_table(table), InputError);
  table = read_lobe_table(kTable4);
  table.bands[0].inverse.values.resize(3);
  EXPECT_THROW(Rotator<float>::from_table(table), InputError);
  table = read_lobe_table(kTable4);
  table.order = 0;
  EXPECT_THROW(Rotator<float>::from_table(table), InputError);
  table = read_lobe_table(kTable4);
  table.bands[0].lobes[0] = 1000;
  EXPECT_THROW(Rotator<float>::from_table(table), InputError);
  // A changed inverse is still safe to use: the shape is what from_table needs.
  table = read_lobe_table(kTable4);
  table.bands[0].inverse(0, 0) = 0;
  EXPECT_NO_THROW(Rotator<float>::from_table(table));
}

}  // namespace
}  // namespace zhf::runtime
