// JsonWriter: nested keys, arrays of objects, number formatting, escaping.
#include <cmath>
#include <cstdint>
#include <limits>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "common/json_writer.h"

namespace viqu {
namespace {

TEST(JsonWriter, DottedKeysMakeNestedObjectsInInsertionOrder) {
  JsonWriter w;
  w.Set("scenario", "static_room");
  w.Set("seed", uint64_t{7});
  w.Set("ate.rmse_m", 0.0123);
  w.Set("robot.fell", false);
  w.Set("ate.mean_m", 0.01);
  EXPECT_EQ(w.ToString(),
            "{\n"
            "  \"scenario\": \"static_room\",\n"
            "  \"seed\": 7,\n"
            "  \"ate\": {\n"
            "    \"rmse_m\": 0.0123,\n"
            "    \"mean_m\": 0.01\n"
            "  },\n"
            "  \"robot\": {\n"
            "    \"fell\": false\n"
            "  }\n"
            "}\n");
  EXPECT_TRUE(w.Has("ate.rmse_m"));
  EXPECT_TRUE(w.Has("ate"));
  EXPECT_FALSE(w.Has("ate.max_m"));
}

TEST(JsonWriter, SettingAgainReplacesInPlace) {
  JsonWriter w;
  w.Set("a", 1);
  w.Set("b", 2);
  w.Set("a", "x");
  EXPECT_EQ(w.ToString(), "{\n  \"a\": \"x\",\n  \"b\": 2\n}\n");
}

TEST(JsonWriter, ArraysOfObjects) {
  JsonWriter w;
  w.EnsureArray("dynamic.objects");
  EXPECT_EQ(w.ToString(), "{\n  \"dynamic\": {\n    \"objects\": []\n  }\n}\n");
  JsonWriter person;
  person.Set("name", "person_1");
  person.Set("latency_s", 0.25);
  JsonWriter box;
  box.Set("name", "box_1");
  box.SetNull("detected_dynamic_s");
  w.Append("dynamic.objects", person);
  w.Append("dynamic.objects", box);
  w.Set("dynamic.precision", 1.0);
  EXPECT_EQ(w.ToString(),
            "{\n"
            "  \"dynamic\": {\n"
            "    \"objects\": [\n"
            "      {\n"
            "        \"name\": \"person_1\",\n"
            "        \"latency_s\": 0.25\n"
            "      },\n"
            "      {\n"
            "        \"name\": \"box_1\",\n"
            "        \"detected_dynamic_s\": null\n"
            "      }\n"
            "    ],\n"
            "    \"precision\": 1\n"
            "  }\n"
            "}\n");
}

TEST(JsonWriter, NumbersUseNineSignificantDigitsAndNullForNonFinite) {
  EXPECT_EQ(JsonWriter::FormatNumber(1.0 / 3.0), "0.333333333");
  EXPECT_EQ(JsonWriter::FormatNumber(123456789.123), "123456789");
  EXPECT_EQ(JsonWriter::FormatNumber(1.5e-12), "1.5e-12");
  EXPECT_EQ(JsonWriter::FormatNumber(-2.0), "-2");
  EXPECT_EQ(JsonWriter::FormatNumber(std::nan("")), "null");
  EXPECT_EQ(JsonWriter::FormatNumber(std::numeric_limits<double>::infinity()), "null");
  JsonWriter w;
  w.Set("nan", std::nan(""));
  w.Set("big", std::numeric_limits<int64_t>::min());
  w.Set("ubig", std::numeric_limits<uint64_t>::max());
  w.SetNumbers("v", {1.5, std::nan("")});
  EXPECT_EQ(w.ToString(),
            "{\n  \"nan\": null,\n  \"big\": -9223372036854775808,\n  \"ubig\": 18446744073709551615,\n"
            "  \"v\": [\n    1.5,\n    null\n  ]\n}\n");
}

TEST(JsonWriter, StringsAreEscaped) {
  EXPECT_EQ(JsonWriter::Quote("a\"b\\c\n\t\x01 \xc3\xa9"), "\"a\\\"b\\\\c\\n\\t\\u0001 \xc3\xa9\"");
  JsonWriter w;
  w.Set("we\"ird", "line\r\n");
  EXPECT_EQ(w.ToString(), "{\n  \"we\\\"ird\": \"line\\r\\n\"\n}\n");
}

TEST(JsonWriter, EmptyObject) { EXPECT_EQ(JsonWriter().ToString(), "{}\n"); }

TEST(JsonWriter, KeyThroughAScalarIsAProgrammingError) {
  JsonWriter w;
  w.Set("ate", 1.0);
  EXPECT_THROW(w.Set("ate.rmse_m", 2.0), std::logic_error);
  EXPECT_THROW(w.Set("a..b", 2.0), std::invalid_argument);
}

}  // namespace
}  // namespace viqu
