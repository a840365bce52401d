#pragma once
// A text file read whole, for the case file and the files it names.
#include <cstddef>
#include <filesystem>
#include <string>

namespace granflow {

struct TextFile {
  enum class Status { read, cannot_open, cannot_read, too_long };
  Status status = Status::read;
  std::string text;    // the file's whole text, if read
  std::string reason;  // the system's reason it could not be opened or read
};

// Reads `file` in pieces. A read error is reported rather than taken for the end of the file, and a
// file longer than `limit` bytes is refused rather than read into memory (a device that never ends,
// /dev/zero, would otherwise be read until memory runs out).
TextFile read_text_file(const std::filesystem::path& file, std::size_t limit);

// The text of a file a case's key names (`key_path`: "obstacle[0].points_file"), `what` saying what it
// should hold ("a file of points"): throws CaseError naming the key and the file where it is a
// directory, cannot be opened or read, or is longer than `limit` bytes.
std::string read_named_file(const std::filesystem::path& file, std::size_t limit, const std::string& key_path,
                            const char* what);

}  // namespace granflow
