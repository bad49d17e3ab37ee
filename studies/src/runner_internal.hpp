// Pieces of the study runner shared by the threaded (runner.cpp) and MPI (mpi_runner.cpp) runs.
#pragma once

#include <cstdio>
#include <functional>
#include <memory>
#include <mutex>
#include <string>
#include <vector>

#include "epicycle/geometry/stage.hpp"
#include "epicycle/studies/runner.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/quasistatic.hpp"

namespace epicycle::studies::internal {

/// "# study <name>; study_hash ...; seed ...; cases ...": identifies the study in its rows file.
std::string StudyLine(const StudySpec& study);
/// "# part cases I:J of C; scene_hash ...; stresses on|off": the cases a part file holds.
std::string PartLine(const StudySpec& study, const CaseRange& range);
/// "# part of study file <absolute path>" (where the merge finds the study file).
std::string PartStudyFileLine(const StudySpec& study);
/// The carrier angles of every case [rad].
std::vector<double> CaseAngles(const StudySpec& study, const geometry::Stage& stage);
/// A row from its CSV line. @throws std::invalid_argument naming `where`.
CaseRow ParseRow(const std::string& line, const StudySpec& study, const std::string& where);
/// The first `limit` case ids without a row (< 0: all), ascending, of `part` (none: of the
/// study); memory for the rows' ids and those returned only (a study of 1e9 samples run with
/// --max-cases 3 lists 3 ids).
std::vector<long> MissingCases(const StudySpec& study, const std::vector<CaseRow>& rows,
                               long limit, const std::optional<CaseRange>& part = std::nullopt);

/// Appends whole lines to the rows file, each flushed at once (writes the comment, study, part
/// and column lines first when the file is new).
class RowWriter {
 public:
  RowWriter(const std::string& path, const StudySpec& study, const std::string& comment,
            bool exists, const std::optional<CaseRange>& part = std::nullopt);
  ~RowWriter();
  RowWriter(const RowWriter&) = delete;
  RowWriter& operator=(const RowWriter&) = delete;
  void Write(const std::string& text);

 private:
  std::FILE* file_ = nullptr;
  std::string path_;
};

/// The warm starts of the cases' first positions (docs/studies.md "Throughput"): per grid point
/// g, the converged first position of case g (the grid point's first sample), solved cold once on
/// first use and shared read-only; every case of grid point g starts its first position from it,
/// whichever worker, rank or shard computes the case, so a row does not depend on the schedule.
class CaseStarts {
 public:
  /// Grid points beyond which the cases start cold (each start holds its contact problem).
  static constexpr long kMaxGridPoints = 256;
  /// enabled = false, a study that varies the bodies or more than kMaxGridPoints: every case cold.
  CaseStarts(const StudySpec& study, const transmission::StageCompliance& compliance,
             bool enabled);
  /// The start of case `case_id`'s first position; nullptr: cold. Thread-safe.
  const transmission::PositionResult* For(long case_id);

 private:
  const StudySpec& study_;
  const transmission::StageCompliance& compliance_;
  std::unique_ptr<std::once_flag[]> once_;
  std::vector<std::unique_ptr<transmission::PositionResult>> starts_;
};

/// The ids on a pool of `threads` workers (warm_start: CaseStarts); `sink` sees each row under
/// one lock.
void ComputeCases(const StudySpec& study, const transmission::StageCompliance& compliance,
                  const std::string& cache_directory, const std::vector<long>& ids, int threads,
                  long limit, bool warm_start, const std::function<void(const CaseRow&)>& sink);

/// The FE compliance of the base scene's nominal bodies, shared by every case.
std::unique_ptr<transmission::FeStageCompliance> NominalCompliance(
    const StudySpec& study, const std::string& cache_directory);

}  // namespace epicycle::studies::internal
