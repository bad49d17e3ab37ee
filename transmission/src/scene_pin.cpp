// The scene's [[face_width.pin]] array: the planets' pins as load-dependent tilts (pin.hpp;
// docs/scenes.md, "Face width"; the model: docs/model.md §10, "The planet's pin").
#include <string>

#include "scene_internal.hpp"

namespace epicycle::transmission::internal {

void ReadPins(TableReader& face_width, Scene& s) {
  FaceWidthSpec& f = s.face_width;
  const int planets = s.stage.planets;
  const double b = s.stage.planet.face_width;
  for (TableReader& r : face_width.TableArray("pin")) {
    PinSpec p;
    p.where = r.Where(r.Has("planet") ? "planet" : "mounting");
    if (f.slices < 2)
      r.Fail("mounting", "given with face_width.slices = 1",
             "a planet's tilt on its pin varies the gap along the face width, which needs "
             "slices >= 2");
    if (r.Has("planet"))
      p.planet = static_cast<int>(r.Integer("planet", Rule::Closed(1, planets).Because(
                                                          "planets are numbered 1.." +
                                                          std::to_string(planets)))) -
                 1;
    for (const PinSpec& q : f.pins)
      if (q.planet == p.planet)
        r.Fail("planet", p.planet < 0 ? "(absent: every planet)" : std::to_string(p.planet + 1),
               "a pin for " +
                   (p.planet < 0 ? std::string("every planet")
                                 : "planet " + std::to_string(p.planet + 1)) +
                   " is already given at " + q.where +
                   "; give one without `planet` (every planet) and at most one per planet");
    const std::string mounting =
        r.StringOr("mounting", "stiffness", {"stiffness", "straddle", "cantilever"});
    if (mounting == "stiffness") {
      p.mounting = PinMounting::kStiffness;
      p.tilting_stiffness = r.Real(
          "tilting_stiffness_Nm_per_rad",
          Rule::Positive().Because("the moment on the pin that tilts the planet by one radian"));
      for (const char* key : {"diameter_mm", "length_mm", "bore_mm", "clamped_side",
                              "youngs_modulus_GPa"})
        if (r.Has(key))
          r.Fail(key, "given with mounting = \"stiffness\"",
                 "a pin's dimensions belong to mounting = \"straddle\" or \"cantilever\"; a given "
                 "tilting stiffness takes none");
    } else {
      p.mounting = mounting == "straddle" ? PinMounting::kStraddle : PinMounting::kCantilever;
      if (r.Has("tilting_stiffness_Nm_per_rad"))
        r.Fail("tilting_stiffness_Nm_per_rad", "given with mounting = \"" + mounting + "\"",
               "the stiffness of a straddle or cantilever pin follows from its dimensions; give "
               "mounting = \"stiffness\" to set it");
      p.diameter = r.Real("diameter_mm", Rule::Positive().Because("the pin's diameter")) * kMm;
      p.bore = r.RealOr("bore_mm", 0,
                        Rule::HalfOpen(0, p.diameter / kMm)
                            .Because("a hollow pin's bore, below its diameter")) *
               kMm;
      p.length =
          r.Real("length_mm",
                 mounting == "straddle"
                     ? Rule{b / kMm, 100 * b / kMm, false, false, ""}.Because(
                           "the span between the carrier's plates, at least the planet's face "
                           "width")
                     : Rule{0.5 * b / kMm, 100 * b / kMm, false, false, ""}.Because(
                           "the distance from the clamping plate to the planet's bearing "
                           "centre, at least half the planet's face width")) *
          kMm;
      p.youngs_modulus =
          r.RealOr("youngs_modulus_GPa", s.material.youngs_modulus / 1e9,
                   Rule::Open(1, 1000).Because("the pin's Young's modulus (steel: 207)")) *
          1e9;
      if (mounting == "cantilever")
        p.clamped_side = r.StringOr("clamped_side", "-z", {"-z", "+z"}) == "+z" ? 1 : -1;
      else if (r.Has("clamped_side"))
        r.Fail("clamped_side", "given with mounting = \"straddle\"",
               "a straddle pin is clamped in both plates");
    }
    r.Done();
    f.pins.push_back(p);
  }
}

}  // namespace epicycle::transmission::internal
