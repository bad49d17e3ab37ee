// Running a study: case k = the quasi-static sweep of the base scene with case k's sampled values
// (studies/sampling.hpp), one row per case appended to the rows file as soon as it is computed
// (written and flushed whole: a killed run leaves at most one truncated last line, which the next
// run drops), a thread pool over the cases with one solver per thread, and a restart that reads
// the rows already written and computes only the missing cases.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "epicycle/studies/study.hpp"
#include "epicycle/transmission/quasistatic.hpp"
#include "epicycle/transmission/run_status.hpp"
#include "epicycle/transmission/stage_problem.hpp"

namespace epicycle::studies {

/// One case's result: the row of the rows file.
struct CaseRow {
  long id = 0;                 ///< case id k, 0-based [-]
  std::vector<double> values;  ///< sampled values in file units (StudySpec::Columns())
  /// How the case ended (the rows file's status field: "ok" for kCompleted, else the status's
  /// name): kCompleted (every position converged), kContactFailure (a position's contact solve
  /// failed), kBadSampledValue (a sampled value broke a rule of the scene: not run), kGeometry
  /// (the stage could not be built or evaluated at the sampled values).
  transmission::RunStatus status = transmission::RunStatus::kContactFailure;
  bool ok() const { return status == transmission::RunStatus::kCompleted; }
  std::string message;               ///< why not (commas and newlines replaced by ';')
  int positions = 0, converged = 0;  ///< [-]
  double k_gamma = 0;                ///< K_γ = max over positions of max_i L_i [-]
  double k_gamma_mean = 0;           ///< max_i of the sweep mean of L_i [-]
  double lsr_min = 0, lsr_max = 0;   ///< extremes of LSR_i over planets and positions [-]
  double te_peak_to_peak = 0;        ///< loaded static transmission error, peak to peak [µrad]
  double sun_orbit = 0;              ///< largest sun-centre displacement [µm]
  /// With stresses (StudySpec::StressGears, else empty): per gear in that order three values over
  /// the case's sweep, its largest root tension (≥ 0), its most negative compression (≤ 0) and
  /// its largest range max − min at one fillet point [MPa] (transmission::RootStressSummary).
  std::vector<double> root_stress;
  /// With StudySpec::Rated (else empty): per gear in StressGears' order, S_F from the case's
  /// largest root tension and S_H from its largest line-of-action Hertz pressure [-]
  /// (transmission::GearRating::s_f_stress, s_h_pressure; K_A of the scene, K_v = 1).
  std::vector<double> safety;
  /// With slices of the face width (StudySpec::FaceMeshes, else empty): per mesh in that order
  /// the largest K_Hβ over the case's sweep and the largest L_i·K_Hβ of its planet at one position
  /// (transmission::MeshFaceSummary: k_h_beta_max, k_gamma_k_h_beta_max) [-].
  std::vector<double> face_load;
  /// A helical stage (StudySpec::HelicalColumns, else empty): the values of those columns [N],
  /// [N·m], [µrad].
  std::vector<double> helical;
  /// The CSV line, '\n'-terminated; numbers in their shortest exact (round-trip) form, so that
  /// the same result gives the same bytes; a failed case has empty result fields; the last field
  /// is the row's check (FNV-1a 64 of the text before it, 16 hex digits).
  std::string Format() const;
};

/// The column line of the rows file (without '\n'); with stresses the results end with
/// sigma_t_<gear>_MPa, sigma_c_<gear>_MPa, sigma_range_<gear>_MPa per gear before the message;
/// then S_F_<gear>, S_H_<gear> per gear when rated (StudySpec::Rated); then K_Hbeta_<mesh>,
/// K_gamma_K_Hbeta_<mesh> per mesh with slices of the face width; then a helical stage's
/// StudySpec::HelicalColumns; the check is last.
std::string RowHeader(const StudySpec& study);

/// Case k of the study on the shared (read-only) compliance of the nominal bodies, or, when the
/// study varies the bodies (StudySpec::VariesBodies: a crack's depth), on the case's own tables
/// (built or read from `cache_directory`; empty: built in memory). Never throws for a failed
/// computation or a case the geometry rejects: the row says why (ok = false).
/// `start`: the case's first position is warm-started from it (the converged first position of
/// another case at the same angle: docs/studies.md "Throughput"); nullptr: cold.
CaseRow ComputeCase(const StudySpec& study, const transmission::StageCompliance& compliance,
                    long case_id, const std::string& cache_directory = {},
                    const transmission::PositionResult* start = nullptr);

/// A slice of a study's case ids, [first, last) (a shard's part: studies/shards.hpp).
struct CaseRange {
  long first = 0;  ///< the first case id [-]
  long last = 0;   ///< one past the last case id [-]
  long Size() const { return last - first; }
  bool Contains(long id) const { return id >= first && id < last; }
};

/// What a rows file already holds.
struct ExistingRows {
  std::vector<CaseRow> rows;     ///< complete, valid rows, in file order
  bool dropped_partial = false;  ///< a truncated last line (a killed run) was dropped
  bool exists = false;           ///< the file existed with a header
};
/// Reads `path` (nothing if it does not exist). A last line without its '\n' is a row the writer
/// was killed in: it is dropped and the file cut back to the last complete line.
/// @throws std::invalid_argument if the file belongs to another study (its study line or column
///         line differ), holds a malformed complete line, a case twice, a row whose check does
///         not match its text or whose sampled values are not the study's for its case (the
///         message names the file and line).
/// With `part`: the file is the part of those cases (its part line, docs/studies.md "Shards"),
/// and a row of another case is refused; without, a part file is refused (merge it instead).
ExistingRows ReadRows(const std::string& path, const StudySpec& study,
                      const std::optional<CaseRange>& part = std::nullopt);

struct RunOptions {
  std::string rows_file;        ///< the CSV of rows (created or resumed)
  std::string comment;          ///< a provenance comment line written first (without '#')
  std::string cache_directory;  ///< FE influence-table cache; empty: in memory only
  int threads = 1;              ///< worker threads, each with its own solver [-]
  long max_new_cases = -1;      ///< stop after computing this many cases (< 0: all) [-]
  /// Only these cases, into a part file (rows_file: its name is studies::PartFileName) that says
  /// so (studies/shards.hpp); none: the whole study.
  std::optional<CaseRange> part;
  /// Warm-start each case's first position from its grid point's first case (docs/studies.md
  /// "Throughput"; within the solvers' tolerances of the cold start); false: cold.
  bool warm_start_cases = true;
  /// Sees each new row as it is written (under the writer's lock), with the count of rows now in
  /// the file and the study's total.
  std::function<void(const CaseRow&, long rows, long total)> on_row;
};

struct RunReport {
  long resumed = 0;   ///< rows found in the file [-]
  long computed = 0;  ///< rows computed now [-]
  bool dropped_partial = false;
  std::vector<CaseRow> rows;                ///< every row of the file, sorted by case id
  std::vector<std::string> table_messages;  ///< what the influence-table cache did
  double seconds = 0;                       ///< of the computation of the new rows [s]
  double table_seconds = 0;                 ///< of building or loading the tables [s]
};

/// Runs (or resumes) the study on this process with `threads` workers.
/// @throws std::invalid_argument as ReadRows, or for a base scene that cannot be built;
///         std::runtime_error if the rows file cannot be written.
RunReport RunStudy(const StudySpec& study, const RunOptions& options);

/// Whether this build has MPI (EPICYCLE_WITH_MPI).
bool HaveMpi();

/// What an MPI launcher told this process through its environment: OpenMPI's mpirun sets
/// OMPI_COMM_WORLD_SIZE and OMPI_COMM_WORLD_RANK, PMI launchers (srun, MPICH's mpiexec) PMI_SIZE
/// and PMI_RANK, PMIx launchers PMIX_RANK.
struct MpiLaunch {
  bool launched = false;  ///< one of the variables is set
  long size = 1;          ///< the largest size given (1 if none) [-]
  long rank = 0;          ///< the largest rank given (0 if none) [-]
  std::string evidence;   ///< the variables found, "OMPI_COMM_WORLD_SIZE = 2, ..." (for messages)
  /// Part of a launch of more than one process (size > 1 or a rank > 0).
  bool Parallel() const { return size > 1 || rank > 0; }
};
/// The launch described by the environment; `lookup` is getenv (a test passes its own table).
/// A value that is not a whole number counts as launched with size and rank unknown (1 and 0).
MpiLaunch DetectMpiLaunch(const std::function<const char*(const char*)>& lookup);
MpiLaunch DetectMpiLaunch();

/// MPI for the lifetime of the object: MPI_Init_thread (funneled: only the main thread calls MPI)
/// when this build has MPI and the process was started by a launcher (DetectMpiLaunch),
/// MPI_Finalize at the end; otherwise inactive (rank 0 of 1).
/// @throws std::invalid_argument in a build without MPI started as one of several processes by a
///         launcher (each would run the whole study into the same rows file): the message says to
///         build with -DEPICYCLE_WITH_MPI=ON.
class MpiSession {
 public:
  MpiSession();
  ~MpiSession();
  MpiSession(const MpiSession&) = delete;
  MpiSession& operator=(const MpiSession&) = delete;
  bool active() const { return active_; }
  int rank() const { return rank_; }
  int size() const { return size_; }

 private:
  bool active_ = false;
  int rank_ = 0, size_ = 1;
};
/// The same over MPI ranks (call between MPI_Init and MPI_Finalize on every rank): rank 0 reads
/// the rows file and hands every rank its share of the missing cases (case i of the missing list
/// to rank i mod size); each rank computes with `threads` workers and sends its rows to rank 0,
/// which alone writes the file. The report is complete on rank 0; other ranks get their counts.
/// Without MPI: RunStudy. @throws as RunStudy (on the rank that finds the problem; the others are
/// aborted by MPI_Abort).
RunReport RunStudyMpi(const StudySpec& study, const RunOptions& options);

}  // namespace epicycle::studies
