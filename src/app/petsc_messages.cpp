#include "app/petsc_messages.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <sstream>
#include <string>
#include <string_view>
#include <thread>
#include <vector>

#include "io/text_file.hpp"
#include "solver/linear_solver.hpp"

namespace granflow {

void warn_unused_petsc_options(int rank, const std::set<std::string>* judged) {
  PetscInt n = 0;
  char **names = nullptr, **values = nullptr;
  PetscOptionsLeftGet(nullptr, &n, &names, &values);
  // Read only by PetscFinalize, after this check.
  constexpr std::string_view at_finalize[] = {"options_view", "options_left", "memory_view",
                                              "malloc_dump",  "malloc_view",  "objects_dump"};
  if (rank == 0)
    for (PetscInt k = 0; k < n; ++k)
      if (std::find(std::begin(at_finalize), std::end(at_finalize), std::string_view(names[k])) == std::end(at_finalize) &&
          !is_default_petsc_option(names[k]) && (!judged || judged->count(names[k])))
        fmt::print(stderr, "warning: PETSc option -{} was given but not used (misspelt, or no such solver)\n", names[k]);
  PetscOptionsLeftRestore(nullptr, &n, &names, &values);
}

// PETSc's errors as one line, where PETSc would print its whole trace: the first report of an error
// (PETSC_ERROR_INITIAL) is printed, the frames it passes through on its way up are not. Every such
// error ends the run (the calls that may fail and are handled push PETSc's quiet handler over this
// one), so a single process exits here, before an abort adds Open MPI's banner; several ranks abort
// here, with status 1 whatever PETSc's error code.
// Running out of memory while the grid is made is the common case. GRANFLOW_PETSC_TRACE=1 keeps
// PETSc's own trace.
void say_error_once(const std::string& what) {
  int world_rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &world_rank);
  // The other ranks wait, so that rank 0's abort stops them before they say it again; an error of one
  // rank alone is still said, by that rank, two seconds later (time for an abort to arrive on a loaded
  // machine).
  if (world_rank > 0) std::this_thread::sleep_for(std::chrono::seconds(2));
  fmt::print(stderr, "error: {}{}\n", what, world_rank > 0 ? fmt::format(" (rank {})", world_rank) : "");
  std::fflush(stderr);
}

namespace {
bool petsc_started = false;

PetscErrorCode one_line_petsc_error(MPI_Comm, int line, const char* function, const char* file, PetscErrorCode code,
                                    PetscErrorType type, const char* message, void*) {
  if (type != PETSC_ERROR_INITIAL) return code;
  const bool memory = code == PETSC_ERR_MEM || std::string_view(function) == "PetscMallocAlign";
  const char* text = nullptr;
  PetscErrorMessage(code, &text, nullptr);
  std::string what = memory ? "out of memory (a coarser mesh may do)"
                            : text ? text : "error";
  if (!memory && message && *message && std::string_view(message) != what) what += fmt::format(": {}", message);
  // Most such errors (an option value PETSc does not know) are met by every rank at once.
  say_error_once(fmt::format("PETSc: {} (PETSc error {} in {}, {}:{})", what, int(code), function, file, line));
  int world_size = 1;
  MPI_Comm_size(MPI_COMM_WORLD, &world_size);
  if (world_size == 1) std::_Exit(1);
  MPI_Abort(MPI_COMM_WORLD, 1);  // the status of README's "Exit status", not PETSc's error code
  return code;
}

std::string startup_error;

PetscErrorCode keep_startup_petsc_error(MPI_Comm, int, const char*, const char*, PetscErrorCode code,
                                        PetscErrorType type, const char* message, void*) {
  if (type == PETSC_ERROR_INITIAL && startup_error.empty()) {
    const char* text = nullptr;
    PetscErrorMessage(code, &text, nullptr);
    startup_error = message && *message ? message : text ? text : "error";
  }
  return code;
}

}  // namespace

