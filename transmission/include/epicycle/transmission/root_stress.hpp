// Root-stress read-outs (docs/model.md §9, docs/stresses.md): each gear's largest tensile and
// compressive fillet stress in one state, and over many states (a sweep, a run) the extremes and
// the largest range at one fillet point (a planet tooth bends one way in the sun mesh and the
// other in the ring mesh: ISO 6336-5's reversed bending).
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "epicycle/compliance/compliance_operator.hpp"

namespace epicycle::transmission {

/// A point of a fillet: tooth k of the body (body frame), side (0: σ = +1, 1: σ = −1) and arc
/// length from the space centre line along the fillet [m].
struct FilletSpot {
  int tooth = 0;
  int side = 0;
  double arc_length = 0;  ///< [m]
};

/// One gear's extremes. Both are 0 (with a default spot) where the state loads no tooth of it.
struct GearRootStress {
  int body = 0;        ///< kSunBody, kRingBody, PlanetBody(i)
  double tension = 0;  ///< largest σ_tt, ≥ 0 [Pa]
  FilletSpot tension_at;
  double compression = 0;  ///< most negative σ_tt, ≤ 0 [Pa]
  FilletSpot compression_at;
};

/// The extremes of bodies 0 … bodies − 1 over `fillets` (StageCompliance::FilletStresses).
std::vector<GearRootStress> SummariseRootStress(
    const std::vector<compliance::FilletStress>& fillets, int bodies);

/// Per fillet point the range max − min of σ_tt over many states.
class RootStressEnvelope {
 public:
  explicit RootStressEnvelope(int bodies) : bodies_(bodies) {}
  void Add(const std::vector<compliance::FilletStress>& fillets);
  int states() const { return states_; }
  /// Per body: the largest range max − min of σ_tt at one fillet point [Pa] and where. A point
  /// seen in fewer states than were added counts 0 for the states that did not compute it (its
  /// tooth was neither loaded nor a neighbour of a loaded one).
  struct Range {
    int body = 0;
    double range = 0;  ///< [Pa]
    FilletSpot at;
    double max = 0, min = 0;  ///< σ_tt at that point [Pa]
  };
  std::vector<Range> Ranges() const;

 private:
  struct Point {
    std::vector<double> max, min;  // start at 0: an unloaded state
    const compliance::InfluenceTable* table = nullptr;
  };
  int bodies_ = 0;
  int states_ = 0;
  // points_[body][2 tooth + side], sized by the body's teeth when it is first seen (a point
  // without table was never computed).
  std::vector<std::vector<Point>> points_;
};

/// Per body over many states (a sweep's positions, a run's output steps): the extremes, where
/// they occur (`x`: the carrier angle [rad] or the time [s] the caller gives with each state) and
/// the largest range at one fillet point.
struct RootStressSummary {
  std::string gear;  ///< the body's name ("sun", "planet1", "gear1": the tracker's `gears`)
  GearRootStress extremes;
  double tension_x = 0;      ///< the state's x at the largest tension
  double compression_x = 0;  ///< at the most negative compression
  RootStressEnvelope::Range range;
};

/// Accumulates states into RootStressSummary per body; a state without fillets adds nothing.
class RootStressTracker {
 public:
  /// `gears`: the name of each body index, the bodies 0 … gears.size() − 1 (a stage's
  /// BodyNames(PlanetBody(planets)), a pair's MeshPairSetup::gears).
  explicit RootStressTracker(std::vector<std::string> gears)
      : bodies_(static_cast<int>(gears.size())), envelope_(bodies_), gears_(std::move(gears)) {}
  void Add(const std::vector<compliance::FilletStress>& fillets, double x);
  /// The same with the state's extremes already summarised (`extremes`:
  /// SummariseRootStress(fillets, gears.size()), the state's own, which its CSV line shows too).
  void Add(const std::vector<compliance::FilletStress>& fillets,
           const std::vector<GearRootStress>& extremes, double x);
  /// Empty when no state carried fillets.
  std::vector<RootStressSummary> Result() const;

 private:
  int bodies_ = 0;
  RootStressEnvelope envelope_;
  std::vector<std::string> gears_;
  std::vector<RootStressSummary> summary_;
};

}  // namespace epicycle::transmission
