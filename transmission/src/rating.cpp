#include "epicycle/transmission/rating.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>
#include <tuple>

#include <fmt/format.h>

#include "epicycle/geometry/helical.hpp"
#include "epicycle/geometry/iso.hpp"
#include "epicycle/geometry/plane.hpp"

namespace epicycle::transmission {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kStressCorrection = 2.0;  // Y_ST of the reference test gear (ISO 6336-3)
constexpr double kReversedBending = 0.7;   // Y_M of an idler (ISO 6336-5)

std::string Deg(double rad) { return fmt::format("{:.4g} deg", geometry::Deg(rad)); }

// One mesh's ISO 6336-2 data: pinion (fewer teeth; the planet in a ring mesh) and wheel.
struct MeshContact {
  std::string name;
  int pinion = 0, wheel = 0;  // bodies
  double sigma_h0 = 0;        // [Pa]
  double z_b = 1, z_d = 1;
};

const geometry::Gear& GearOfBody(const geometry::Stage& stage, int body) {
  return body == kSunBody ? stage.sun() : body == kRingBody ? stage.ring() : stage.planet(body - 2);
}

// Mesh m's ISO 6336-2 nominal contact stress σ_H0 (without Z_B, Z_D) at the tangential force ft
// [N] with the elasticity factor z_e [√Pa], its factors appended to `factors`. A helical mesh
// takes the transverse section's factors with β_b and ε_β, and Z_β (ISO 6336-2:2006).
MeshContact RateMeshContact(const geometry::Stage& stage, const geometry::MeshSummary& m, double ft,
                            double z_e, std::vector<RatingFactor>* factors) {
  auto factor = [&](std::string symbol, double value, std::string source) {
    factors->push_back({std::move(symbol), value, std::move(source)});
  };
  const bool helical = stage.sun().spec().helix.helical();
  const bool internal = m.kind == geometry::MeshKind::kPlanetRing;
  const int a = internal ? PlanetBody(0) : kSunBody, b = internal ? kRingBody : PlanetBody(0);
  const bool a_pinion = internal || GearOfBody(stage, a).teeth() <= GearOfBody(stage, b).teeth();
  MeshContact c;
  c.name = m.name;
  c.pinion = a_pinion ? a : b;
  c.wheel = a_pinion ? b : a;
  const geometry::Gear& g1 = GearOfBody(stage, c.pinion);
  const geometry::Gear& g2 = GearOfBody(stage, c.wheel);
  const geometry::HelicalMesh hm = geometry::SummariseHelicalMesh(m, g1, g2);
  const auto f = helical ? geometry::iso::HelicalContactFactorsB(
                               g1.teeth(), g1.spec().pressure_angle, m.pressure_angle,
                               m.centre_distance, g1.base_radius(), g1.tip_radius(),
                               g2.base_radius(), g2.tip_radius(), m.contact_ratio_iso, internal,
                               hm.helix_angle, hm.base_helix_angle, hm.overlap_ratio)
                         : geometry::iso::ContactFactorsB(
                               g1.teeth(), g1.spec().pressure_angle, m.pressure_angle,
                               m.centre_distance, g1.base_radius(), g1.tip_radius(),
                               g2.base_radius(), g2.tip_radius(), m.contact_ratio_iso, internal);
  const double u = (internal ? -1.0 : 1.0) * g2.teeth() / g1.teeth();
  const double b_width = geometry::ContactFaceWidth(g1, g2);
  c.sigma_h0 =
      f.z_h * z_e * f.z_eps * std::sqrt(ft / (2 * g1.reference_radius() * b_width) * (u + 1) / u);
  if (helical) c.sigma_h0 *= f.z_beta;
  c.z_b = f.z_b;
  c.z_d = f.z_d;
  const std::string mesh = internal ? "ring mesh" : "sun mesh";
  auto role = [](int body) { return body >= PlanetBody(0) ? "planet" : BodyName(body); };
  const std::string at = fmt::format("ISO 6336-2, the {}: alpha_w = {}, eps_alpha = {:.4f}", mesh,
                                     Deg(m.pressure_angle), m.contact_ratio_iso);
  factor("Z_H " + mesh, f.z_h, at);
  factor("Z_eps " + mesh, f.z_eps, at);
  factor("Z_B " + mesh, f.z_b,
         fmt::format("{} (pinion {}): M_1 = {:.4f}", at, role(c.pinion), f.m1));
  factor("Z_D " + mesh, f.z_d,
         internal ? at + " (internal wheel: 1)"
                  : fmt::format("{} (wheel {}): M_2 = {:.4f}", at, role(c.wheel), f.m2));
  factor("u " + mesh, u, "z_wheel/z_pinion (negative: internal)");
  if (helical) {
    factor("Z_beta " + mesh, f.z_beta,
           fmt::format("ISO 6336-2: 1/sqrt(cos beta), beta = {}", Deg(hm.helix_angle)));
    factor("eps_beta " + mesh, hm.overlap_ratio,
           fmt::format("b sin beta/(pi m_n), b = {:.4g} mm", hm.face_width * 1e3));
  }
  return c;
}

}  // namespace