PetscErrorCode granflow_petsc_error(MPI_Comm comm, int line, const char* function, const char* file,
                                    PetscErrorCode code, PetscErrorType type, const char* message, void* context) {
  return petsc_started ? one_line_petsc_error(comm, line, function, file, code, type, message, context)
                       : keep_startup_petsc_error(comm, line, function, file, code, type, message, context);
}

void petsc_has_started() { petsc_started = true; }

const std::string& startup_petsc_error_text() { return startup_error; }

namespace {

// An options file as PETSc reads it while it starts, with the files it includes in turn: readable,
// of a sane length, and not including itself (PETSc would recurse until its stack ran out). The lines'
// own syntax is PETSc's to judge (keep_startup_petsc_error says what it found). `chain` holds the
// files that include this one. Empty when every file can be used.
std::string unusable_options_file(const std::string& source, const std::string& option, const std::string& file,
                                  std::vector<std::string>& chain) {
  std::error_code ec;
  const std::string path = std::filesystem::weakly_canonical(file, ec).string();
  if (std::find(chain.begin(), chain.end(), path) != chain.end()) {
    std::string loop;
    for (auto k = std::find(chain.begin(), chain.end(), path); k != chain.end(); ++k) loop += *k + " -> ";
    return fmt::format("{} {}: {} includes itself ({}{})", source, option, file, loop, path);
  }
  constexpr std::size_t limit = std::size_t(1) << 20;
  const TextFile read = std::filesystem::is_directory(file, ec)
                            ? TextFile{TextFile::Status::cannot_open, {}, "a directory"}
                            : read_text_file(file, limit);
  switch (read.status) {
    case TextFile::Status::read: break;
    case TextFile::Status::cannot_open:
    case TextFile::Status::cannot_read: return fmt::format("{} {}: cannot read {}: {}", source, option, file, read.reason);
    case TextFile::Status::too_long:
      return fmt::format("{} {}: {} is longer than {} MiB, not an options file", source, option, file, limit >> 20);
  }
  if (option != "-options_file") return {};
  chain.push_back(path);
  std::istringstream lines(read.text);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line.substr(0, line.find('#')));
    std::string first, second;
    if (words >> first >> second && first == "-options_file")
      if (auto problem = unusable_options_file(source, option, second, chain); !problem.empty()) return problem;
  }
  chain.pop_back();
  return {};
}

}  // namespace

// PETSc stops inside PetscInitialize, with its error trace, on an options file it cannot read, and
// finds a -log_view file it cannot write only at the end of the run: say which, in one line, before
// anything runs. Empty when every such file among the words (of --petsc or PETSC_OPTIONS) can be used.
std::string unusable_petsc_file(const std::vector<std::string>& words, const std::string& source) {
  for (size_t k = 0; k < words.size(); ++k) {
    if (words[k] == "-log_view" && k + 1 < words.size() && words[k + 1][0] != '-') {
      // [type]:file[:format]: a file named where the viewer's type ends
      const std::string& viewer = words[k + 1];
      const size_t colon = viewer.find(':');
      if (colon == std::string::npos) continue;
      const std::string file = viewer.substr(colon + 1, viewer.find(':', colon + 1) - colon - 1);
      if (file.empty()) continue;
      const std::filesystem::path path(file);
      const std::filesystem::path dir = path.has_parent_path() ? path.parent_path() : std::filesystem::path(".");
      std::error_code ec;
      const bool writable = std::filesystem::exists(path, ec) ? !std::filesystem::is_directory(path, ec) &&
                                                                     access(file.c_str(), W_OK) == 0
                                                               : std::filesystem::is_directory(dir, ec) &&
                                                                     access(dir.c_str(), W_OK) == 0;
      if (!writable) return fmt::format("{} -log_view {}: cannot write {}", source, viewer, file);
      continue;
    }
    if (words[k] != "-options_file" && words[k] != "-options_file_yaml") continue;
    if (k + 1 == words.size()) return fmt::format("{} {}: names no file", source, words[k]);
    std::vector<std::string> chain;
    if (auto problem = unusable_options_file(source, words[k], words[k + 1], chain); !problem.empty()) return problem;
  }
  return {};
}

}  // namespace granflow
