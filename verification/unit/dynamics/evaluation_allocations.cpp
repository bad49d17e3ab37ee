// Heap allocations during one right-hand-side evaluation (DynamicModel::Evaluate) of the paper's
// run-out case (scenes/paper_stage_runout.toml, FE compliance with the local terms), sun fixed
// and floating, friction on (the scene's Xu & Kahraman) and off: with the same Evaluation passed
// again and the same contact set, an evaluation allocates nothing (docs/dynamic_cost.md).
//
// The count: this file replaces the C library's allocating functions (malloc, calloc, realloc,
// aligned_alloc, posix_memalign, memalign) by pass-throughs to glibc's own (__libc_malloc, ...)
// that add one to a counter while it is switched on. Counting there rather than in a replaced
// operator new sees Eigen's matrices too (Eigen allocates with std::malloc) as well as every
// operator new (the C++ library's calls malloc, its aligned form aligned_alloc); free is glibc's,
// which owns every block either way. The replacement holds for the whole test executable
// (epicycle_tests_dynamics); with the counter off it only forwards. Under a sanitizer, whose
// runtime replaces malloc itself, the replacement and the case are left out.
#include <catch2/catch.hpp>

#include <cstddef>
#include <cstdlib>
#include <new>
#include <string>
#include <vector>

#include "dynamics_fixtures.hpp"
#include "stage_fixtures.hpp"

#if defined(__SANITIZE_ADDRESS__) || defined(__SANITIZE_THREAD__)
#define EPICYCLE_TEST_COUNTS_ALLOCATIONS 0
#elif defined(__has_feature)
#if __has_feature(address_sanitizer) || __has_feature(thread_sanitizer) || \
    __has_feature(memory_sanitizer)
#define EPICYCLE_TEST_COUNTS_ALLOCATIONS 0
#endif
#endif
#if !defined(EPICYCLE_TEST_COUNTS_ALLOCATIONS) && defined(__GLIBC__)
#define EPICYCLE_TEST_COUNTS_ALLOCATIONS 1
#endif

#if EPICYCLE_TEST_COUNTS_ALLOCATIONS

namespace {
// One thread evaluates; thread_local keeps another thread's allocations out of the count.
thread_local bool counting = false;
thread_local long allocations = 0;
inline void Count() {
  if (counting) ++allocations;
}
}  // namespace

extern "C" {
void* __libc_malloc(std::size_t);
void* __libc_calloc(std::size_t, std::size_t);
void* __libc_realloc(void*, std::size_t);
void* __libc_memalign(std::size_t, std::size_t);

void* malloc(std::size_t size) {
  Count();
  return __libc_malloc(size);
}
void* calloc(std::size_t n, std::size_t size) {
  Count();
  return __libc_calloc(n, size);
}
void* realloc(void* p, std::size_t size) {
  Count();
  return __libc_realloc(p, size);
}
void* aligned_alloc(std::size_t alignment, std::size_t size) {
  Count();
  return __libc_memalign(alignment, size);
}
void* memalign(std::size_t alignment, std::size_t size) {
  Count();
  return __libc_memalign(alignment, size);
}
int posix_memalign(void** out, std::size_t alignment, std::size_t size) {
  Count();
  // posix_memalign's rules: a power of two, a multiple of sizeof(void*).
  if (alignment % sizeof(void*) != 0 || (alignment & (alignment - 1)) != 0) return 22;  // EINVAL
  void* p = __libc_memalign(alignment, size);
  if (p == nullptr && size != 0) return 12;  // ENOMEM
  *out = p;
  return 0;
}
}  // extern "C"

using namespace epicycle;

namespace {

// Heap allocations made while f runs.
template <class F>
long AllocationsDuring(F&& f) {
  allocations = 0;
  counting = true;
  f();
  counting = false;
  return allocations;
}

bool SameContacts(const dynamics::Evaluation& a, const dynamics::Evaluation& b) {
  if (a.terms.size() != b.terms.size()) return false;
  for (int j = 0; j < a.terms.size(); ++j)
    if (a.terms.contacts[j].Label() != b.terms.contacts[j].Label()) return false;
  return true;
}

}  // namespace

TEST_CASE("allocation counter: operator new, aligned new, Eigen and std::string are counted",
          "[unit][dynamics]") {
  // The counter itself, on allocations it must see (else a zero below would mean nothing).
  CHECK(AllocationsDuring([] {
          std::vector<double> v(100);
          REQUIRE(v.size() == 100);
        }) == 1);
  CHECK(AllocationsDuring([] {
          Eigen::VectorXd x(64);
          x.setOnes();
          REQUIRE(x.sum() == 64);
        }) == 1);
  CHECK(AllocationsDuring([] {
          auto* p = new (std::align_val_t{64}) double[8];
          ::operator delete[](p, std::align_val_t{64});
        }) == 1);
  CHECK(AllocationsDuring([] {
          std::string s(100, 'x');
          REQUIRE(s.size() == 100);
        }) == 1);
  CHECK(AllocationsDuring([] {}) == 0);
}

