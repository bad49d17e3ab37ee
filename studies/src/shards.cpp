#include "epicycle/studies/shards.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

#include "runner_internal.hpp"

namespace epicycle::studies {

namespace {

std::string RangeText(const CaseRange& r) {
  return std::to_string(r.first) + ":" + std::to_string(r.last);
}

std::string Named(const PartHead& h) { return h.path + " (cases " + RangeText(h.range) + ")"; }

// "I:J of C" at the start of `text`; false if it does not parse.
bool ParseRangeOf(const std::string& text, CaseRange* range, long* cases) {
  long first = 0, last = 0, total = 0;
  int used = 0;
  if (std::sscanf(text.c_str(), "%ld:%ld of %ld%n", &first, &last, &total, &used) != 3) return false;
  *range = CaseRange{first, last};
  *cases = total;
  return used > 0;
}

}  // namespace

CaseRange ShardRange(long cases, long shard, long shards, const std::string& option) {
  if (shards < 1 || shard < 0 || shard >= shards || shards > cases)
    throw std::invalid_argument(option + " = " + std::to_string(shard) + "/" +
                                std::to_string(shards) +
                                ": must be K/N with 0 <= K < N <= the study's " +
                                std::to_string(cases) + " cases (K counts from 0)");
  // ⌊k C/N⌋ without overflow for C up to 1e9 and N up to C (long is 64 bits here).
  return CaseRange{shard * cases / shards, (shard + 1) * cases / shards};
}

void CheckCaseRange(const CaseRange& range, long cases, const std::string& option) {
  if (range.first < 0 || range.last <= range.first || range.last > cases)
    throw std::invalid_argument(option + " = " + RangeText(range) +
                                ": must be I:J with 0 <= I < J <= the study's " +
                                std::to_string(cases) + " cases (J exclusive)");
}

std::string PartFileName(const CaseRange& range) {
  return "study_cases_" + std::to_string(range.first) + "_" + std::to_string(range.last) + ".csv";
}

PartHead ReadPartHead(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::invalid_argument(path + ": cannot read the study part");
  PartHead h;
  h.path = path;
  std::string line;
  bool first = true;
  while (std::getline(in, line) && !line.empty() && line[0] == '#') {
    if (line.rfind("# study ", 0) == 0) {
      h.study_line = line;
    } else if (line.rfind("# part cases ", 0) == 0) {
      h.part_line = line;
      if (!ParseRangeOf(line.substr(sizeof("# part cases ") - 1), &h.range, &h.cases))
        throw std::invalid_argument(path + ": a malformed part line '" + line + "'");
      h.stresses = line.size() >= 3 && line.compare(line.size() - 3, 3, " on") == 0;
    } else if (line.rfind("# part of study file ", 0) == 0) {
      h.study_file = line.substr(sizeof("# part of study file ") - 1);
    } else if (first) {
      h.comment = line.substr(line.rfind("# ", 0) == 0 ? 2 : 1);
    }
    first = false;
  }
  if (h.part_line.empty())
    throw std::invalid_argument(path +
                                ": not a study part (no '# part cases' line before its column "
                                "line): give the parts written by `epicycle study FILE --cases "
                                "I:J` or `--shard K/N`");
  return h;
}

std::vector<std::string> FindParts(const std::vector<std::string>& paths) {
  std::vector<std::string> parts;
  for (const std::string& p : paths) {
    std::error_code error;
    if (std::filesystem::is_directory(p, error)) {
      std::vector<std::string> found;
      for (const auto& e : std::filesystem::directory_iterator(p)) {
        const std::string name = e.path().filename().string();
        if (e.is_regular_file() && name.rfind("study_cases_", 0) == 0 &&
            name.size() > 4 && name.compare(name.size() - 4, 4, ".csv") == 0)
          found.push_back(e.path().string());
      }
      if (found.empty())
        throw std::invalid_argument(p + ": a folder without study parts (study_cases_*.csv)");
      std::sort(found.begin(), found.end());
      parts.insert(parts.end(), found.begin(), found.end());
    } else if (std::filesystem::exists(p, error)) {
      parts.push_back(p);
    } else {
      throw std::invalid_argument(p + ": no such study part or folder of parts");
    }
  }
  if (parts.empty()) throw std::invalid_argument("no study parts given to merge");
  return parts;
}

MergedRows MergeParts(const StudySpec& study, const std::vector<std::string>& parts) {
  std::vector<PartHead> heads;
  for (const std::string& p : parts) heads.push_back(ReadPartHead(p));
  // Each part of this study: the same study line (name, study hash, seed, count) and part line
  // (scene hash, stresses) as the study would write for its range.
  for (const PartHead& h : heads) {
    if (h.study_line != internal::StudyLine(study))
      throw std::invalid_argument(Named(h) + " is a part of another study ('" + h.study_line +
                                  "'; the study merged is '" + internal::StudyLine(study) + "')");
    if (h.part_line != internal::PartLine(study, h.range))
      throw std::invalid_argument(Named(h) + " was computed on another scene or with other "
                                  "outputs ('" + h.part_line + "'; the study merged gives '" +
                                  internal::PartLine(study, h.range) + "')");
  }
  std::sort(heads.begin(), heads.end(), [](const PartHead& a, const PartHead& b) {
    return a.range.first != b.range.first ? a.range.first < b.range.first
                                          : a.range.last < b.range.last;
  });
  // Every case in exactly one part: sorted by first id, a part must start where the one before
  // it ended.
  long next = 0;
  for (std::size_t i = 0; i < heads.size(); ++i) {
    const CaseRange& r = heads[i].range;
    if (r.first < next)
      throw std::invalid_argument(
          Named(heads[i - 1]) + " and " + Named(heads[i]) + " overlap in cases " +
          RangeText({r.first, std::min(next, r.last)}) +
          " (a shard given twice, or shards of different counts): give each case's part once");
    if (r.first > next)
      throw std::invalid_argument(
          "cases " + RangeText({next, r.first}) + " are in no part (" +
          (i == 0 ? std::string("before ") : "between " + Named(heads[i - 1]) + " and ") +
          Named(heads[i]) + "): run `epicycle study FILE --cases " + RangeText({next, r.first}) +
          "` and merge again");
    next = r.last;
  }
  if (next < study.Cases())
    throw std::invalid_argument("cases " + RangeText({next, study.Cases()}) +
                                " are in no part (after " + Named(heads.back()) +
                                "): run `epicycle study FILE --cases " +
                                RangeText({next, study.Cases()}) + "` and merge again");
  MergedRows merged;
  merged.comment = heads.front().comment;
  merged.rows.reserve(static_cast<std::size_t>(study.Cases()));
  for (const PartHead& h : heads) {
    // A truncated last line (a shard killed while writing) is left for the shard's rerun to cut
    // off: the merge changes no part.
    {
      std::ifstream in(h.path, std::ios::binary | std::ios::ate);
      const auto size = static_cast<long long>(in.tellg());
      char last = '\n';
      if (size > 0) {
        in.seekg(size - 1);
        in.get(last);
      }
      if (last != '\n')
        throw std::invalid_argument(Named(h) +
                                    " ends in a truncated row (its shard was stopped while "
                                    "writing): run its shard again to resume it, then merge");
    }
    ExistingRows part = ReadRows(h.path, study, h.range);
    if (static_cast<long>(part.rows.size()) != h.range.Size()) {
      const std::vector<long> missing = internal::MissingCases(study, part.rows, 1, h.range);
      throw std::invalid_argument(Named(h) + " holds " + std::to_string(part.rows.size()) +
                                  " of its " + std::to_string(h.range.Size()) +
                                  " cases (the first missing: case " +
                                  std::to_string(missing.front()) +
                                  "): run its shard again to resume it, then merge");
    }
    std::sort(part.rows.begin(), part.rows.end(),
              [](const CaseRow& a, const CaseRow& b) { return a.id < b.id; });
    for (CaseRow& r : part.rows) merged.rows.push_back(std::move(r));
  }
  return merged;
}

void WriteRowsFile(const std::string& path, const StudySpec& study, const std::string& comment,
                   const std::vector<CaseRow>& rows) {
  const std::string temporary = path + ".merging";
  std::error_code error;
  std::filesystem::remove(temporary, error);
  {
    internal::RowWriter writer(temporary, study, comment, false);
    for (const CaseRow& r : rows) writer.Write(r.Format());
  }
  std::filesystem::rename(temporary, path, error);
  if (error) throw std::runtime_error(path + ": cannot write the study's rows (" +
                                      error.message() + ")");
}

}  // namespace epicycle::studies
