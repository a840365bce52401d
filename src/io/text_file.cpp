#include "io/text_file.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
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

std::optional<double> number_in(std::string_view field) {
  if (field.starts_with('+')) {
    field.remove_prefix(1);
    if (field.starts_with('-') || field.starts_with('+')) return std::nullopt;
  }
  double value = 0.0;
  const auto [ptr, ec] = std::from_chars(field.data(), field.data() + field.size(), value);
  if (field.empty() || ec != std::errc() || ptr != field.data() + field.size()) return std::nullopt;
  return value;
}

std::string printable(std::string_view text, std::size_t most) {
  std::string out;
  for (std::size_t i = 0; i < std::min(text.size(), most); ++i) {
    const auto byte = static_cast<unsigned char>(text[i]);
    if (byte >= 0x20 && byte < 0x7f)
      out += char(byte);
    else
      out += fmt::format("\\x{:02X}", byte);
  }
  if (text.size() > most) out += fmt::format("... ({} bytes)", text.size());
  return out;
}

}  // namespace granflow
