// io/json.h: the tools' JSON reader (nlohmann-json with zhf's checks), held to the same rules as
// the runtime's own parser (runtime/json.h) on the same documents.
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "zhf/io/errors.h"
#include "zhf/io/json.h"
#include "zhf/runtime/json.h"
#include "zhf/runtime/limits.h"

namespace zhf::io::json {
namespace {

std::string refusal(const std::string& text, const Limits& limits = {}) {
  try {
    parse(text, "t.json", limits);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

std::string runtime_refusal(const std::string& text) {
  try {
    runtime::json::parse(text, "t.json");
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

template <typename Read>
std::string message(Read&& read) {
  try {
    read();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

TEST(IoJson, ReadsNumbersExactlyAndKeepsFileOrder) {
  const Json v = parse(R"({"z": [1, -0.5, 2e-3, 12345678901234567890], "s": "x\u00e9\ud83d\ude00\n", "a": true, "n": null})", "t");
  const Field top(v, "t");
  EXPECT_EQ(v.begin().key(), "z");  // file order, not sorted
  const std::vector<Field> z = top.member("z").items(4);
  EXPECT_EQ(z[1].number(), -0.5);
  EXPECT_EQ(z[2].number(), 2e-3);
  EXPECT_EQ(top.member("s").string(), "x\xc3\xa9\xf0\x9f\x98\x80\n");
  EXPECT_TRUE(top.member("a").boolean());
  EXPECT_TRUE(top.member("n").is(Kind::kNull));
  EXPECT_EQ(Field(parse("0.1", "t"), "t").number(), 0.1);
  EXPECT_EQ(Field(parse("1e-400", "t"), "t").number(), 0.0);  // below a double's range: zero
  EXPECT_EQ(Field(parse("9223372036854775807", "t"), "t").integer(0LL, 9223372036854775807LL), 9223372036854775807LL);
}

// Each document is refused by both readers: the tools and the runtime follow one set of rules.
TEST(IoJson, RefusesWhatTheRuntimeReaderRefuses) {
  const std::vector<std::pair<std::string, std::string>> documents = {
      {"", "t.json: file is empty"},
      {" \n\t", "t.json: file is empty"},
      {"NaN", "not valid JSON at line 1"},
      {"[Infinity]", "not valid JSON at line 1"},
      {"[-Infinity]", "not valid JSON at line 1"},
      {"[1e400]", "the number '1e400' is beyond the range of a double"},
      {"[0.5e3333333333]", "is beyond the range of a double"},
      {"[1,]", "not valid JSON at line 1"},
      {"{\"a\": 1} x", "not valid JSON at line 1, column 10"},
      {"{\"a\": 1, \"a\": 2}", "the key 'a' appears twice"},
      {"{\"b\": {\"a\": 1, \"c\": [{\"a\": 2}], \"a\": 3}}", "the key 'a' appears twice"},
      {"[01]", "not valid JSON at line 1"},
      {"[.5]", "not valid JSON at line 1"},
      {"[+1]", "not valid JSON at line 1"},
      {"[0x10]", "not valid JSON at line 1"},
      {"\"a\tb\"", "not valid JSON at line 1"},
      {std::string("\"a\0b\"", 5), "not valid JSON at line 1"},
      {std::string("{\"order\"\0: 3}", 13), "not valid JSON at line 1"},
      {"\"\\u0000\"", "a NUL character"},
      {"{\"\\u0000\": 1}", "a NUL character"},
      {"\"\\ud800\"", "not valid JSON at line 1"},
      {"\"\\udc00\"", "not valid JSON at line 1"},
      {"\"\\q\"", "not valid JSON at line 1"},
      {"\"abc", "not valid JSON at line 1"},
      {"{\"a\" 1}", "not valid JSON at line 1"},
      {"// c\n1", "not valid JSON at line 1"},
      {"[1] /* c */", "not valid JSON at line 1"},
      {std::string(100000, '['), "nested deeper than 64 levels"},
      {std::string(100000, '{'), "not valid JSON"},
      {"[\"" + std::string((1 << 16) + 1, 'a') + "\"]", "a string longer than 65536 bytes"},
  };
  for (const auto& [text, needle] : documents) {
    const std::string m = refusal(text);
    EXPECT_NE(m.find(needle), std::string::npos) << "'" << text.substr(0, 40) << "': " << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    EXPECT_EQ(m.rfind("t.json: ", 0), 0u) << m;
    EXPECT_NE(runtime_refusal(text), "") << "the runtime's reader accepts '" << text.substr(0, 40) << "'";
  }
  EXPECT_EQ(refusal(std::string(64, '[') + std::string(64, ']')), "");
  EXPECT_EQ(runtime_refusal(std::string(64, '[') + std::string(64, ']')), "");
}

TEST(IoJson, LimitsAreCheckedWhileParsing) {
  Limits small;
  small.max_values = 10;
  EXPECT_NE(refusal("[1,2,3,4,5,6,7,8,9,10,11]", small).find("more than 10 values"), std::string::npos);
  EXPECT_EQ(refusal("[1,2,3,4,5,6,7,8,9]", small), "");
  small.max_string_bytes = 8;
  EXPECT_NE(refusal("[\"0123456789\"]", small).find("a string longer than 8 bytes"), std::string::npos);
  EXPECT_NE(refusal("{\"0123456789\": 1}", small).find("a string longer than 8 bytes"), std::string::npos);
  small.max_depth = 2;
  EXPECT_NE(refusal("[[[1]]]", small).find("nested deeper than 2 levels"), std::string::npos);
  EXPECT_EQ(refusal("[[1]]", small), "");
}

// An object of count distinct keys "k0".."k<count-1>", each holding 0.
std::string object_of_keys(std::size_t count) {
  std::string text = "{";
  for (std::size_t k = 0; k < count; ++k) text += (k ? ",\"k" : "\"k") + std::to_string(k) + "\":0";
  return text + "}";
}

// Both readers bound the keys of an object (runtime::kMaxJsonObjectKeys) and find a duplicate by
// sorting an object's keys once when it closes, so a document parses in O(n log k): an object of
// 16 MiB of distinct keys is refused at the key past the limit, before the rest is read, and one
// at the limit is read whole, its members in file order, a duplicate anywhere in it named.
TEST(IoJson, KeysPerObjectAreBoundedAndDuplicatesFoundWithoutAQuadraticSearch) {
  const std::size_t most = runtime::kMaxJsonObjectKeys;
  const std::string keys = "an object with more than " + std::to_string(most) + " keys";
  std::string huge = "{";
  for (std::size_t k = 0; huge.size() < (std::size_t(16) << 20) - 32; ++k) huge += (k ? ",\"" : "\"") + std::to_string(k) + "\":0";
  huge += "}";
  EXPECT_NE(refusal(huge).find(keys), std::string::npos) << refusal(huge).substr(0, 200);
  EXPECT_NE(runtime_refusal(huge).find(keys), std::string::npos) << runtime_refusal(huge).substr(0, 200);
  EXPECT_NE(refusal(object_of_keys(most + 1)).find(keys), std::string::npos);
  EXPECT_NE(runtime_refusal(object_of_keys(most + 1)).find(keys), std::string::npos);
  const std::string full = object_of_keys(most);
  EXPECT_EQ(refusal(full), "");
  EXPECT_EQ(runtime_refusal(full), "");
  const Json parsed = parse(full, "t.json");
  EXPECT_EQ(parsed.begin().key(), "k0");
  EXPECT_EQ((--parsed.end()).key(), "k" + std::to_string(most - 1));
  // A duplicate of the first key as the last, and of the last as the second.
  for (const std::string& duplicated : {std::string("k0"), "k" + std::to_string(most - 2)}) {
    std::string twice = object_of_keys(most - 1);
    if (duplicated == "k0") twice.insert(twice.size() - 1, ",\"k0\":1");
    else twice.insert(twice.find(',') + 1, "\"" + duplicated + "\":1,");
    const std::string expected = "the key '" + duplicated + "' appears twice";
    EXPECT_NE(refusal(twice).find(expected), std::string::npos) << refusal(twice);
    EXPECT_NE(runtime_refusal(twice).find(expected), std::string::npos) << runtime_refusal(twice);
  }
}

TEST(IoJson, MessagesQuoteOnlyAShortEscapedExcerpt) {
  const std::string long_token = refusal("[" + std::string(1 << 20, 'x') + "]");
  EXPECT_LT(long_token.size(), 200u) << long_token;
  const std::string binary = refusal(std::string("\x01\x02\xff\n\nrm -rf", 12));
  for (const char c : binary) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << "a raw byte " << int(c) << " in " << binary;
  EXPECT_NE(refusal("{\n\n  \"a\": ?}").find("line 3, column 8"), std::string::npos) << refusal("{\n\n  \"a\": ?}");
}

TEST(IoJson, FieldReadsNameTheFieldAndNeverWrapOrRound) {
  const Json v = parse(R"({"order": 4294967299, "big": 18446744073709551615, "x": 3.5, "three": 3.0, "k": [1, -2],
                           "deep": {"s": 3}, "e": "glsl"})",
                       "t.json");
  const Field top(v, "t.json");
  EXPECT_EQ(message([&] { top.member("order").integer(2, 32); }), "t.json: order: must be 2..32 (got 4294967299)");
  EXPECT_EQ(message([&] { top.member("big").integer(-1LL, 100LL); }), "t.json: big: must be -1..100 (got 18446744073709551615)");
  EXPECT_EQ(message([&] { top.member("big").integer(-5LL, -1LL); }), "t.json: big: must be -5..-1 (got 18446744073709551615)");
  EXPECT_EQ(message([&] { top.member("x").integer(0, 10); }), "t.json: x: expected an integer, found 3.5");
  EXPECT_EQ(message([&] { top.member("three").integer(0, 10); }), "t.json: three: expected an integer, found 3.0");
  EXPECT_EQ(message([&] { top.member("x").number(0, 1); }), "t.json: x: must be in [0, 1] (got 3.5)");
  EXPECT_EQ(message([&] { top.member("missing"); }), "t.json: missing: missing");
  EXPECT_EQ(message([&] { top.member("k").items(3); }), "t.json: k: expected 3 entries, found 2");
  EXPECT_EQ(message([&] { top.member("k").items(3, 5); }), "t.json: k: expected 3 to 5 entries, found 2");
  EXPECT_EQ(message([&] { top.member("deep").member("s").string(); }), "t.json: deep.s: expected a string, found a number");
  EXPECT_EQ(message([&] { top.allow_only({"order", "big", "x", "three", "k", "e"}); }), "t.json: deep: unknown field");
  EXPECT_EQ(message([&] { top.member("e").one_of({"cpp", "wgsl"}); }), "t.json: e: 'glsl' is not one of cpp, wgsl");
  EXPECT_EQ(message([&] { Field(parse("[]", "t.json"), "t.json").member("a"); }), "t.json: top level: expected an object, found an array");
  EXPECT_EQ(top.member("k").items(2)[1].integer(-5, 5), -2);
  EXPECT_EQ(top.member("e").one_of({"cpp", "glsl"}), "glsl");
}

}  // namespace
}  // namespace zhf::io::json
