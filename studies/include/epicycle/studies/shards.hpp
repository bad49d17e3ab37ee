// Shards of a study for any scheduler (docs/studies.md "Shards"): a slice of the case ids run as
// a part file of its own (the rows file of those cases, with the same seeds and bytes as a whole
// run's rows, and a line saying which cases of which study it holds), and the merge that joins
// the parts of one study into the rows a single run writes.
#pragma once

#include <string>
#include <vector>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/study.hpp"

namespace epicycle::studies {

/// Shard `shard` of `shards` (0-based) of a study of `cases` cases: the ids
/// [⌊shard·cases/shards⌋, ⌊(shard + 1)·cases/shards⌋), contiguous and together every id once.
/// @throws std::invalid_argument naming `option` unless 0 ≤ shard < shards ≤ cases.
CaseRange ShardRange(long cases, long shard, long shards, const std::string& option);
/// @throws std::invalid_argument naming `option` and the range unless 0 ≤ first < last ≤ cases.
void CheckCaseRange(const CaseRange& range, long cases, const std::string& option);

/// The part file's name in its folder: "study_cases_<first>_<last>.csv" (last exclusive).
std::string PartFileName(const CaseRange& range);

/// What a part file says about itself (its comment lines before the column line).
struct PartHead {
  std::string path;
  std::string comment;     ///< its first comment line (the provenance), without "# "
  std::string study_line;  ///< "# study <name>; study_hash ...; seed ...; cases ..."
  std::string part_line;   ///< "# part cases I:J of C; scene_hash ...; stresses on|off"
  CaseRange range;         ///< the cases it holds
  long cases = 0;          ///< the study's total [-]
  bool stresses = false;   ///< its rows have the root-stress columns
  std::string study_file;  ///< the study file as the shard read it (absolute path)
};
/// @throws std::invalid_argument naming the file if it is not a part (no part line).
PartHead ReadPartHead(const std::string& path);

/// The part files of `paths`: a file is taken as given, a folder gives its study_cases_*.csv
/// files (sorted by name). @throws std::invalid_argument naming a path that does not exist or a
/// folder without parts.
std::vector<std::string> FindParts(const std::vector<std::string>& paths);

/// The parts of one study joined: every case once, sorted by case id.
struct MergedRows {
  std::string comment;        ///< the first part's provenance comment (without "# ")
  std::vector<CaseRow> rows;  ///< sorted by case id
};
/// Reads and checks the parts (without changing them): each of this study (its study line,
/// scene hash, stresses and column line), complete (every case of its range, no truncated last
/// line), their ranges neither overlapping nor leaving a gap in [0, Cases()).
/// @throws std::invalid_argument naming the part file(s) and the case range at fault.
MergedRows MergeParts(const StudySpec& study, const std::vector<std::string>& parts);

/// Writes a whole rows file (as a single run leaves it after all its cases: the comment, study
/// and column lines, then `rows` in the given order), through a temporary file renamed into
/// place. @throws std::runtime_error if it cannot be written.
void WriteRowsFile(const std::string& path, const StudySpec& study, const std::string& comment,
                   const std::vector<CaseRow>& rows);

}  // namespace epicycle::studies
