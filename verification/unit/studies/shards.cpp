// Shard ranges (docs/studies.md "Shards"): shard K of N is [⌊K C/N⌋, ⌊(K+1) C/N⌋). The reference
// is the definition itself, checked as a partition of [0, C): every case in exactly one shard,
// the sizes within one of C/N; bad K/N and I:J are refused naming the option and the rule.
#include <catch2/catch.hpp>

#include "epicycle/studies/shards.hpp"
#include "thrown_message.hpp"

using namespace epicycle;

TEST_CASE("study shards: K of N partition the cases, sizes within one of C/N",
          "[unit][studies]") {
  for (long cases : {1L, 7L, 42L, 1000000000L})
    for (long n : {1L, 2L, 3L, 7L}) {
      if (n > cases) continue;
      long next = 0;
      for (long k = 0; k < n; ++k) {
        const studies::CaseRange r = studies::ShardRange(cases, k, n, "--shard");
        INFO(cases << " cases, shard " << k << "/" << n);
        CHECK(r.first == next);  // contiguous, no gap, no overlap
        CHECK(r.Size() >= cases / n);
        CHECK(r.Size() <= cases / n + 1);
        next = r.last;
      }
      CHECK(next == cases);  // every case
    }
  CHECK(studies::PartFileName({4, 9}) == "study_cases_4_9.csv");
}

TEST_CASE("study shards: a shard or case range outside the study is refused by name",
          "[unit][studies]") {
  CHECK(test::ThrownMessage([] { studies::ShardRange(14, 3, 3, "--shard"); }) ==
        "--shard = 3/3: must be K/N with 0 <= K < N <= the study's 14 cases (K counts from 0)");
  CHECK_THAT(test::ThrownMessage([] { studies::ShardRange(2, 0, 3, "--shard"); }),
             Catch::StartsWith("--shard = 0/3: must be K/N"));
  CHECK(test::ThrownMessage([] { studies::CheckCaseRange({5, 2}, 14, "--cases"); }) ==
        "--cases = 5:2: must be I:J with 0 <= I < J <= the study's 14 cases (J exclusive)");
  CHECK_THAT(test::ThrownMessage([] { studies::CheckCaseRange({0, 15}, 14, "--cases"); }),
             Catch::StartsWith("--cases = 0:15"));
  CHECK(test::ThrownMessage([] { studies::CheckCaseRange({0, 14}, 14, "--cases"); }) ==
        "(nothing thrown)");
}
