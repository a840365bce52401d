#pragma once
// A text file read whole, for the case file and the files it names.
#include <cstddef>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>

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
// The number a whole field of a text file spells (an optional '+', then what std::from_chars reads: "nan"
// and "inf" too), or none: an empty field, "+-5", "1.5m".
std::optional<double> number_in(std::string_view field);

// A piece of a file as a message shows it: its first `most` bytes, those that are not printable ASCII as
// \xNN, so that a binary file named by mistake does not fill the terminal with its bytes.
std::string printable(std::string_view text, std::size_t most);

std::string read_named_file(const std::filesystem::path& file, std::size_t limit, const std::string& key_path,
                            const char* what);

}  // namespace granflow
