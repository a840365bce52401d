#include "io/text_file.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fstream>

#include "io/case_error.hpp"

namespace granflow {

TextFile read_text_file(const std::filesystem::path& file, std::size_t limit) {
  TextFile f;
  std::ifstream in(file, std::ios::binary);
  if (!in) return {TextFile::Status::cannot_open, {}, std::strerror(errno)};
  char piece[1 << 16];
  while (in.read(piece, sizeof piece) || in.gcount() > 0) {
    f.text.append(piece, std::size_t(in.gcount()));
    if (f.text.size() > limit) return {TextFile::Status::too_long, {}, {}};
  }
  if (in.bad()) return {TextFile::Status::cannot_read, {}, errno != 0 ? std::strerror(errno) : "input/output error"};
  return f;
}

std::string read_named_file(const std::filesystem::path& file, std::size_t limit, const std::string& key_path,
                            const char* what) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw CaseError(fmt::format("{}: '{}' is a directory, not {}", key_path, file.string(), what));
  TextFile read = read_text_file(file, limit);
  switch (read.status) {
    case TextFile::Status::read: break;
    case TextFile::Status::cannot_open:
      throw CaseError(fmt::format("{}: cannot open '{}': {}", key_path, file.string(), read.reason));
    case TextFile::Status::cannot_read:
      throw CaseError(fmt::format("{}: cannot read '{}': {}", key_path, file.string(), read.reason));
    case TextFile::Status::too_long:
      throw CaseError(fmt::format("{}: '{}' is longer than {} MiB, not {}", key_path, file.string(), limit >> 20, what));
  }
  return std::move(read.text);
}

}  // namespace granflow
