// The study over MPI ranks (EPICYCLE_WITH_MPI): rank 0 owns the rows file. It reads the rows
// already there, broadcasts the missing case ids, computes its own share on its threads and, on
// its main thread, receives the other ranks' rows and writes each at once (whichever rank computed
// a row, its bytes are those ComputeCase gives: the same as a threaded run).
// OpenMPI's handles (MPI_COMM_WORLD, MPI_CHAR, ...) are macros with C casts that expand here.
#pragma GCC diagnostic ignored "-Wold-style-cast"
#include <mpi.h>

#include <algorithm>
#include <chrono>
#include <cstdlib>
#include <deque>
#include <mutex>
#include <stdexcept>
#include <string>
#include <thread>
#include <vector>

#include "epicycle/config.h"
#include "epicycle/studies/runner.hpp"
#include "runner_internal.hpp"

namespace epicycle::studies {

namespace {

// A rank that cannot go on (its tables failed to build or load, a worker threw) sends kFailTag
// with its message instead of kDoneTag, so that rank 0 never waits for rows that will not come.
constexpr int kRowTag = 1, kDoneTag = 2, kFailTag = 3;

// Rank 0's share and the others' rows meet here: worker threads push, the main thread writes.
struct Outbox {
  std::mutex lock;
  std::deque<CaseRow> rows;
  bool done = false;
};

}  // namespace

bool HaveMpi() { return true; }

MpiSession::MpiSession() {
  if (!DetectMpiLaunch().launched) return;
  int provided = 0;
  MPI_Init_thread(nullptr, nullptr, MPI_THREAD_FUNNELED, &provided);
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  active_ = true;
}

MpiSession::~MpiSession() {
  if (active_) MPI_Finalize();
}

RunReport RunStudyMpi(const StudySpec& study, const RunOptions& options) {
  int initialised = 0;
  MPI_Initialized(&initialised);
  if (!initialised) return RunStudy(study, options);
  int rank = 0, size = 1;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  MPI_Comm_size(MPI_COMM_WORLD, &size);

  RunReport report;
  std::vector<long> missing;
  std::unique_ptr<internal::RowWriter> writer;
  if (rank == 0) {
    try {
      ExistingRows existing = ReadRows(options.rows_file, study, options.part);
      report.resumed = static_cast<long>(existing.rows.size());
      report.dropped_partial = existing.dropped_partial;
      report.rows = std::move(existing.rows);
      missing = internal::MissingCases(study, report.rows, options.max_new_cases, options.part);
      writer = std::make_unique<internal::RowWriter>(options.rows_file, study, options.comment,
                                                     existing.exists, options.part);
    } catch (...) {
      // Bad input found on rank 0: the other ranks wait in the broadcast; end them too.
      long none = -1;
      MPI_Bcast(&none, 1, MPI_LONG, 0, MPI_COMM_WORLD);
      throw;
    }
  }
  long count = static_cast<long>(missing.size());
  MPI_Bcast(&count, 1, MPI_LONG, 0, MPI_COMM_WORLD);
  if (count < 0) {
    if (rank == 0) return report;  // not reached: rank 0 rethrew above
    throw std::invalid_argument("the study's rows file was rejected on rank 0 (its message there)");
  }
  missing.resize(static_cast<std::size_t>(count));
  if (count > 0) MPI_Bcast(missing.data(), static_cast<int>(count), MPI_LONG, 0, MPI_COMM_WORLD);
  std::vector<long> mine;
  for (long i = rank; i < count; i += size) mine.push_back(missing[static_cast<std::size_t>(i)]);
  if (count == 0) return report;

  const auto t0 = std::chrono::steady_clock::now();
  if (rank != 0) {
    try {
      const auto compliance = internal::NominalCompliance(study, options.cache_directory);
      report.table_messages = compliance->tables().messages();
      const auto t1 = std::chrono::steady_clock::now();
      report.table_seconds = std::chrono::duration<double>(t1 - t0).count();
      // Rows go to rank 0 as their CSV text: what rank 0 writes is byte for byte what was
      // computed.
      internal::ComputeCases(study, *compliance, options.cache_directory, mine, options.threads, -1,
                             options.warm_start_cases,
                             [&](const CaseRow& r) {
                               const std::string line = r.Format();
                               MPI_Send(line.data(), static_cast<int>(line.size()), MPI_CHAR, 0,
                                        kRowTag, MPI_COMM_WORLD);
                               ++report.computed;
                             });
      report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
    } catch (const std::exception& e) {
      const std::string why = e.what();
      MPI_Send(why.data(), static_cast<int>(why.size()), MPI_CHAR, 0, kFailTag, MPI_COMM_WORLD);
      throw;
    }
    MPI_Send(nullptr, 0, MPI_CHAR, 0, kDoneTag, MPI_COMM_WORLD);
    return report;
  }
  const auto compliance = internal::NominalCompliance(study, options.cache_directory);
  report.table_messages = compliance->tables().messages();
  const auto t1 = std::chrono::steady_clock::now();
  report.table_seconds = std::chrono::duration<double>(t1 - t0).count();

  Outbox box;
  std::exception_ptr error;
  std::thread local([&] {
    try {
      internal::ComputeCases(study, *compliance, options.cache_directory, mine, options.threads, -1,
                             options.warm_start_cases,
                             [&](const CaseRow& r) {
                               const std::lock_guard<std::mutex> g(box.lock);
                               box.rows.push_back(r);
                             });
    } catch (...) {
      error = std::current_exception();
    }
    const std::lock_guard<std::mutex> g(box.lock);
    box.done = true;
  });
  auto accept = [&](const CaseRow& row, const std::string& text) {
    writer->Write(text);
    report.rows.push_back(row);
    ++report.computed;
    if (options.on_row) options.on_row(row, static_cast<long>(report.rows.size()),
                         options.part ? options.part->Size() : study.Cases());
  };
  int remote_done = 0;
  bool local_done = false;
  std::vector<std::string> failures;
  while (remote_done < size - 1 || !local_done) {
    {
      std::deque<CaseRow> rows;
      {
        const std::lock_guard<std::mutex> g(box.lock);
        rows.swap(box.rows);
        local_done = box.done;
      }
      for (const CaseRow& r : rows) accept(r, r.Format());
    }
    int flag = 0;
    MPI_Status status;
    MPI_Iprobe(MPI_ANY_SOURCE, MPI_ANY_TAG, MPI_COMM_WORLD, &flag, &status);
    if (!flag) {
      std::this_thread::sleep_for(std::chrono::milliseconds(2));
      continue;
    }
    int bytes = 0;
    MPI_Get_count(&status, MPI_CHAR, &bytes);
    std::string line(static_cast<std::size_t>(bytes), '\0');
    MPI_Recv(line.data(), bytes, MPI_CHAR, status.MPI_SOURCE, status.MPI_TAG, MPI_COMM_WORLD,
             MPI_STATUS_IGNORE);
    if (status.MPI_TAG == kDoneTag) {
      ++remote_done;
      continue;
    }
    if (status.MPI_TAG == kFailTag) {
      // The other ranks and this one finish their shares (bounded); the failed rank's cases stay
      // missing, and a rerun computes them.
      ++remote_done;
      failures.push_back("rank " + std::to_string(status.MPI_SOURCE) + " stopped (" + line +
                         "); its cases were not computed");
      continue;
    }
    const std::string text = line;
    if (!line.empty() && line.back() == '\n') line.pop_back();
    accept(internal::ParseRow(line, study, "row from rank " + std::to_string(status.MPI_SOURCE)),
           text);
  }
  local.join();
  {
    const std::lock_guard<std::mutex> g(box.lock);
    for (const CaseRow& r : box.rows) accept(r, r.Format());
  }
  if (error) std::rethrow_exception(error);
  if (!failures.empty()) {
    std::string m;
    for (const std::string& f : failures) m += (m.empty() ? "" : "; ") + f;
    throw std::runtime_error(m + ". The rows file holds the " + std::to_string(report.computed) +
                             " new rows of the other ranks; run the study again to compute the "
                             "missing cases");
  }
  report.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t1).count();
  std::sort(report.rows.begin(), report.rows.end(),
            [](const CaseRow& a, const CaseRow& b) { return a.id < b.id; });
  return report;
}

}  // namespace epicycle::studies
