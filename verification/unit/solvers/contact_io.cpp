// Problem files: exact round trip, and clear errors for bad files.
#include <catch2/catch.hpp>

#include <cstdio>
#include <fstream>

#include "contact_collection.hpp"
#include "epicycle/solvers/contact_io.hpp"

namespace epicycle::solvers {

TEST_CASE("problem files round-trip exactly", "[unit][solvers]") {
  GearLikeSpec spec;
  spec.support_stiffness = 1e-9;
  ContactProblemFile f = MakeGearLikeProblem(spec, "roundtrip");
  f.provenance = {{"version", "0.1.0"}, {"scene_hash", "fnv1a64:0123456789abcdef"}};
  const std::string path = "contact_io_roundtrip.json";
  WriteContactProblemFile(f, path);
  const ContactProblemFile g = ReadContactProblemFile(path);
  std::remove(path.c_str());
  CHECK(g.data.name == "roundtrip");
  CHECK(g.category == "gear-like");
  REQUIRE(g.seed.has_value());
  CHECK(*g.seed == spec.seed);
  CHECK(g.data.compliance == f.data.compliance);  // bit for bit
  CHECK(g.data.overlap == f.data.overlap);
  CHECK(g.data.equality_matrix == f.data.equality_matrix);
  CHECK(g.data.equality_rhs == f.data.equality_rhs);
  CHECK(g.data.support_stiffness == f.data.support_stiffness);
  REQUIRE(g.data.local.size() == f.data.local.size());
  CHECK(g.data.local[5].body[1].depth == f.data.local[5].body[1].depth);
  CHECK(g.data.contact_labels == f.data.contact_labels);
  CHECK(g.data.multiplier_labels == f.data.multiplier_labels);
  CHECK(g.provenance == f.provenance);
}

TEST_CASE("bad problem files give clear errors", "[unit][solvers]") {
  const std::string head = R"({"format": "epicycle-contact-problem", "version": 1, )";
  auto parse = [](const std::string& t) { return ParseContactProblemFile(t, "t.json"); };
  CHECK_THROWS_WITH(parse("{"), Catch::Contains("t.json: not valid JSON"));
  // A number beyond double is bad JSON too (a fuzzing finding: it escaped as another exception).
  CHECK_THROWS_WITH(parse(head + R"("overlap_m": [-1.1e8500], "compliance_m_per_N": [[1]]})"),
                    Catch::Contains("t.json: not valid JSON") && Catch::Contains("overflow"));
  CHECK_THROWS_WITH(
      parse(R"({"format": "x", "version": 1, "overlap_m": [0], "compliance_m_per_N": [[1]]})"),
      Catch::Contains("key 'format'"));
  CHECK_THROWS_WITH(
      parse(
          R"({"format": "epicycle-contact-problem", "version": 2, "overlap_m": [0], "compliance_m_per_N": [[1]]})"),
      Catch::Contains("key 'version'") && Catch::Contains("reads version 1"));
  CHECK_THROWS_WITH(
      parse(head + R"("overlap_m": [0], "compliance_m_per_N": [[1]], "complience": 1})"),
      Catch::Contains("key 'complience': unknown key"));
  CHECK_THROWS_WITH(parse(head + R"("compliance_m_per_N": [[1]]})"),
                    Catch::Contains("key 'overlap_m': missing"));
  CHECK_THROWS_WITH(parse(head + R"("overlap_m": [null], "compliance_m_per_N": [[1e-9]]})"),
                    Catch::Contains("key 'overlap_m[0]': must be a number, found null"));
  CHECK_THROWS_WITH(
      parse(head + R"("overlap_m": [0, 0], "compliance_m_per_N": [[1e-9, 0], [0]]})"),
      Catch::Contains("compliance_m_per_N[1]") && Catch::Contains("rows must have equal length"));
  CHECK_THROWS_WITH(
      parse(head + R"("overlap_m": [0, 0], "compliance_m_per_N": [[1e-9, 0], [1e-9, 1e-9]]})"),
      Catch::Contains("t.json: compliance is not symmetric"));
  CHECK_THROWS_WITH(
      parse(
          head +
          R"("overlap_m": [0], "compliance_m_per_N": [[1e-9]], "local": [{"face_width_m": -0.025, "reduced_radius_m": 0.01, "bodies": [{"youngs_modulus_Pa": 2e11, "poisson_ratio": 0.3, "depth_m": 0.002}, {"youngs_modulus_Pa": 2e11, "poisson_ratio": 0.3, "depth_m": 0.002}]}]})"),
      Catch::Contains("local[0].face_width = -0.025"));
  CHECK_THROWS_WITH(ReadContactProblemFile("/nonexistent/p.json"),
                    Catch::Contains("cannot be opened"));
}

}  // namespace epicycle::solvers