// ISO 6336-1:2006 clause 7.5 (method C), equation numbers of that edition; docs/model.md §10
// "Ratings across the face" gives the source of each and what is unconfirmed.
FaceLoadFactorC IsoFaceLoadFactorC(const FaceLoadFactorInputs& in) {
  for (const auto& [name, value, positive] : {std::tuple{"f_ma [m]", in.assembly, false},
                                              {"f_sh [m]", in.deflection, false},
                                              {"f_Hbeta [m]", in.lead_slope, false},
                                              {"c_gamma_alpha [N/m^2]", in.mesh_stiffness, true},
                                              {"b [m]", in.face_width, true},
                                              {"F_m [N]", in.mean_force, true},
                                              {"h [m]", in.tooth_depth, true},
                                              {"B1", in.b1, true},
                                              {"B2", in.b2, true}})
    if (!std::isfinite(value) || value < 0 || (positive && value == 0))
      throw std::invalid_argument(fmt::format("ISO 6336-1 method C: {} = {}: must be finite and {}",
                                              name, value, positive ? "> 0" : ">= 0"));
  for (const auto& [name, value] : {std::pair{"B1", in.b1}, {"B2", in.b2}})
    if (value > 1)
      throw std::invalid_argument(
          fmt::format("ISO 6336-1 method C: {} = {}: must be in (0, 1]", name, value));
  constexpr double kUm = 1e-6;
  FaceLoadFactorC c;
  const double line_load = in.mean_force / in.face_width;  // F_m/b [N/m]
  // F_βx,min (eqs. 55, 56): the larger of 0.005 µm per N/mm of F_m/b and 0.5 f_Hβ.
  c.f_beta_x_min = std::max(0.005 * kUm * (line_load * 1e-3), 0.5 * in.lead_slope);
  const double f_beta_x = 1.33 * in.b1 * in.deflection + in.b2 * in.assembly;  // eq. 52
  c.at_minimum = c.f_beta_x_min > f_beta_x;
  c.f_beta_x = std::max(f_beta_x, c.f_beta_x_min);
  c.y_beta = std::min(0.15 * c.f_beta_x, 6 * kUm);  // eq. 48: surface-hardened steel
  c.f_beta_y = c.f_beta_x - c.y_beta;               // eq. 43
  c.c_gamma_beta = 0.85 * in.mesh_stiffness;
  const double x = c.f_beta_y * c.c_gamma_beta * in.face_width / (2 * in.mean_force);
  c.lifted = x > 1;
  c.k_h_beta = c.lifted ? 2 * std::sqrt(x) : 1 + x;  // eqs. 39 and 41
  const double bh = std::max(3.0, in.face_width / in.tooth_depth);
  c.n_f = bh * bh / (1 + bh + bh * bh);  // eqs. 69, 70
  c.k_f_beta = std::pow(c.k_h_beta, c.n_f);
  return c;
}

std::array<double, 2> MethodCModification(double crowning, bool end_relieved, double assembly,
                                          double deflection) {
  for (const auto& [name, value] :
       {std::pair{"C_beta [m]", crowning}, {"f_ma [m]", assembly}, {"f_sh [m]", deflection}})
    if (!(std::isfinite(value) && value >= 0))
      throw std::invalid_argument(
          fmt::format("ISO 6336-1 method C's helix modification: {} = {}: must be finite and >= 0",
                      name, value));
  // Table 8's rows (docs/model.md §10, "Ratings across the face").
  if (crowning > 0) {
    // The two crowning rows presuppose a crowning sized to what it compensates.
    if (crowning >= 0.5 * (assembly + deflection)) return {0.5, 0.5};
    return {1.0, 0.5};
  }
  if (end_relieved) return {0.7, 0.7};
  return {1.0, 1.0};
}

