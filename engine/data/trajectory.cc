#include "engine/data/trajectory.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <limits>
#include <set>
#include <string>
#include <string_view>
#include <vector>

#include "engine/base/input_file.h"
#include "engine/base/number_text.h"
#include "engine/base/parallel_for.h"
#include "engine/data/time_base.h"

namespace vesselid {
namespace {

bool IsBlank(char c) { return c == ' ' || c == '\t' || c == '\r'; }

std::string_view Trim(std::string_view s) {
  size_t b = 0, e = s.size();
  while (b < e && IsBlank(s[b])) ++b;
  while (e > b && IsBlank(s[e - 1])) --e;
  return s.substr(b, e - b);
}

// Lines of a file read in blocks, none longer than kMaxLine (a file without newlines would
// otherwise be read into one string whole). A line is a view into the block it lies in, or
// into a carry string when it spans two blocks; it stays valid until the next call.
class LineReader {
 public:
  static constexpr size_t kMaxLine = size_t{16} << 20;

  explicit LineReader(const std::string& path)
      : file_(std::fopen(path.c_str(), "rb")), buffer_(size_t{1} << 18) {
    struct stat info;
    if (file_ != nullptr && ::fstat(fileno(file_), &info) == 0) size_ = info.st_size;
  }
  ~LineReader() {
    if (file_ != nullptr) std::fclose(file_);
  }
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  bool open() const { return file_ != nullptr; }
  // Bytes of the file not yet returned as lines (from its size when opened).
  std::uint64_t bytes_left() const { return (size_ > read_ ? size_ - read_ : 0) + (end_ - begin_); }
  bool too_long() const { return too_long_; }
  bool failed() const { return file_ != nullptr && std::ferror(file_) != 0; }

  // The next line without its '\n'; false at the end, on a read error or a line too long.
  bool Next(std::string_view* line) {
    carry_.clear();
    while (true) {
      if (begin_ == end_) {
        if (file_ == nullptr) return false;
        end_ = std::fread(buffer_.data(), 1, buffer_.size(), file_);
        read_ += end_;
        begin_ = 0;
        if (end_ == 0) {
          *line = carry_;
          return !carry_.empty();
        }
      }
      const char* start = buffer_.data() + begin_;
      const void* newline = std::memchr(start, '\n', end_ - begin_);
      const size_t length = newline ? static_cast<const char*>(newline) - start : end_ - begin_;
      if (carry_.size() + length > kMaxLine) {
        too_long_ = true;
        return false;
      }
      begin_ += length;
      if (newline && carry_.empty()) {  // the whole line in this block: no copy
        ++begin_;
        *line = std::string_view(start, length);
        return true;
      }
      carry_.append(start, length);
      if (newline) {
        ++begin_;
        *line = carry_;
        return true;
      }
    }
  }

