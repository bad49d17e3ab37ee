// One tolerance study, as every front end asks for it (docs/studies.md): a request (the study and
// typed overrides: stresses, threads, a partial run, a part, the rows file; every default resolved
// here), a run that computes or resumes the cases (RunStudyMpi: threads, MPI ranks) and streams
// each new row to a sink, and one record of the study's summary. The program (`epicycle study`)
// and Python's `study` parse their options into a request and format the record; report/ writes
// its one serialisation (report::RecordJson), whose keys are the fields VisitRecord names.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/studies/runner.hpp"
#include "epicycle/studies/shards.hpp"
#include "epicycle/studies/study.hpp"
#include "epicycle/studies/study_summary.hpp"
#include "epicycle/transmission/record.hpp"

namespace epicycle::studies {

/// What a study run is asked for.
struct StudyRequest {
  StudySpec study;         ///< read and validated (ReadStudy, ParseStudy)
  std::string study_path;  ///< the study file as the user named it (in the record)
  bool stresses = false;   ///< root stresses too (also when the study or scene asks for them)
  int threads = 0;         ///< worker threads [-]; 0: one per core
  long max_cases = -1;     ///< compute at most this many new cases (< 0: all) [-]
  std::optional<CaseRange> part;  ///< only these cases, into a part file (no summary)
  /// The rows file (created or resumed); a part's is in its folder under PartFileName.
  std::string rows_file;
  std::string comment;          ///< the rows file's provenance comment (without '#')
  std::string cache_directory;  ///< FE influence-table cache; empty: in memory only
  int rank = 0;  ///< this process's MPI rank (MpiSession::rank): rank 0 alone summarises
};

/// Where a run streams each row as it is written (under the writer's lock).
class StudySink {
 public:
  virtual ~StudySink() = default;
  virtual void Row(const CaseRow& /*row*/, long /*rows*/, long /*total*/) {}
};

/// What a study found: its summary over every row of the file. Every field is in the record's one
/// serialisation (VisitRecord).
struct StudyRecord {
  std::string study;       ///< the study file as named in the request
  std::string study_hash;  ///< of the study text (StudySpec::hash)
  std::uint64_t seed = 0;
  long cases_total = 0;               ///< of the study [-]
  StudySummary summary;               ///< over the rows in the file
  std::vector<std::string> warnings;  ///< the study's
  double computed_seconds = 0;        ///< wall time of the cases computed now [s]
};

/// What the run did besides its record (for a front end's console): rows resumed and computed,
/// the tables' messages and time.
struct StudyRun {
  RunReport report;
  /// The study's record; none for a part (its rows only: the summary is the merge's) and on MPI
  /// ranks other than 0.
  std::optional<StudyRecord> record;
};

/// Resolves the request's defaults (threads: one per core; stresses), runs or resumes the cases
/// (RunStudyMpi) and summarises them.
/// @throws std::invalid_argument as RunStudy; std::runtime_error if the rows file cannot be
/// written.
StudyRun RunStudy(const StudyRequest& request, StudySink& sink);

/// The record of `rows` (a merge's, a run's): the study's summary and its identity.
StudyRecord MakeStudyRecord(const StudySpec& study, const std::string& study_path,
                            const std::vector<CaseRow>& rows, double computed_seconds);

/// The record's fields, each once with its name and unit (its serialisation's keys).
void VisitRecord(const StudyRecord& record, transmission::RecordVisitor& visit);

}  // namespace epicycle::studies