double TableMeshLoadFactor(int planets) {
  if (planets < 1)
    throw std::invalid_argument(
        fmt::format("TableMeshLoadFactor: planets = {}: must be >= 1", planets));
  return planets <= 3 ? 1.0 : planets == 4 ? 1.2 : planets == 5 ? 1.3 : 1.4;
}

RatingInputs RatingInputsOf(const Scene& scene) {
  RatingInputs in;
  in.source = scene.source;
  in.bending_limit = scene.material.bending_limit;
  in.contact_limit = scene.material.contact_limit;
  in.youngs_modulus = scene.material.youngs_modulus;
  in.poisson_ratio = scene.material.poisson_ratio;
  in.application_factor = scene.rating.application_factor;
  in.sun_torque = scene.loads.sun_torque;
  in.leads = scene.face_width.leads;
  auto refuse = [&](const char* key, double value, const char* rule) {
    throw std::invalid_argument(fmt::format("{}: {} = {}: must be {} (the ratings' input)",
                                            scene.source, key, value, rule));
  };
  if (!(std::isfinite(in.youngs_modulus) && in.youngs_modulus > 0))
    refuse("[material] youngs_modulus_GPa", in.youngs_modulus / 1e9, "finite and > 0");
  if (!(in.poisson_ratio >= 0 && in.poisson_ratio < 0.5))
    refuse("[material] poisson_ratio", in.poisson_ratio, "in [0, 0.5)");
  if (!(in.application_factor >= 1 && in.application_factor <= 4))
    refuse("[rating] application_factor", in.application_factor, "in [1, 4]");
  if (!std::isfinite(in.sun_torque)) refuse("[load] sun_torque_Nm", in.sun_torque, "finite");
  for (const auto& [key, value] : {std::pair{"[material] bending_limit_MPa", in.bending_limit},
                                   {"[material] contact_limit_MPa", in.contact_limit}})
    if (!(std::isfinite(value) && value >= 0))
      refuse(key, value / 1e6, "finite and >= 0 (0: not given)");
  return in;
}

void CheckRatingInputs(const RatingInputs& inputs, const std::string& asked_by) {
  for (const auto& [key, symbol, value] :
       {std::tuple{"bending_limit_MPa", "sigma_Flim", inputs.bending_limit},
        {"contact_limit_MPa", "sigma_Hlim", inputs.contact_limit}})
    if (!(value > 0))
      throw std::invalid_argument(
          fmt::format("{} needs the scene's [material] {} (ISO 6336-5's {}): {} does not give it",
                      asked_by, key, symbol, inputs.source));
}