 private:
  std::FILE* file_;
  std::vector<char> buffer_;
  std::string carry_;
  size_t begin_ = 0, end_ = 0;
  std::uint64_t size_ = 0, read_ = 0;
  bool too_long_ = false;
};

// Room for about `rows` more rows (the bytes left over the first row's length, a little
// more): the columns then grow without copies. Capacity never touched costs no memory.
void ReserveRows(std::uint64_t rows, Trajectory* trajectory) {
  const size_t n = static_cast<size_t>(std::min<std::uint64_t>(rows + rows / 8 + 16, 1u << 26));
  trajectory->t.reserve(n);
  trajectory->line.reserve(n);
  for (std::vector<double>& column : trajectory->columns) column.reserve(n);
}

constexpr char kByteOrderMark[] = "\xEF\xBB\xBF";

// The trimmed fields of `line` into *fields (views into the line). A field in double quotes
// (RFC 4180, as pandas writes a note holding a comma) may hold the separator and "" for a
// quote; its view is what lies between the quotes ("" left as it is: such a field is text,
// which no read column takes).
void SplitFields(std::string_view line, char separator, std::vector<std::string_view>* fields) {
  fields->clear();
  const char* p = line.data();
  const char* const end = p + line.size();
  while (true) {
    const char* const start = p;
    const char* field = p;
    while (field != end && (*field == ' ' || *field == '\t') && *field != separator) ++field;
    if (field != end && *field == '"') {
      const char* close = field + 1;
      while (close != end && !(*close == '"' && (close + 1 == end || close[1] != '"'))) {
        close += *close == '"' ? 2 : 1;  // "" inside: one quote
      }
      if (close != end) {
        const char* after = close + 1;
        while (after != end && *after != separator && (*after == ' ' || *after == '\t')) ++after;
        if (after == end || *after == separator) {
          fields->push_back(std::string_view(field + 1, close - field - 1));
          if (after == end) break;
          p = after + 1;
          continue;
        }
      }
      // No closing quote before the separator: read as plain text.
    }
    while (p != end && *p != separator) ++p;
    fields->push_back(Trim(std::string_view(start, p - start)));
    if (p == end) break;
    ++p;
  }
}

// The number in a field (NaN when it is empty), or false with why it is not a measurement,
// to follow "column '<name>': " in a message.
bool ParseMeasurement(std::string_view field, double* value, std::string* why) {
  *value = std::numeric_limits<double>::quiet_NaN();
  if (!field.empty() && !ParseFiniteNumber(field, value)) {
    *why = "'" + std::string(field) + "' is not a finite number";
    return false;
  }
  if (std::abs(*value) > kMaxDataMagnitude) {
    *why = std::string(field) +
           " is too large for a measurement (|value| > 1e100; its square would overflow the "
           "cost)";
    return false;
  }
  return true;
}

// What the reader does with each field of a row (Header::slot).
constexpr int kTimeField = -1;
constexpr int kSkippedField = -2;

// The header row's checks (a time column, no duplicate among the columns read): the slot of
// each field (kTimeField, kSkippedField or the channel it fills) and the channel names, or
// false with the message. `line` is the raw header row (to name another separator it is
// split by).
bool CheckHeader(const std::vector<std::string>& header, std::string_view line,
                 const CsvReadOptions& options, int* time_column, std::vector<int>* slots,
                 std::vector<std::string>* names, std::vector<std::string>* skipped,
                 std::string* what) {
  auto fail = [&](const std::string& message) {
    *what = message;
    return false;
  };
  *time_column = -1;
  names->clear();
  skipped->clear();
  slots->assign(header.size(), kSkippedField);
  std::vector<std::string_view> fields;
  std::set<std::string> seen;  // not a pairwise check: that is quadratic in a wide header
  const std::set<std::string> wanted(options.columns.begin(), options.columns.end());
  const std::string& time_name = options.time_column;
  for (size_t i = 0; i < header.size(); ++i) {
    if (header[i] != time_name) continue;
    if (*time_column >= 0) return fail("duplicate column '" + header[i] + "' (the time)");
    *time_column = static_cast<int>(i);
  }
  if (*time_column < 0) {
    // A header split by another separator names the separator, not a missing column.
    for (char other : {',', ';', '\t'}) {
      if (other == options.separator) continue;
      SplitFields(line, other, &fields);
      for (std::string_view name : fields) {
        if (name != time_name) continue;
        return fail("the header is separated by " + SeparatorName(other) + ", not " +
                    SeparatorName(options.separator) + ": convert the file to commas or set " +
                    "the experiment's separator: \"" +
                    (other == '\t' ? "\\t" : std::string(1, other)) + "\"");
      }
    }
    return fail("header has no time column '" + time_name + "'");
  }
  for (size_t i = 0; i < header.size(); ++i) {
    const bool time = static_cast<int>(i) == *time_column;
    const bool read = time || (!header[i].empty() && (wanted.empty() || wanted.count(header[i])));
    if (!read) {
      skipped->push_back(header[i]);
      continue;
    }
    if (!seen.insert(header[i]).second) return fail("duplicate column '" + header[i] + "'");
    if (time) {
      (*slots)[i] = kTimeField;
    } else {
      (*slots)[i] = static_cast<int>(names->size());
      names->push_back(header[i]);
    }
  }
  return true;
}

// One block of a file read whole: its text, its rows (non-blank lines) and lines (blank
// ones included), counted first so that every block parses into its own place of the
// trajectory's columns, from row `first_row`.
struct RowBlock {
  std::string_view text;
  size_t rows = 0, first_row = 0;
  int lines = 0;
  bool ok = true;
};

// Counts the rows and lines of `block`; false for a line longer than LineReader::kMaxLine.
bool CountRows(RowBlock* block) {
  const char* p = block->text.data();
  const char* const end = p + block->text.size();
  while (p != end) {
    // Looked for no further than a line may reach: a longer one is not read past.
    const size_t reach = std::min<size_t>(end - p, LineReader::kMaxLine + 1);
    const char* newline = static_cast<const char*>(std::memchr(p, '\n', reach));
    if (newline == nullptr && reach < static_cast<size_t>(end - p)) return false;
    const char* line_end = newline != nullptr ? newline : end;
    if (static_cast<size_t>(line_end - p) > LineReader::kMaxLine) return false;
    ++block->lines;
    if (!Trim(std::string_view(p, line_end - p)).empty()) ++block->rows;
    p = newline != nullptr ? newline + 1 : end;
  }
  return true;
}

// Parses the rows of `block` as ReadTrajectoryCsv does into rows [first_row, first_row + rows)
// of `result` (and of `time_ns` for an epoch record), numbering lines from `first_line`;
// false at the first thing the sequential reader would reject, which then names it. Times are
// checked to increase within the block.
bool ParseRowBlock(const RowBlock& block, const CsvReadOptions& options,
                   const std::vector<int>& slots, int first_line, Trajectory* result,
                   std::vector<std::int64_t>* time_ns) {
  std::vector<std::string_view> fields;
  std::string why;
  const char* p = block.text.data();
  const char* const end = p + block.text.size();
  size_t row = block.first_row;
  int number = first_line;
  for (; p != end; ++number) {
    const char* newline = static_cast<const char*>(std::memchr(p, '\n', end - p));
    const std::string_view line(p, (newline != nullptr ? newline : end) - p);
    p = newline != nullptr ? newline + 1 : end;
    if (Trim(line).empty()) continue;
    SplitFields(line, options.separator, &fields);
    if (fields.size() != slots.size()) return false;
    for (size_t i = 0; i < fields.size(); ++i) {
      if (slots[i] == kSkippedField) continue;
      double value;
      if (!ParseMeasurement(fields[i], &value, &why)) return false;
      if (slots[i] != kTimeField) {
        result->columns[slots[i]][row] = value;
        continue;
      }
      if (fields[i].empty()) return false;
      if (result->epoch) {
        std::int64_t& ns = (*time_ns)[row];
        if (!ParseNanoseconds(fields[i], &ns)) return false;
        if (row > block.first_row && !(ns > (*time_ns)[row - 1])) return false;
      } else if (row > block.first_row && !(value > result->t[row - 1])) {
        return false;
      }
      result->t[row] = value;
      result->line[row] = number;
    }
    ++row;
  }
  return true;
}

// The end of the line at `from` in `text` (its newline, or the text's end), looked for no
// further than LineReader::kMaxLine: npos for a longer line, which the sequential reader then
// names.
size_t LineEnd(std::string_view text, size_t from) {
  const size_t limit = std::min(text.size(), from + LineReader::kMaxLine + 1);
  const size_t newline = text.substr(0, limit).find('\n', from);
  if (newline != std::string_view::npos) return newline;
  return limit == text.size() ? text.size() : std::string_view::npos;
}

// ReadTrajectoryCsv's fast path for a file of many rows: read whole, cut into blocks at line
// ends, the blocks parsed on the machine's cores and joined in order. False, with nothing
// reported, for anything the sequential reader would reject or that needs its care (a file
// below `parallel_bytes`, one core, a bad header or row, a time not after the last block's):
// the caller then reads the file sequentially, which names the first problem's line.
bool ReadTrajectoryCsvInBlocks(const std::string& path, const CsvReadOptions& options,
                               Trajectory* trajectory) {
  const int threads = ParallelThreads(0);
  // The file mapped, not copied: its pages are the page cache's, read ahead (MADV_WILLNEED)
  // but mapped only as the parse reaches them, so that a file the parse gives up on early (a
  // line beyond kMaxLine) never becomes resident whole.
  struct Mapping {
    void* data = MAP_FAILED;
    size_t length = 0;
    ~Mapping() {
      if (data != MAP_FAILED) ::munmap(data, length);
    }
  } mapping;
  {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return false;
    struct stat info;
    if (::fstat(fd, &info) == 0 && S_ISREG(info.st_mode) && threads > 1 &&
        static_cast<std::uint64_t>(info.st_size) >= std::max<std::uint64_t>(options.parallel_bytes, 2) &&
        static_cast<std::uint64_t>(info.st_size) <= options.max_bytes) {
      mapping.length = static_cast<size_t>(info.st_size);
      mapping.data = ::mmap(nullptr, mapping.length, PROT_READ, MAP_PRIVATE, fd, 0);
      if (mapping.data != MAP_FAILED) ::madvise(mapping.data, mapping.length, MADV_WILLNEED);
    }
    ::close(fd);
    if (mapping.data == MAP_FAILED) return false;
  }
  const std::string_view text(static_cast<const char*>(mapping.data), mapping.length);
  // The header: the first line that is not blank.
  size_t begin = 0;
  int header_line = 0;
  std::string_view line;
  while (begin < text.size()) {
    const size_t newline = LineEnd(text, begin);
    if (newline == std::string_view::npos) return false;
    line = text.substr(begin, newline - begin);
    begin = newline + 1;
    ++header_line;
    if (line.size() > LineReader::kMaxLine) return false;
    if (header_line == 1 && line.substr(0, 3) == kByteOrderMark) line.remove_prefix(3);
    if (!Trim(line).empty()) break;
  }
  std::vector<std::string_view> fields;
  SplitFields(line, options.separator, &fields);
  const std::vector<std::string> header(fields.begin(), fields.end());
  Trajectory result;
  result.source = path;
  int time_column = -1;
  std::vector<int> slots;
  std::string what;
  if (!CheckHeader(header, line, options, &time_column, &slots, &result.names,
                   &result.skipped_columns, &what)) {
    return false;
  }
  // Epoch or not, from the first row's time.
  {
    size_t at = begin;
    std::string_view first;
    while (at < text.size()) {
      const size_t newline = LineEnd(text, at);
      if (newline == std::string_view::npos) return false;
      first = text.substr(at, newline - at);
      at = newline + 1;
      if (!Trim(first).empty()) break;
    }
    SplitFields(first, options.separator, &fields);
    double t0 = 0.0;
    if (fields.size() != header.size() || !ParseFiniteNumber(fields[time_column], &t0)) {
      return false;
    }
    result.epoch = std::abs(t0) >= kEpochThreshold;
  }
  // Blocks of about equal size, each ending at a line end (the last at the file's end).
  const size_t wanted = static_cast<size_t>(threads) * 4;
  const size_t size = std::max<size_t>((text.size() - begin + wanted - 1) / wanted, 1);
  std::vector<RowBlock> blocks;
  for (size_t from = begin; from < text.size();) {
    size_t to = std::min(text.size(), from + size);
    if (to < text.size()) {
      const size_t newline = LineEnd(text, to - 1);
      if (newline == std::string_view::npos) return false;
      to = newline + 1;
    }
    blocks.emplace_back();
    blocks.back().text = text.substr(from, to - from);
    from = to;
  }
  ParallelFor(static_cast<int>(blocks.size()), 0,
              [&](int b) { blocks[b].ok = CountRows(&blocks[b]); });
  size_t rows = 0;
  std::vector<int> first_line(blocks.size());
  int line_number = header_line + 1;
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (!blocks[b].ok) return false;
    blocks[b].first_row = rows;
    first_line[b] = line_number;
    rows += blocks[b].rows;
    line_number += blocks[b].lines;
  }
  if (rows < 2 || rows > options.max_values / header.size()) return false;
  // The columns' pages are first touched (zeroed) on every core, a column each.
  result.columns.resize(result.names.size());
  std::vector<std::int64_t> time_ns;
  ParallelFor(static_cast<int>(result.columns.size()) + 3, 0, [&](int c) {
    if (c == 0) result.t.resize(rows);
    if (c == 1) result.line.resize(rows);
    if (c == 2) time_ns.resize(result.epoch ? rows : 0);
    if (c >= 3) result.columns[c - 3].resize(rows);
  });
  ParallelFor(static_cast<int>(blocks.size()), 0, [&](int b) {
    blocks[b].ok = ParseRowBlock(blocks[b], options, slots, first_line[b], &result, &time_ns);
  });
  for (size_t b = 0; b < blocks.size(); ++b) {
    if (!blocks[b].ok) return false;
    // Times increase across the join too.
    const size_t row = blocks[b].first_row;
    if (blocks[b].rows > 0 && row > 0 &&
        !(result.epoch ? time_ns[row] > time_ns[row - 1] : result.t[row] > result.t[row - 1])) {
      return false;
    }
  }
  if (result.epoch) {
    result.time_origin_ns = time_ns.front();
    for (size_t k = 0; k < time_ns.size(); ++k) {
      result.t[k] = NanosecondsToSeconds(time_ns[k] - time_ns.front());
    }
  }
  *trajectory = std::move(result);
  return true;
}

}  // namespace

