// Output files as a set: refuse to replace earlier results unless asked, and
// write several text files all or nothing.
#pragma once
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "stickslip/io/metadata.hpp"

namespace stickslip::io {

// The results of a finished sweep that `dir` holds now (results.nc,
// summary.json, summary.csv, records.csv, and a sensitivity study's
// sensitivity.nc; the journal is not a result).
[[nodiscard]] std::vector<std::string> existing_sweep_results(const std::string& dir);

// The run metadata (resolved configuration, version, git revision, command
// line, creation time) that DIR/results.nc of a finished sweep (or
// DIR/sensitivity.nc of a sensitivity study) carries in its global attributes; nullopt, with the reason in `problem`, when the file is
// missing, unreadable or lacks the resolved configuration.
[[nodiscard]] std::optional<run_metadata> read_finished_metadata(const std::string& dir,
                                                                 std::string* problem = nullptr);
// The `warning` global attribute of the same file (an unmet --target-ci, or
// a study's undefined or wide indices): what a --resume that finds the run
// finished says again, in the CLI and in Python. "" when there is none or
// the file cannot be read.
[[nodiscard]] std::string read_finished_warning(const std::string& dir);

// Throws stickslip::error (exit code 2, invalid input) naming the first of
// `paths` that exists: "'P' already exists (...): <how_to_proceed>".
// `what` says what the file is ("the results of an earlier sweep").
void refuse_to_replace(const std::vector<std::string>& paths, const std::string& what,
                       const std::string& how_to_proceed);

// The outputs of an earlier run that write_all removed (it returns them)
// and that are still gone, in one line for a note: "removed 'a', 'b': they
// were an earlier run's, which this run does not write"; empty when there
// are none. A file written again since (a study's figure, drawn after
// write_all) is not named.
[[nodiscard]] std::string removed_outputs_note(const std::vector<std::string>& removed);

// One output file: the flag that names it (for messages), its path, and
// the function that prints its text.
struct text_output {
  std::string flag;  // "-o", "--events-file", ...
  std::string path;
  std::function<std::string()> text;
};

// Writes every file, or none. First the checks: no path may be a directory or
// named twice, and unless `replace_existing` none may exist yet
// (refuse_to_replace with `how_to_proceed`). Then each file goes to
// `path.tmp` (flushed, fsynced), and only then are all renamed into place. A failure removes the temporaries, the files this
// call already renamed, and the directories it created, and throws
// stickslip::error with the system's reason: exit code 2 when a path is an
// existing directory or two outputs share a path, 3 for I/O failures.
void write_text_files(const std::vector<text_output>& files, bool replace_existing,
                      const std::string& how_to_proceed);

}  // namespace stickslip::io