namespace {

// ISO 6336-1 clause 7.5, method C, per planet mesh, fed the model's misalignment and c_γ
// (mesh_stiffness per unit face width [N/m²], sun and ring mesh), beside the model's K_Hβ and its
// own stresses per slice.
void RateFaceWidth(const RatingInputs& inputs, const geometry::Stage& stage,
                   const SweepSummary& summary, const std::array<double, 2>& mesh_stiffness,
                   double ft, double k_table, const std::vector<double>& k_model, double ka_kv,
                   StageRating* out) {
  auto factor = [&](std::string symbol, double value, std::string source) {
    out->factors.push_back({std::move(symbol), value, std::move(source)});
  };
  const geometry::Gear& sun = stage.sun();
  const double km = k_table * ka_kv;  // F_m = F_t K_A K_γ K_v
  factor("F_m", ft * km, "ISO 6336-1 method C: F_t K_A K_gamma(table) K_v [N]");
  factor("y_beta", 0.15,
         "ISO 6336-1 method C running-in: 0.15 F_betax, at most 6 um (case-hardened steel)");
  factor("c_gamma_beta / c_gamma_alpha", 0.85, "ISO 6336-1 method C");
  for (std::size_t k = 0; k < 2; ++k)
    factor(std::string("c_gamma_alpha ") + (k == 0 ? "sun mesh" : "ring mesh") + " [N/(mm um)]",
           mesh_stiffness[k] / 1e9,
           "the model's mean mesh stiffness per unit face width (planet 1's mesh at the "
           "scene's load)");
  auto depth = [&](const geometry::Gear& g) { return std::abs(g.tip_radius() - g.root_radius()); };
  for (const MeshFaceSummary& f : summary.face_width) {
    const std::size_t k = f.ring_mesh ? 1 : 0;
    const geometry::Gear& mate = f.ring_mesh ? stage.ring() : sun;
    const geometry::Gear& planet = stage.planet(f.planet);
    MeshFaceRating r;
    r.mesh = f.mesh;
    r.k_gamma_table = k_table;
    r.k_gamma_model = k_model[static_cast<std::size_t>(f.planet)];
    r.k_h_beta_model = f.k_h_beta_max;
    r.iso_inputs.assembly = std::abs(f.misalignment_assembly);
    r.iso_inputs.deflection = std::abs(f.misalignment_deflection);
    r.iso_inputs.mesh_stiffness = mesh_stiffness[k];
    r.iso_inputs.face_width = geometry::ContactFaceWidth(planet, mate);
    r.iso_inputs.mean_force = ft * km;
    // b/h: the smaller of the two gears' (ISO 6336-1), so the deeper tooth.
    r.iso_inputs.tooth_depth = std::max(depth(planet), depth(mate));
    // B1, B2 and f_Hβ from the leads of the mesh's two gears (the scene's [[face_width.lead]]).
    const std::string names[2] = {BodyName(PlanetBody(f.planet)),
                                  BodyName(f.ring_mesh ? kRingBody : kSunBody)};
    double crowning = 0;
    bool end_relieved = false;
    for (const LeadSpec& l : inputs.leads)
      if (l.gear == names[0] || l.gear == names[1]) {
        crowning += l.crowning;
        end_relieved = end_relieved || l.end_relief > 0;
        r.iso_inputs.lead_slope = std::max(r.iso_inputs.lead_slope, std::abs(l.slope));
      }
    const std::array<double, 2> b =
        MethodCModification(crowning, end_relieved, r.iso_inputs.assembly, r.iso_inputs.deflection);
    r.iso_inputs.b1 = b[0];
    r.iso_inputs.b2 = b[1];
    const std::string why =
        crowning > 0 ? fmt::format(
                           "ISO 6336-1 method C, table 8: crowning C_beta = {:.4g} um of "
                           "the mesh's gears {} 0.5 (f_ma + f_sh)",
                           crowning * 1e6, b[0] == b[1] ? ">=" : "<")
                     : "ISO 6336-1 method C, table 8: end relief of the mesh's gears";
    if (b[0] != b[1]) {
      factor("B1 " + f.mesh, b[0], why);
      factor("B2 " + f.mesh, b[1], why);
    } else if (b[0] != 1) {
      factor("B1 = B2 " + f.mesh, b[0], why);
    }
    r.iso = IsoFaceLoadFactorC(r.iso_inputs);
    // Listed where the lead slope sets F_βx (a slope the misalignment hardly shows).
    if (r.iso.at_minimum && r.iso.f_beta_x_min == 0.5 * r.iso_inputs.lead_slope)
      factor("F_betax,min " + f.mesh + " [um]", r.iso.f_beta_x_min * 1e6,
             fmt::format("ISO 6336-1 method C eq. 56: 0.5 f_Hbeta (f_Hbeta = {:.4g} um of the "
                         "mesh's gears) exceeds 1.33 B1 f_sh + B2 f_ma = {:.4g} um",
                         r.iso_inputs.lead_slope * 1e6,
                         (1.33 * r.iso_inputs.b1 * r.iso_inputs.deflection +
                          r.iso_inputs.b2 * r.iso_inputs.assembly) *
                             1e6));
    r.k_gamma_k_h_beta_model = f.k_gamma_k_h_beta_max;
    r.k_gamma_k_h_beta_iso = k_table * r.iso.k_h_beta;
    r.root_stress = r.s_f_stress = r.hertz_pressure = r.s_h_pressure = kNaN;
    if (f.stresses && f.root_stress_max > 0) {
      const bool is_planet = f.root_stress_gear.rfind("planet", 0) == 0;
      r.root_stress_gear = f.root_stress_gear;
      r.root_stress = f.root_stress_max;
      r.s_f_stress = inputs.bending_limit * kStressCorrection *
                     (is_planet ? kReversedBending : 1.0) / (r.root_stress * ka_kv);
    }
    if (f.stresses && f.hertz_pressure_max > 0) {
      r.hertz_pressure = f.hertz_pressure_max;
      r.s_h_pressure = inputs.contact_limit / (r.hertz_pressure * std::sqrt(ka_kv));
    }
    out->face_width.push_back(r);
  }
}

}  // namespace