TEST_CASE("a warm evaluation of the run-out case allocates nothing", "[unit][dynamics]") {
  const auto sun = GENERATE(transmission::SunSupport::kFixed, transmission::SunSupport::kFloating);
  test::RigOptions o;
  o.sun = sun;
  const test::DynamicRig rig =
      test::MakeRig(test::SceneText("paper_stage_runout.toml"), "paper_stage_runout.toml", o);
  REQUIRE(rig.scene.dynamics.friction.law != transmission::FrictionLaw::kOff);
  // The same stage model with friction off.
  transmission::DynamicSettings off = rig.scene.dynamics;
  off.friction.law = transmission::FrictionLaw::kOff;
  dynamics::DynamicModel frictionless(*rig.stage_model, off, rig.scene.inertia, rig.scene.loads);
  frictionless.SetMeshStiffness(rig.model->sun_mesh_stiffness(), rig.model->ring_mesh_stiffness());

  for (const dynamics::DynamicModel* model : {rig.model.get(), &frictionless}) {
    const bool friction = model == rig.model.get();
    CAPTURE(sun == transmission::SunSupport::kFixed ? "sun fixed" : "sun floating", friction);
    const Eigen::VectorXd d = model->QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
    const Eigen::VectorXd v = Eigen::VectorXd::Zero(model->size());
    auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
    // As the integrator calls it: two neighbouring states (one step of 3 µs apart) in turn, each
    // warm-started from the other; the first rounds size every buffer.
    dynamics::Evaluation pair[2];
    const double times[2] = {0.0, 3e-6};
    model->Evaluate(times[0], d, v, *solver, {}, nullptr, &pair[0], false);
    for (int round = 0; round < 4; ++round)
      for (int k = 0; k < 2; ++k)
        model->Evaluate(times[k], d, v, *solver, {}, &pair[1 - k], &pair[k], false);
    REQUIRE(pair[0].ok);
    REQUIRE(pair[1].ok);
    REQUIRE(SameContacts(pair[0], pair[1]));
    REQUIRE(pair[0].terms.size() > 0);
    const Eigen::VectorXd before = pair[0].acceleration;
    long counted = 0;
    for (int k : {0, 1})
      counted += AllocationsDuring(
          [&] { model->Evaluate(times[k], d, v, *solver, {}, &pair[1 - k], &pair[k], false); });
    CHECK(pair[0].ok);
    CHECK(pair[1].ok);
    CHECK(SameContacts(pair[0], pair[1]));
    // The evaluation measured is the one of the rounds before it (the warm start moves it by
    // round-off at most).
    CHECK((pair[0].acceleration - before).norm() <= 1e-9 * before.norm());
    CHECK(counted == 0);
    if (friction) CHECK(pair[0].friction.cwiseAbs().maxCoeff() > 0);
    // The count sees the evaluation's own buffers: the same evaluation into a fresh work space
    // (no poses, search, compliance or tip-round buffers kept) allocates.
    dynamics::Evaluation fresh;
    CHECK(AllocationsDuring(
              [&] { model->Evaluate(times[0], d, v, *solver, {}, &pair[1], &fresh, false); }) > 0);
  }
}

TEST_CASE("a warm evaluation of a stage with face-width slices allocates nothing",
          "[unit][dynamics][face_width]") {
  // scenes/paper_stage_pin_tilt.toml: 20 uncoupled slices per contact and planet 1's pin tilted,
  // friction on. The slices' expansion (FaceWidthModel::Expand into the terms' own buffers) and
  // the contact problem's Kronecker terms (validated from their factors, no dense Cholesky) are on
  // the path measured. At 10 slices too, the kernel S I of the face's other count.
  const int slices = GENERATE(10, 20);
  CAPTURE(slices);
  std::string text = test::SceneText("paper_stage_pin_tilt.toml");
  const std::string key = "slices = 20";
  const std::size_t at = text.find(key);
  REQUIRE(at != std::string::npos);
  text.replace(at, key.size(), "slices = " + std::to_string(slices));
  const test::DynamicRig rig = test::MakeRig(text, "paper_stage_pin_tilt.toml", {});
  REQUIRE(rig.scene.face_width.slices == slices);
  const dynamics::DynamicModel& model = *rig.model;
  const Eigen::VectorXd d = model.QuasiStaticStart({}, solvers::Backend::kActiveSetNewton);
  const Eigen::VectorXd v = Eigen::VectorXd::Zero(model.size());
  auto solver = solvers::MakeContactSolver(solvers::Backend::kActiveSetNewton);
  dynamics::Evaluation pair[2];
  const double times[2] = {0.0, 3e-6};
  model.Evaluate(times[0], d, v, *solver, {}, nullptr, &pair[0], false);
  for (int round = 0; round < 4; ++round)
    for (int k = 0; k < 2; ++k)
      model.Evaluate(times[k], d, v, *solver, {}, &pair[1 - k], &pair[k], false);
  REQUIRE(pair[0].ok);
  REQUIRE(pair[1].ok);
  REQUIRE(SameContacts(pair[0], pair[1]));
  // Every potential contact is split into its slices, and the terms carry the structure.
  REQUIRE(pair[0].terms.size() == slices * static_cast<int>(pair[0].terms.plane_contacts.size()));
  REQUIRE(pair[0].terms.compliance_terms.size() == 1);
  long counted = 0;
  for (int k : {0, 1})
    counted += AllocationsDuring(
        [&] { model.Evaluate(times[k], d, v, *solver, {}, &pair[1 - k], &pair[k], false); });
  CHECK(pair[0].ok);
  CHECK(pair[1].ok);
  CHECK(counted == 0);
  // The count sees the slices' buffers: a fresh work space allocates them.
  dynamics::Evaluation fresh;
  CHECK(AllocationsDuring(
            [&] { model.Evaluate(times[0], d, v, *solver, {}, &pair[1], &fresh, false); }) > 0);
}

#endif  // EPICYCLE_TEST_COUNTS_ALLOCATIONS
