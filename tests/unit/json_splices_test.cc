// JsonSplices prints a document with placeholders exactly as nlohmann prints the whole one:
// pretty and compact, arrays and objects (keys sorted, a repeated key's last value), empty
// ones, placeholders inside spliced elements and inside nested objects and arrays.
#include "engine/output/json_splices.h"

#include <gtest/gtest.h>

#include <sstream>

namespace vesselid {
namespace json_splices_test {

using nlohmann::json;

json Element(size_t i) {
  return {{"name", "e" + std::to_string(i)},
          {"values", {i, 0.5 * static_cast<double>(i)}},
          {"nested", {{"ok", i % 2 == 0}, {"none", nullptr}}}};
}

// The document built whole (splices null) and with placeholders (splices given).
json Document(JsonSplices* splices) {
  json j;
  j["first"] = "text with \"quotes\" and a line\nbreak";
  j["array"] = JsonSplices::ArrayIn(splices, 5, Element);
  j["empty_array"] = JsonSplices::ArrayIn(splices, 0, Element);
  j["object"] = JsonSplices::ObjectIn(splices, {"zeta", "alpha", "mu", "alpha"},
                                      [](size_t i) { return json(static_cast<double>(i) / 3); });
  j["empty_object"] = JsonSplices::ObjectIn(splices, {}, Element);
  // Placeholders inside spliced elements: an array of arrays.
  j["deep"]["list"] = JsonSplices::ArrayIn(splices, 3, [splices](size_t i) {
    return JsonSplices::ArrayIn(splices, i, [](size_t k) { return json(k); });
  });
  j["stages"] = json::array({{{"estimates", JsonSplices::ArrayIn(splices, 2, Element)}}, 7});
  return j;
}

std::string Spliced(int indent) {
  JsonSplices splices;
  const json document = Document(&splices);
  std::ostringstream out;
  splices.Write(document, indent, &out);
  return out.str();
}

TEST(JsonSplices, PrintsAsTheWholeDocumentPretty) {
  EXPECT_EQ(Spliced(2), Document(nullptr).dump(2));
  EXPECT_EQ(Spliced(4), Document(nullptr).dump(4));
}

TEST(JsonSplices, PrintsAsTheWholeDocumentCompact) {
  EXPECT_EQ(Spliced(-1), Document(nullptr).dump(-1));
}

TEST(JsonSplices, AnObjectKeepsARepeatedKeysLastValue) {
  const json parsed = json::parse(Spliced(2));
  EXPECT_DOUBLE_EQ(parsed["object"]["alpha"].get<double>(), 1.0);
  EXPECT_EQ(parsed["object"].size(), 3u);
}

TEST(JsonSplices, ElementsAreFormedWhileWritten) {
  // Each element is asked for once, when it is printed (none while the document is built).
  int formed = 0;
  JsonSplices splices;
  json document;
  document["a"] = splices.Array(3, [&formed](size_t i) {
    ++formed;
    return json(i);
  });
  EXPECT_EQ(formed, 0);
  std::ostringstream out;
  splices.Write(document, 2, &out);
  EXPECT_EQ(formed, 3);
  EXPECT_EQ(out.str(), "{\n  \"a\": [\n    0,\n    1,\n    2\n  ]\n}");
}

}  // namespace json_splices_test
}  // namespace vesselid