StageRating RateStage(const RatingInputs& inputs, const geometry::Stage& stage,
                      const SweepSummary& summary, double dynamic_factor,
                      const std::string& dynamic_source, const MotionStresses* motion,
                      const std::array<double, 2>* mesh_stiffness) {
  CheckRatingInputs(inputs, "a rating");
  if (!(dynamic_factor >= 1 && std::isfinite(dynamic_factor)))
    throw std::invalid_argument(
        fmt::format("RateStage: K_v = {}: must be finite and >= 1", dynamic_factor));
  if (!(summary.converged > 0))
    throw std::runtime_error("rating: K_gamma from the run needs a converged position, none is");

  const int n = stage.planets();
  StageRating out;
  out.application_factor = inputs.application_factor;
  out.dynamic_factor = dynamic_factor;
  out.dynamic_source = dynamic_source;
  const geometry::Gear& sun = stage.sun();
  const bool helical = sun.spec().helix.helical();
  const double torque = std::abs(inputs.sun_torque);
  out.tangential_force = torque / (n * sun.reference_radius());
  const double ft = out.tangential_force;
  auto factor = [&](std::string symbol, double value, std::string source) {
    out.factors.push_back({std::move(symbol), value, std::move(source)});
  };
  factor("K_A", out.application_factor,
         "the scene's [rating] application_factor (default 1: uniform load)");
  factor("K_v", dynamic_factor, dynamic_source);
  if (motion != nullptr)
    factor("model's own stresses", 1.0,
           motion->source + ": root stresses and pressures in motion, taken without K_v");
  const bool faces = !summary.face_width.empty();
  factor("K_Hbeta = K_Fbeta", 1.0,
         faces ? "in the gears' ISO columns; the meshes' face-width ratings take the run's K_Hbeta "
                 "and ISO 6336-1 method C's"
               : "plane model: the load is uniform over the face width");
  factor("K_Halpha = K_Falpha", 1.0,
         "nominal case; the model resolves the sharing between tooth pairs in its own columns");
  const double k_table = TableMeshLoadFactor(n);
  factor("K_gamma table", k_table,
         fmt::format("application-level table for {} planets (AGMA 6123 / ISO 6336)", n));
  std::vector<double> k_model(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) {
    k_model[i] = n * summary.lsr_max[i];
    factor(fmt::format("K_gamma planet{}", i + 1), k_model[i],
           fmt::format("the run: max over {} positions of L_{} = n LSR_{}", summary.converged,
                       i + 1, i + 1));
  }
  const double z_e = geometry::iso::ElasticityFactor(inputs.youngs_modulus, inputs.poisson_ratio,
                                                     inputs.youngs_modulus, inputs.poisson_ratio);
  factor("Z_E [sqrt(MPa)]", z_e / 1e3, "ISO 6336-2, the scene's E and nu on both gears");
  factor("Y_ST", kStressCorrection, "ISO 6336-3: the reference test gear's stress correction");
  factor("Y_M planet", kReversedBending,
         "ISO 6336-5: an idler's teeth bend both ways (fully reversed bending)");
  factor("life, lubricant, roughness, size factors", 1.0,
         "endurance beyond 5e7 cycles, reference test-gear conditions");

  // ISO 6336-2 per mesh (the planets' meshes are alike: planet 1's geometry).
  std::vector<MeshContact> meshes;
  for (const geometry::MeshSummary& m : {stage.meshes()[0], stage.meshes()[1]})
    meshes.push_back(RateMeshContact(stage, m, ft, z_e, &out.factors));
  auto gear_of = [&](int body) -> const geometry::Gear& { return GearOfBody(stage, body); };

  // ISO 6336-3 σ_F0 of a gear in a mesh, once per member and mesh (the planets are alike); NaN
  // (with the reason) where method B does not apply.
  std::map<std::pair<int, int>, std::pair<double, std::string>> sigma_f0;
  auto bending = [&](int body, std::size_t mesh) {
    const int role = body == kSunBody ? 0 : body == kRingBody ? 2 : 1;
    const auto key = std::pair{role, static_cast<int>(mesh)};
    if (const auto it = sigma_f0.find(key); it != sigma_f0.end()) return it->second;
    const geometry::MeshSummary& m = stage.meshes()[mesh];
    const geometry::Gear& g = gear_of(role == 1 ? PlanetBody(0) : body);
    const geometry::GearSpec& s = g.spec();
    if (g.internal() || !s.rack)
      return sigma_f0[key] = {kNaN,
                              "ISO 6336-3 bending not rated: method B's form factors here are "
                              "those of an external gear cut by a rack; the model's root stress "
                              "rates it"};
    const geometry::Gear& mate = role == 0                                  ? stage.planet(0)
                                 : m.kind == geometry::MeshKind::kSunPlanet ? stage.sun()
                                                                            : stage.ring();
    // A helical gear: its virtual spur gear in the normal section (ISO 6336-3:2006), and Y_β.
    const double beta = s.helix.angle, c_beta = std::cos(beta);
    const geometry::HelicalMesh hm = geometry::SummariseHelicalMesh(m, g, mate);
    const auto y =
        helical ? geometry::iso::HelicalRootFormFactorsB(
                      g.teeth(), geometry::NormalModule(g),
                      std::atan(std::tan(s.pressure_angle) * c_beta), s.profile_shift / c_beta,
                      beta, hm.base_helix_angle, s.rack->addendum, s.rack->tip_radius,
                      2 * g.tip_radius(), m.contact_ratio_iso)
                : geometry::iso::RootFormFactorsB(
                      g.teeth(), s.module, s.pressure_angle, s.profile_shift, s.rack->addendum,
                      s.rack->tip_radius, 2 * g.tip_radius(), m.contact_ratio_iso);
    const geometry::iso::HelicalBendingFactors hb =
        helical ? geometry::iso::HelicalBending(g.teeth(), beta, hm.base_helix_angle,
                                                m.contact_ratio_iso, hm.overlap_ratio)
                : geometry::iso::HelicalBendingFactors{};
    const double y_beta = hb.y_beta;
    const std::string who = role == 0 ? "sun" : "planets",
                      mesh_name =
                          m.kind == geometry::MeshKind::kSunPlanet ? "sun mesh" : "ring mesh";
    const std::string at = fmt::format(
        "ISO 6336-3 method B, {} in the {}: s_Fn = {:.3f} mm, rho_F = {:.3f} mm, h_Fe = {:.3f} "
        "mm, alpha_Fen = {}",
        who, mesh_name, y.s_fn * 1e3, y.rho_f * 1e3, y.h_fe * 1e3, Deg(y.alpha_fen));
    factor("Y_F " + who + " " + mesh_name, y.y_f, at);
    factor("Y_S " + who + " " + mesh_name, y.y_s, at);
    if (!helical)
      return sigma_f0[key] = {ft / (geometry::ContactFaceWidth(g, mate) * s.module) * y.y_f * y.y_s,
                              std::string()};
    factor(
        "Y_beta " + who + " " + mesh_name, y_beta,
        fmt::format("ISO 6336-3: 1 - eps_beta beta/120 deg, eps_beta = {:.4f}", hm.overlap_ratio));
    factor("Y_eps " + who + " " + mesh_name, hb.y_eps,
           fmt::format("ISO 6336-3:1996 0.25 + 0.75/eps_alpha_n, eps_alpha_n = eps_alpha/cos^2 "
                       "beta_b = {:.4f}, z_n = {:.3f}: reported, not applied (method B of 2006 "
                       "loads the virtual gear's outer point of single pair contact)",
                       hb.virtual_contact_ratio, hb.virtual_teeth));
    return sigma_f0[key] = {ft / (geometry::ContactFaceWidth(g, mate) * geometry::NormalModule(g)) *
                                y.y_f * y.y_s * y_beta,
                            std::string()};
  };

  // The name of mesh k (0: sun mesh, 1: ring mesh) as `body` sees it: a planet's own meshes.
  auto MeshName = [&](int body, std::size_t k) {
    return body >= PlanetBody(0) ? geometry::MeshName(body - 2, stage.meshes()[k].kind)
                                 : stage.meshes()[k].name;
  };
  const double ka_kv = out.application_factor * dynamic_factor;
  auto rate = [&](int body, const std::vector<std::size_t>& in_meshes, double k_model_gear) {
    GearRating r;
    r.body = body;
    r.gear = BodyName(body);
    r.k_gamma_table = k_table;
    r.k_gamma_model = k_model_gear;
    r.reversed_bending = body >= PlanetBody(0) ? kReversedBending : 1.0;
    r.sigma_f0 = kNaN;
    for (std::size_t k : in_meshes) {
      const auto [s0, note] = bending(body, k);
      if (!note.empty()) r.note = note;
      if (!std::isnan(s0) && !(s0 <= r.sigma_f0)) {
        r.sigma_f0 = s0;
        r.bending_mesh = MeshName(body, k);
      }
      const MeshContact& c = meshes[k];
      // Planet 1 stands for every planet in the mesh data.
      const bool pinion = body == c.pinion || (body >= PlanetBody(0) && c.pinion >= PlanetBody(0));
      const double zbd = pinion ? c.z_b : c.z_d;
      if (!(zbd * c.sigma_h0 <= r.z_bd * r.sigma_h0)) {
        r.sigma_h0 = c.sigma_h0;
        r.z_bd = zbd;
        r.contact_mesh = MeshName(body, k);
      }
    }
    const double flim = inputs.bending_limit * kStressCorrection * r.reversed_bending;
    const double hlim = inputs.contact_limit;
    r.sigma_f_table = r.sigma_f0 * ka_kv * k_table;
    r.sigma_f_model = r.sigma_f0 * ka_kv * k_model_gear;
    r.s_f_table = flim / r.sigma_f_table;
    r.s_f_model = flim / r.sigma_f_model;
    r.sigma_h_table = r.z_bd * r.sigma_h0 * std::sqrt(ka_kv * k_table);
    r.sigma_h_model = r.z_bd * r.sigma_h0 * std::sqrt(ka_kv * k_model_gear);
    r.s_h_table = hlim / r.sigma_h_table;
    r.s_h_model = hlim / r.sigma_h_model;
    r.root_stress = r.contact_pressure = r.s_f_stress = r.s_h_pressure = kNaN;
    // The model's own: the run's stresses, times K_v unless they are the stresses in motion.
    const auto& root = motion != nullptr ? motion->root_stress : summary.root_stress;
    const auto& pressure = motion != nullptr ? motion->contact_pressure : summary.contact_pressure;
    const double own = motion != nullptr ? out.application_factor : ka_kv;
    for (const RootStressSummary& s : root)
      if (s.extremes.body == body && s.extremes.tension > 0) {
        r.root_stress = s.extremes.tension;
        r.s_f_stress = flim / (r.root_stress * own);
      }
    for (const FlankPressure& p : pressure)
      if (p.body == body && p.drive && !p.tip && p.pressure > 0) {
        r.contact_pressure = p.pressure;
        r.s_h_pressure = hlim / (p.pressure * std::sqrt(own));
      }
    if (root.empty())
      r.note += std::string(r.note.empty() ? "" : "; ") +
                "the model's own columns need the run's stresses ([model] stresses)";
    return r;
  };
  if (faces && mesh_stiffness != nullptr)
    RateFaceWidth(inputs, stage, summary, *mesh_stiffness, ft, k_table, k_model, ka_kv, &out);
  const double k_all = *std::max_element(k_model.begin(), k_model.end());
  out.gears.push_back(rate(kSunBody, {0}, k_all));
  for (int i = 0; i < n; ++i) out.gears.push_back(rate(PlanetBody(i), {0, 1}, k_model[i]));
  out.gears.push_back(rate(kRingBody, {1}, k_all));
  return out;
}

}  // namespace epicycle::transmission
