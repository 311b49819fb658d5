// runtime/json.h: the one JSON reader, strict and bounded, and its field reads.
#include <string>

#include <gtest/gtest.h>

#include "zhf/runtime/json.h"

namespace zhf::runtime::json {
namespace {

std::string refusal(const std::string& text, const Limits& limits = {}) {
  try {
    parse(text, "t.json", limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

void expect_refused(const std::string& text, const std::string& needle) {
  const std::string message = refusal(text);
  EXPECT_NE(message.find(needle), std::string::npos) << "'" << text.substr(0, 40) << "': " << message;
  EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  EXPECT_EQ(message.rfind("t.json: ", 0), 0u) << message;
}

TEST(Json, ParsesWhatZhfWritesExactly) {
  const Value v = parse(R"({"a": [1, -0.5, 2e-3, 12345678901234567890], "s": "x\u00e9\ud83d\ude00\n", "t": true, "n": null})", "t");
  ASSERT_EQ(v.kind, Value::Kind::kObject);
  const Value& a = *v.find("a");
  EXPECT_EQ(a.items[1].number, -0.5);
  EXPECT_EQ(a.items[2].number, 2e-3);
  EXPECT_TRUE(a.items[0].integral);
  EXPECT_FALSE(a.items[2].integral);
  EXPECT_EQ(v.find("s")->text, "x\xc3\xa9\xf0\x9f\x98\x80\n");
  EXPECT_TRUE(v.find("t")->boolean);
  EXPECT_EQ(v.find("n")->kind, Value::Kind::kNull);
  EXPECT_EQ(parse("0.1", "t").number, 0.1);
  EXPECT_EQ(parse("1e-400", "t").number, 0.0);  // below a double's range: zero
}

TEST(Json, RefusesWhatIsNotStrictJson) {
  expect_refused("", "t.json: file is empty");
  expect_refused("NaN", "NaN and Infinity");
  expect_refused("[Infinity]", "NaN and Infinity");
  expect_refused("[1e400]", "beyond the range of a double");
  expect_refused("[1,]", "unexpected character");
  expect_refused("{\"a\": 1} x", "unexpected characters after the value");
  expect_refused("{\"a\": 1, \"a\": 2}", "the key 'a' appears twice");
  expect_refused("[01]", "expected ',' or ']'");
  expect_refused("[.5]", "unexpected character");
  expect_refused("[+1]", "unexpected character");
  expect_refused("[0x10]", "expected ',' or ']'");
  expect_refused("\"a\tb\"", "control character");
  expect_refused(std::string("\"a\0b\"", 5), "control character");
  expect_refused("\"\\u0000\"", "NUL");
  expect_refused("\"\\ud800\"", "surrogate");
  expect_refused("\"\\udc00\"", "surrogate");
  expect_refused("\"\\q\"", "unknown escape");
  expect_refused("\"abc", "unterminated");
  expect_refused("{\"a\" 1}", "expected ':'");
  expect_refused("// c\n1", "unexpected character");
}

TEST(Json, LimitsAreCheckedWhileParsing) {
  expect_refused(std::string(100000, '['), "nested deeper than 64 levels");
  EXPECT_EQ(refusal(std::string(64, '[') + std::string(64, ']')), "");
  Limits small;
  small.max_values = 10;
  EXPECT_NE(refusal("[1,2,3,4,5,6,7,8,9,10,11]", small).find("more than 10 values"), std::string::npos);
  small.max_string_bytes = 8;
  EXPECT_NE(refusal("[\"0123456789\"]", small).find("a string longer than 8 bytes"), std::string::npos);
  expect_refused("[" + std::string(100, '1') + "]", "a number longer than 64 characters");
}

TEST(Json, MessagesQuoteOnlyAShortEscapedExcerpt) {
  const std::string message = refusal("[" + std::string(1 << 20, 'x') + "]");
  EXPECT_LT(message.size(), 200u) << message;
  const std::string binary = refusal(std::string("\x01\x02\xff\n\nrm -rf", 12));
  EXPECT_EQ(binary.find('\n'), std::string::npos);
  EXPECT_NE(binary.find("\\x01"), std::string::npos) << binary;
  EXPECT_NE(refusal("{\n\n  \"a\": ?}").find("line 3, column 8"), std::string::npos) << refusal("{\n\n  \"a\": ?}");
}

TEST(Json, FieldReadsNameTheFieldAndNeverWrapOrRound) {
  const Value v = parse(R"({"order": 4294967299, "x": 3.5, "k": [1, 2], "deep": {"s": 3}})", "t.json");
  const Field top(v, "t.json");
  auto message = [&](auto&& read) {
    try {
      read();
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string();
  };
  EXPECT_EQ(message([&] { top.member("order").integer(2, 32); }), "t.json: order: must be 2..32 (got 4294967299)");
  EXPECT_EQ(message([&] { top.member("x").integer(0, 10); }), "t.json: x: expected an integer, found 3.5");
  EXPECT_EQ(message([&] { top.member("missing"); }), "t.json: missing: missing");
  EXPECT_EQ(message([&] { top.member("k").items(3); }), "t.json: k: expected 3 entries, found 2");
  EXPECT_EQ(message([&] { top.member("deep").member("s").string(); }), "t.json: deep.s: expected a string, found a number");
  EXPECT_EQ(message([&] { top.allow_only({"order", "x", "k"}); }), "t.json: deep: unknown field");
  EXPECT_EQ(message([&] { Field(parse("[]", "t.json"), "t.json").member("a"); }), "t.json: top level: expected an object, found an array");
  EXPECT_EQ(top.member("k").items(2)[1].integer(0, 5), 2);
}

}  // namespace
}  // namespace zhf::runtime::json
