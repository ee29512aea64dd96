// A JSON document whose large arrays and objects are formed one element at a time while its
// text is written. The document holds a placeholder where each such array or object goes
// (Array, Object); Write prints the document exactly as nlohmann's dump(indent) prints the
// whole one, each placeholder replaced by its elements, each formed, printed and released in
// turn. A run of 500 000 segments held its results.json as one document in ~10 KiB per
// segment; the text takes ~1.7 KiB.
#pragma once

#include <deque>
#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include "nlohmann/json.hpp"

namespace vesselid {

class JsonSplices {
 public:
  using Element = std::function<nlohmann::json(size_t)>;

  // The placeholder of an array of `count` elements, element(i) the i-th. The callbacks run
  // during Write: what they refer to must outlive it.
  nlohmann::json Array(size_t count, Element element);
  // The placeholder of an object with members keys[i]: value(i), printed in key order as
  // nlohmann's objects are (a repeated key keeps its last value).
  nlohmann::json Object(std::vector<std::string> keys, Element value);

  // With `splices` null the array or object itself, formed at once (a document to inspect);
  // else its placeholder in `splices`.
  static nlohmann::json ArrayIn(JsonSplices* splices, size_t count, const Element& element);
  static nlohmann::json ObjectIn(JsonSplices* splices, std::vector<std::string> keys,
                                 const Element& value);

  // `document` as dump(indent) prints it (indent < 0: compact), placeholders filled.
  void Write(const nlohmann::json& document, int indent, std::ostream* out) const;

 private:
  struct Splice {
    bool object = false;
    size_t count = 0;
    std::vector<std::string> keys;  // objects: sorted, unique
    std::vector<size_t> order;      // objects: the element of each sorted key
    Element element;
  };

  // `text` (a dump) to `out`, each placeholder replaced; `indent` spaces precede every line
  // after the first.
  void WriteText(const std::string& text, int indent, int step, std::ostream* out) const;
  void WriteSplice(const Splice& splice, int indent, int step, std::ostream* out) const;

  // A deque: an element may add placeholders of its own while a splice is being written, and
  // that must not move the splice being written.
  std::deque<Splice> splices_;
};

}  // namespace vesselid
