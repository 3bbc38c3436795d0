#pragma once
/// @file Internal to core/mesh: the line and number scanning shared by the strict text mesh
/// readers (OFF, Medit, Gmsh, TetGen). They validate every token before they allocate or
/// index anything, and word their errors the same way: the path first, then the line.
#include <charconv>
#include <cstddef>
#include <cstdint>
#include <fstream>
#include <string>
#include <string_view>
#include <vector>

namespace progsim {

/// A non-blank line of a text file with its "#" comment (if the format has them) removed,
/// split at white space.
struct TextLine {
  std::size_t number = 0;  ///< counting from 1
  std::vector<std::string> tokens;
};

/// Hands out the non-blank lines of a text file one by one, and words its parse errors.
class TextLines {
 public:
  /// Opens `path`, read as `format` (a name for messages, such as "OFF"). "#" starts a comment
  /// if `hash_comments`. Throws Error(Status::io_error) if the file's size cannot be read
  /// (missing file, a directory).
  TextLines(const std::string& path, std::string format, bool hash_comments = true);

  /// The next non-blank line; false at the end of the file.
  bool next(TextLine& line);

  /// Like next(), but a missing line is a truncated file; `expected` names what was due.
  /// Throws Error(Status::io_error).
  TextLine require(const std::string& expected);

  /// The file's size in bytes, to bound the counts a header declares.
  std::uintmax_t file_size() const { return file_size_; }

  /// The number of the last line read (0 before the first).
  std::size_t line_number() const { return number_; }

  /// Throws Error(io_error, "<path>: cannot parse the file as <format> (line N: <what>)").
  [[noreturn]] void fail_parse(std::size_t line, const std::string& what) const;

  /// Throws Error(invalid_mesh, "<path>: <what>").
  [[noreturn]] void fail_mesh(const std::string& what) const;

  /// Throws Error(io_error, "<path>: <what>").
  [[noreturn]] void fail_io(const std::string& what) const;

  /// Throws Error(io_error) unless `count` items of at least `min_bytes` bytes each fit in the
  /// file; `what` names the items ("vertices"), `line` the header that declares them.
  void check_count(std::size_t line, std::size_t count, std::size_t min_bytes,
                   const std::string& what) const;

  /// `token` on line `line` as a count of `what` ("vertices") of at least `min_bytes` bytes
  /// each. Throws Error(io_error) unless it is a whole number that the file can hold (and an
  /// int can count).
  std::size_t count(std::size_t line, const std::string& token, std::size_t min_bytes,
                    const std::string& what) const;

  /// `token` on line `line` as a coordinate of `what` ("vertex 3"); "nan" and "inf" are read.
  /// Throws Error(io_error) if it is not a number.
  double coordinate(std::size_t line, const std::string& token, const std::string& what) const;

  /// `token` on line `line` as an index in [first, first + size), returned counting from 0.
  /// Throws Error(invalid_mesh) naming `what` ("tet 3") otherwise.
  int index(std::size_t line, const std::string& token, long long first, std::size_t size,
            const std::string& what) const;

 private:
  std::string path_;
  std::string format_;
  bool hash_comments_;
  std::ifstream in_;
  std::uintmax_t file_size_ = 0;
  std::size_t number_ = 0;
};

/// Parses all of `token` as a number of type T; false if anything is left over or wrong.
/// Accepts a leading '+', and "nan"/"inf" for floating-point T.
template <class T>
bool parse_whole(std::string_view token, T& value) {
  if (!token.empty() && token[0] == '+') token.remove_prefix(1);  // from_chars rejects '+'
  const auto [end, error] = std::from_chars(token.data(), token.data() + token.size(), value);
  return !token.empty() && error == std::errc() && end == token.data() + token.size();
}

}  // namespace progsim
