#include "epicycle/studies/sampling.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <numbers>
#include <stdexcept>
#include <string>

#include "epicycle/studies/sobol.hpp"

namespace epicycle::studies {

namespace {

// SplitMix64's finaliser (Steele, Lea & Flood 2014): a bijective mix of 64 bits, so that nearby
// counters give unrelated seeds.
std::uint64_t Mix(std::uint64_t z) {
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

}  // namespace

bool Iso1328Applies(int grade, double reference_diameter, double module) {
  const double d = reference_diameter * 1e3, m = module * 1e3;
  return grade >= 1 && grade <= 11 && m >= 0.5 && m <= 70.0 && d >= 5.0 && d <= 15000.0;
}

double Iso1328RunoutTolerance(int grade, double reference_diameter, double module) {
  if (!Iso1328Applies(grade, reference_diameter, module))
    throw std::invalid_argument(
        "ISO 1328-1: class " + std::to_string(grade) + ", d = " +
        std::to_string(reference_diameter * 1e3) + " mm, m_n = " + std::to_string(module * 1e3) +
        " mm: outside classes 1..11, 0.5 <= m_n <= 70 mm, 5 <= d <= 15000 mm");
  const double d = reference_diameter * 1e3, m = module * 1e3;
  const double fp =
      (0.002 * d + 0.55 * std::sqrt(d) + 0.7 * m + 12.0) * std::pow(std::numbers::sqrt2, grade - 5);
  return 0.9 * fp * 1e-6;
}

CaseStream::CaseStream(std::uint64_t seed, long case_id, int variable)
    : engine_(Mix(Mix(Mix(seed) ^ static_cast<std::uint64_t>(case_id)) ^
                  static_cast<std::uint64_t>(variable))) {}

double CaseStream::Uniform() {
  // The top 53 bits as a fraction: every double in [0, 1) on the 2^-53 grid, equally likely.
  return static_cast<double>(engine_() >> 11) * 0x1.0p-53;
}

double CaseStream::Normal() {
  // Box–Muller: u1 in (0, 1] keeps the logarithm finite.
  const double u1 = 1.0 - Uniform(), u2 = Uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * std::numbers::pi * u2);
}

std::vector<double> SampleCase(const StudySpec& study, long case_id) {
  if (case_id < 0 || case_id >= study.Cases())
    throw std::invalid_argument("case " + std::to_string(case_id) + ": the study has " +
                                std::to_string(study.Cases()) + " cases");
  if (study.design == Design::kSobol) return SobolCaseValues(study, case_id);
  return DrawValues(study, case_id);
}

std::vector<double> DrawValues(const StudySpec& study, long stream) {
  std::vector<double> values;
  // Grid point g = k mod G (the first grid variable varies fastest); the random streams use k.
  long grid_index = stream % study.GridPoints();
  for (std::size_t j = 0; j < study.variables.size(); ++j) {
    const Variable& v = study.variables[j];
    const double to_file = SiToFile(v.quantity);
    CaseStream rng(study.seed, stream, static_cast<int>(j));
    double x = 0.0;
    switch (v.distribution) {
      case Distribution::kNormal:
        x = v.mean + v.sigma * rng.Normal();
        break;
      case Distribution::kUniform:
      case Distribution::kIso1328:
        x = v.min + (v.max - v.min) * rng.Uniform();
        break;
      case Distribution::kGrid: {
        const long size = static_cast<long>(v.grid.size());
        x = v.grid[static_cast<std::size_t>(grid_index % size)];
        grid_index /= size;
        break;
      }
    }
    values.push_back(x * to_file);
    if (v.quantity == Quantity::kRunout) values.push_back(360.0 * rng.Uniform());
  }
  return values;
}

transmission::Scene CaseScene(const StudySpec& study, const std::vector<double>& values) {
  transmission::Scene scene = study.scene;
  geometry::StageSpec& st = scene.stage;
  const auto n = static_cast<std::size_t>(st.planets);
  std::size_t c = 0;
  for (const Variable& v : study.variables) {
    const double x = values.at(c++);
    const double si = x * FileToSi(v.quantity);
    const auto i = static_cast<std::size_t>(v.target.planet);
    switch (v.quantity) {
      case Quantity::kPinRadial:
      case Quantity::kPinTangential:
        if (st.pin_errors.empty()) st.pin_errors.assign(n, {});
        (v.quantity == Quantity::kPinRadial ? st.pin_errors[i].radial
                                            : st.pin_errors[i].tangential) = si;
        break;
      case Quantity::kRunout: {
        const geometry::Runout r{si, values.at(c++) * std::numbers::pi / 180.0};
        if (v.target.kind == Target::Kind::kSun) st.sun_runout = r;
        if (v.target.kind == Target::Kind::kRing) st.ring_runout = r;
        if (v.target.kind == Target::Kind::kPlanet) {
          if (st.planet_runouts.empty()) st.planet_runouts.assign(n, {});
          st.planet_runouts[i] = r;
        }
        break;
      }
      case Quantity::kThickness:
        if (v.target.kind == Target::Kind::kSun) st.sun.thickness_error = si;
        if (v.target.kind == Target::Kind::kRing) st.ring.thickness_error = si;
        if (v.target.kind == Target::Kind::kPlanet) {
          if (st.planet_thickness_errors.empty()) st.planet_thickness_errors.assign(n, 0.0);
          st.planet_thickness_errors[i] = si;
        }
        break;
      case Quantity::kTorque:
        if (!(si * study.scene.loads.sun_torque > 0))
          throw std::invalid_argument(
              "sampled torque " + std::to_string(si) +
              " N m: must be non-zero with the sign of the scene's sun_torque_Nm = " +
              std::to_string(study.scene.loads.sun_torque) +
              " (the loaded flanks are the scene's)");
        scene.loads.sun_torque = si;
        break;
      case Quantity::kPitDepth:
      case Quantity::kPitWidth: {
        // A normal distribution's draw can leave the scene's range: the case is refused.
        transmission::Pit& p = scene.damage.pits.at(static_cast<std::size_t>(v.target.pit));
        const bool depth = v.quantity == Quantity::kPitDepth;
        const double hi = depth ? 0.25 * st.sun.module : 1.0;
        if (!(si > 0 && si <= hi))
          throw std::invalid_argument(
              "sampled pit" + std::to_string(v.target.pit) + (depth ? " depth " : " width ") +
              std::to_string(depth ? si * 1e6 : si) + (depth ? " um" : "") + ": must be in (0, " +
              std::to_string(depth ? hi * 1e6 : hi) + "] (the scene's depth_um, width_fraction)");
        (depth ? p.depth : p.width_fraction) = si;
        break;
      }
      case Quantity::kPinTiltRadial:
      case Quantity::kPinTiltTangential: {
        // The value over the planet's face width b replaces that component of the scene's tilt.
        transmission::FaceWidthSpec& f = scene.face_width;
        auto it = std::find_if(
            f.pin_tilts.begin(), f.pin_tilts.end(),
            [&](const transmission::PinTilt& p) { return p.planet == v.target.planet; });
        if (it == f.pin_tilts.end()) {
          f.pin_tilts.push_back({});
          it = std::prev(f.pin_tilts.end());
          it->planet = v.target.planet;
        }
        (v.quantity == Quantity::kPinTiltRadial ? it->radial : it->tangential) =
            si / st.planet.face_width;
        it->where = study.source + ": variable " + v.Columns().front() + " (the case's " +
                    std::to_string(it->radial * st.planet.face_width * 1e6) + " um radial, " +
                    std::to_string(it->tangential * st.planet.face_width * 1e6) +
                    " um tangential over the face width)";
        break;
      }
      case Quantity::kLeadSlope:
      case Quantity::kCrowning: {
        const bool crowning = v.quantity == Quantity::kCrowning;
        // A draw below 0 (a grid's or uniform's values are checked when read): refused.
        if (crowning && !(si >= 0))
          throw std::invalid_argument("sampled " + v.Columns().front() + " " +
                                      std::to_string(si * 1e6) +
                                      " um: must be >= 0 (the scene's crowning_um)");
        transmission::FaceWidthSpec& f = scene.face_width;
        const std::string gear = v.target.Name();
        auto it = std::find_if(f.leads.begin(), f.leads.end(),
                               [&](const transmission::LeadSpec& l) { return l.gear == gear; });
        if (it == f.leads.end()) {
          f.leads.push_back({});
          it = std::prev(f.leads.end());
          it->gear = gear;
        }
        (crowning ? it->crowning : it->slope) = si;
        it->where = study.source + ": variable " + v.Columns().front() + " (the case's slope " +
                    std::to_string(it->slope * 1e6) + " um, crowning " +
                    std::to_string(it->crowning * 1e6) + " um)";
        break;
      }
      case Quantity::kCrackDepth: {
        compliance::RootCrack& k =
            scene.damage.cracks.at(static_cast<std::size_t>(v.target.crack)).crack;
        if (!(si > 0))
          throw std::invalid_argument("sampled crack" + std::to_string(v.target.crack) + " depth " +
                                      std::to_string(si * 1e3) +
                                      " mm: must be > 0 (the scene's depth_mm)");
        if (k.path.size() == 1) {
          k.path[0].length = si;
        } else {
          const double scale = si / k.depth();  // a polyline's segments alike
          for (compliance::CrackSegment& g : k.path) g.length *= scale;
        }
        break;
      }
    }
  }
  // A case's tilts and leads within the contact search's window, as the scene reader checks them.
  transmission::CheckFaceGapWindow(scene);
  return scene;
}

}  // namespace epicycle::studies
