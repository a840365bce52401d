#include "io/text_file.hpp"

#include <cerrno>
#include <cstring>
#include <fstream>

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

}  // namespace granflow
