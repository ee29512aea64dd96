#include "engine/output/json_splices.h"

#include <algorithm>
#include <numeric>

namespace vesselid {
namespace {

using nlohmann::json;

// A placeholder is the string "\x01splice<i>\x01"; dump prints it as below (control
// characters escaped; names holding them are refused when a config is read).
const std::string kOpen = "\"\\u0001splice";
const std::string kClose = "\\u0001\"";

void Spaces(int n, std::ostream* out) {
  for (int i = 0; i < n; ++i) out->put(' ');
}

// text[begin, end) with `indent` spaces after each line break.
void WriteIndented(const std::string& text, size_t begin, size_t end, int indent,
                   std::ostream* out) {
  while (begin < end) {
    const size_t line_break = text.find('\n', begin);
    if (line_break == std::string::npos || line_break >= end) {
      out->write(text.data() + begin, static_cast<std::streamsize>(end - begin));
      return;
    }
    out->write(text.data() + begin, static_cast<std::streamsize>(line_break + 1 - begin));
    Spaces(indent, out);
    begin = line_break + 1;
  }
}

}  // namespace

json JsonSplices::Array(size_t count, Element element) {
  Splice splice;
  splice.count = count;
  splice.element = std::move(element);
  splices_.push_back(std::move(splice));
  return "\x01splice" + std::to_string(splices_.size() - 1) + "\x01";
}

json JsonSplices::Object(std::vector<std::string> keys, Element value) {
  Splice splice;
  splice.object = true;
  std::vector<size_t> order(keys.size());
  std::iota(order.begin(), order.end(), size_t{0});
  std::stable_sort(order.begin(), order.end(),
                   [&](size_t a, size_t b) { return keys[a] < keys[b]; });
  for (size_t k = 0; k < order.size(); ++k) {
    // A repeated key: the last value, as assigning it again to a json object keeps.
    if (k + 1 < order.size() && keys[order[k + 1]] == keys[order[k]]) continue;
    splice.keys.push_back(keys[order[k]]);
    splice.order.push_back(order[k]);
  }
  splice.count = splice.keys.size();
  splice.element = std::move(value);
  splices_.push_back(std::move(splice));
  return "\x01splice" + std::to_string(splices_.size() - 1) + "\x01";
}

json JsonSplices::ArrayIn(JsonSplices* splices, size_t count, const Element& element) {
  if (splices != nullptr) return splices->Array(count, element);
  json array = json::array();
  for (size_t i = 0; i < count; ++i) array.push_back(element(i));
  return array;
}

json JsonSplices::ObjectIn(JsonSplices* splices, std::vector<std::string> keys,
                           const Element& value) {
  if (splices != nullptr) return splices->Object(std::move(keys), value);
  json object = json::object();
  for (size_t i = 0; i < keys.size(); ++i) object[keys[i]] = value(i);
  return object;
}

void JsonSplices::Write(const json& document, int indent, std::ostream* out) const {
  WriteText(document.dump(indent), 0, indent, out);
}

void JsonSplices::WriteText(const std::string& text, int indent, int step,
                            std::ostream* out) const {
  size_t position = 0;
  for (;;) {
    const size_t open = text.find(kOpen, position);
    WriteIndented(text, position, open == std::string::npos ? text.size() : open, indent, out);
    if (open == std::string::npos) return;
    const size_t close = text.find(kClose, open);
    const size_t index = std::stoul(text.substr(open + kOpen.size(), close - open - kOpen.size()));
    // The placeholder's line is indented by its leading spaces in `text` and `indent`.
    const size_t line = text.rfind('\n', open);
    const size_t line_start = line == std::string::npos ? 0 : line + 1;
    const size_t leading = text.find_first_not_of(' ', line_start) - line_start;
    WriteSplice(splices_.at(index), indent + static_cast<int>(leading), step, out);
    position = close + kClose.size();
  }
}

// As dump prints an array or object at the line indent `indent`: "[]" when empty; compact
// "[a,b]" / {"k":v}; else each element on its own line `step` spaces further in.
void JsonSplices::WriteSplice(const Splice& splice, int indent, int step,
                              std::ostream* out) const {
  const char open = splice.object ? '{' : '[', close = splice.object ? '}' : ']';
  out->put(open);
  if (splice.count == 0) {
    out->put(close);
    return;
  }
  if (step >= 0) out->put('\n');
  const int inner = step >= 0 ? indent + step : 0;
  for (size_t i = 0; i < splice.count; ++i) {
    if (step >= 0) Spaces(inner, out);
    if (splice.object) {
      *out << json(splice.keys[i]).dump() << (step >= 0 ? ": " : ":");
    }
    const json element = splice.element(splice.object ? splice.order[i] : i);
    WriteText(element.dump(step), inner, step, out);
    if (i + 1 < splice.count) out->put(',');
    if (step >= 0) out->put('\n');
  }
  if (step >= 0) Spaces(indent, out);
  out->put(close);
}

}  // namespace vesselid
