#include "mesh/text_lines.hpp"

#include <cctype>
#include <climits>
#include <filesystem>

#include "common/error.hpp"

namespace progsim {
namespace {

std::vector<std::string> split(const std::string& text) {
  std::vector<std::string> tokens;
  std::size_t i = 0;
  const auto space = [&](std::size_t k) {
    return std::isspace(static_cast<unsigned char>(text[k])) != 0;
  };
  while (i < text.size()) {
    while (i < text.size() && space(i)) ++i;
    const std::size_t start = i;
    while (i < text.size() && !space(i)) ++i;
    if (i > start) tokens.push_back(text.substr(start, i - start));
  }
  return tokens;
}

}  // namespace

TextLines::TextLines(const std::string& path, std::string format, bool hash_comments)
    : path_(path), format_(std::move(format)), hash_comments_(hash_comments) {
  std::error_code error;
  file_size_ = std::filesystem::file_size(path, error);
  if (error) fail_io("cannot read the file's size (" + error.message() + ")");
  in_.open(path, std::ios::binary);
  if (!in_) fail_io("cannot open the file for reading");
}

bool TextLines::next(TextLine& line) {
  for (std::string text; std::getline(in_, text);) {
    ++number_;
    line = TextLine{number_, split(hash_comments_ ? text.substr(0, text.find('#')) : text)};
    if (!line.tokens.empty()) return true;
  }
  return false;
}

TextLine TextLines::require(const std::string& expected) {
  TextLine line;
  if (!next(line)) fail_parse(number_, "the file ends before " + expected + " (truncated)");
  return line;
}

void TextLines::fail_parse(std::size_t line, const std::string& what) const {
  fail(Status::io_error, path_ + ": cannot parse the file as " + format_ + " (line " +
                             std::to_string(line) + ": " + what + ")");
}

void TextLines::fail_mesh(const std::string& what) const {
  fail(Status::invalid_mesh, path_ + ": " + what);
}

void TextLines::fail_io(const std::string& what) const {
  fail(Status::io_error, path_ + ": " + what);
}

void TextLines::check_count(std::size_t line, std::size_t count, std::size_t min_bytes,
                            const std::string& what) const {
  if (count <= file_size_ / min_bytes) return;
  fail_parse(line, "it declares " + std::to_string(count) + " " + what + ", more than the file's " +
                       std::to_string(file_size_) +
                       " bytes can hold (truncated file or corrupt header)");
}

std::size_t TextLines::count(std::size_t line, const std::string& token, std::size_t min_bytes,
                             const std::string& what) const {
  std::size_t value = 0;
  if (!parse_whole(token, value))
    fail_parse(line, "the number of " + what + " '" + token + "' is not a whole number");
  check_count(line, value, min_bytes, what);
  if (value > static_cast<std::size_t>(INT_MAX))
    fail_parse(line, "more than " + std::to_string(INT_MAX) + " " + what);
  return value;
}

double TextLines::coordinate(std::size_t line, const std::string& token,
                             const std::string& what) const {
  double value = 0.0;
  if (!parse_whole(token, value))
    fail_parse(line, what + " coordinate '" + token + "' is not a number");
  return value;
}

int TextLines::index(std::size_t line, const std::string& token, long long first, std::size_t size,
                     const std::string& what) const {
  long long value = 0;
  if (parse_whole(token, value) && value >= first && value - first < static_cast<long long>(size))
    return static_cast<int>(value - first);
  fail_mesh(what + " references vertex '" + token + "', not an index in [" + std::to_string(first) +
            ", " + std::to_string(first + static_cast<long long>(size)) + ") (line " +
            std::to_string(line) + ")");
}

}  // namespace progsim