int Trajectory::Find(const std::string& name) const {
  for (size_t i = 0; i < names.size(); ++i) {
    if (names[i] == name) return static_cast<int>(i);
  }
  return -1;
}

Channel ExtractChannel(const Trajectory& trajectory, int column) {
  Channel channel;
  const std::vector<double>& values = trajectory.columns[column];
  channel.t.reserve(values.size());  // one allocation: experiments cut from long records call
  channel.value.reserve(values.size());  // this once per segment and output
  for (size_t k = 0; k < values.size(); ++k) {
    if (std::isnan(values[k])) continue;
    channel.t.push_back(trajectory.t[k]);
    channel.value.push_back(values[k]);
  }
  return channel;
}

bool ReadTrajectoryCsv(const std::string& path, const CsvReadOptions& options,
                       Trajectory* trajectory, std::string* error) {
  if (!CheckInputFile(path, "data file", options.max_bytes, "limits.file_mb", error)) {
    return false;
  }
  if (ReadTrajectoryCsvInBlocks(path, options, trajectory)) return true;
  LineReader in(path);
  if (!in.open()) {
    *error = path + ": cannot open file";
    return false;
  }
  Trajectory result;
  result.source = path;
  std::string_view line;
  int line_number = 0;
  int time_column = -1;
  std::vector<std::string> header;
  std::vector<std::string_view> fields;
  auto fail = [&](const std::string& what) {
    *error = path + ":" + std::to_string(line_number) + ": " + what;
    return false;
  };
  auto next = [&]() {
    ++line_number;
    return in.Next(&line);
  };
  while (next()) {
    if (line_number == 1 && line.substr(0, 3) == kByteOrderMark) line.remove_prefix(3);
    if (Trim(line).empty()) continue;
    SplitFields(line, options.separator, &fields);
    header.assign(fields.begin(), fields.end());
    break;
  }
  if (in.too_long()) return fail("line longer than " + ByteCount(LineReader::kMaxLine));
  if (header.empty()) return fail("empty file, expected a header row");
  std::vector<int> slots;
  {
    std::string what;
    if (!CheckHeader(header, line, options, &time_column, &slots, &result.names,
                     &result.skipped_columns, &what)) {
      return fail(what);
    }
  }
  result.columns.resize(result.names.size());
  // Cells of each read column that are not numbers: count, the first rows and the first text.
  struct Bad {
    int count = 0;
    std::vector<size_t> rows;
    std::vector<int> lines;
    std::string first_text, first_why;
  };
  std::vector<Bad> bad(result.names.size());
  constexpr size_t kFirstBadCells = 3;

  std::uint64_t values = 0;
  std::vector<std::int64_t> time_ns;  // epoch logs: every time exactly, in nanoseconds
  while (next()) {
    if (Trim(line).empty()) continue;
    values += header.size();
    if (values > options.max_values) {
      return fail("more than " + std::to_string(options.max_values) +
                  " values (rows x columns) in one data file (limits.data_values)");
    }
    SplitFields(line, options.separator, &fields);
    if (fields.size() != header.size()) {
      return fail("expected " + std::to_string(header.size()) + " fields, found " +
                  std::to_string(fields.size()));
    }
    const size_t row = result.t.size();  // this row's index
    for (size_t i = 0; i < fields.size(); ++i) {
      if (slots[i] == kSkippedField) continue;
      const std::string_view field = fields[i];
      double value;
      std::string why;
      if (!ParseMeasurement(field, &value, &why)) {
        if (slots[i] == kTimeField || !(options.max_bad_share > 0.0)) {
          return fail("column '" + header[i] + "': " + why);
        }
        Bad& b = bad[slots[i]];
        if (b.count++ == 0) {
          b.first_text = std::string(field.substr(0, 40));
          b.first_why = why;
        }
        if (b.rows.size() < kFirstBadCells) {
          b.rows.push_back(row);
          b.lines.push_back(line_number);
        }
        value = std::numeric_limits<double>::quiet_NaN();  // a missing sample
      }
      if (slots[i] == kTimeField) {
        if (field.empty()) return fail("missing time value");
        if (result.t.empty()) result.epoch = std::abs(value) >= kEpochThreshold;
        if (result.epoch) {
          std::int64_t ns = 0;
          if (!ParseNanoseconds(field, &ns)) {
            return fail("time " + std::string(field) +
                        " cannot be read to the nanosecond (an epoch time needs |t| < 9.2e9 s: "
                        "give it in seconds, not milliseconds)");
          }
          if (!time_ns.empty() && !(ns > time_ns.back())) {
            return fail("time " + std::string(field) + " is not after the previous time " +
                        FormatNanoseconds(time_ns.back()) + " (t must be strictly increasing)");
          }
          time_ns.push_back(ns);
        } else if (!result.t.empty() && !(value > result.t.back())) {
          return fail("time " + std::string(field) + " is not after the previous time " +
                      std::to_string(result.t.back()) + " (t must be strictly increasing)");
        }
        if (result.t.empty()) ReserveRows(in.bytes_left() / (line.size() + 1), &result);
        result.t.push_back(value);
        result.line.push_back(line_number);
      } else {
        result.columns[slots[i]].push_back(value);
      }
    }
  }
  if (in.too_long()) return fail("line longer than " + ByteCount(LineReader::kMaxLine));
  if (in.failed()) return fail("read error");
  if (result.t.size() < 2) return fail("fewer than two data rows");
  if (result.epoch) {
    // Relative times from exact integer differences (time_base.h).
    result.time_origin_ns = time_ns.front();
    for (size_t k = 0; k < time_ns.size(); ++k) {
      result.t[k] = NanosecondsToSeconds(time_ns[k] - time_ns.front());
    }
  }
  const size_t rows = result.t.size();
  for (size_t c = 0; c < bad.size(); ++c) {
    const Bad& b = bad[c];
    if (b.count == 0) continue;
    if (b.count > options.max_bad_share * static_cast<double>(rows)) {
      char share[160];
      std::snprintf(share, sizeof(share),
                    " (%d of the column's %zu cells are not numbers, more than the %g %% "
                    "an experiment's bad_cells accepts)",
                    b.count, rows, 100.0 * options.max_bad_share);
      line_number = b.lines.front();
      return fail("column '" + result.names[c] + "': " + b.first_why + share);
    }
    Trajectory::BadCells cells;
    cells.column = result.names[c];
    cells.count = b.count;
    cells.cells = static_cast<int>(rows);
    cells.lines = b.lines;
    for (size_t row : b.rows) cells.times.push_back(result.t[row]);
    cells.first_text = b.first_text;
    result.bad_cells.push_back(std::move(cells));
  }
  *trajectory = std::move(result);
  return true;
}

std::string SeparatorName(char separator) {
  return separator == '\t' ? "tabs" : "'" + std::string(1, separator) + "'";
}

bool WriteTrajectoryCsv(const std::string& path, const Trajectory& trajectory, std::string* error) {
  const std::string temporary = path + ".tmp";
  std::remove(temporary.c_str());  // a link at the temporary's name is removed, not written through
  std::FILE* file = std::fopen(temporary.c_str(), "w");
  if (file == nullptr) {
    *error = path + ": cannot write file";
    return false;
  }
  std::fputs("t", file);
  for (const std::string& name : trajectory.names) std::fprintf(file, ",%s", name.c_str());
  std::fputc('\n', file);
  // std::to_chars with a precision writes what printf's %.<precision>g writes, several times
  // faster (a trace has a number per sample and channel). Blocks of rows are formatted on the
  // machine's cores (one thread inside a parallel worker, parallel_for.h) and written in order.
  constexpr size_t kBlockRows = 8192;
  const size_t rows = trajectory.t.size();
  const size_t blocks = (rows + kBlockRows - 1) / kBlockRows;
  const size_t threads = static_cast<size_t>(ParallelThreads(0));
  std::vector<std::string> text(std::min(blocks, threads));
  for (size_t first = 0; first < blocks; first += text.size()) {
    const size_t batch = std::min(text.size(), blocks - first);
    ParallelFor(static_cast<int>(batch), 0, [&](int b) {
      std::string& out = text[b];
      out.clear();
      char number[32];
      auto append = [&](double value, int precision) {
        out.append(number, std::to_chars(number, number + sizeof(number), value,
                                         std::chars_format::general, precision)
                               .ptr);
      };
      const size_t begin = (first + b) * kBlockRows, end = std::min(rows, begin + kBlockRows);
      for (size_t k = begin; k < end; ++k) {
        append(trajectory.t[k], 10);
        for (const std::vector<double>& column : trajectory.columns) {
          out += ',';
          if (!std::isnan(column[k])) append(column[k], 12);
        }
        out += '\n';
      }
    });
    for (size_t b = 0; b < batch; ++b) std::fwrite(text[b].data(), 1, text[b].size(), file);
  }
  // The cause ("No space left on device", "File too large"): the failed write's errno.
  const bool written = std::ferror(file) == 0;
  int code = written ? 0 : errno;
  if (std::fclose(file) != 0 && code == 0) code = errno;
  const bool failed = !written || code != 0;
  if (failed || std::rename(temporary.c_str(), path.c_str()) != 0) {
    if (code == 0) code = errno;
    std::remove(temporary.c_str());
    *error = path + ": write failed" + (code != 0 ? ": " + std::string(std::strerror(code)) : "");
    return false;
  }
  return true;
}

}  // namespace vesselid
