// The 3D reference's reading and its run (fe3d.hpp): the layers' contact forces at the scene's
// torque as a line load across the face, and the ccx run that produces them.
#include <sys/resource.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <stdexcept>

#include "epicycle/io/number_format.hpp"
#include "fe3d.hpp"

namespace epicycle::fe_reference {

namespace {

// CPU seconds (user + system) of the waited-for children so far.
double ChildrenCpuSeconds() {
  rusage u{};
  getrusage(RUSAGE_CHILDREN, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
         1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

// ccx on `directory`/deck.inp (its log in ccx.log).
void RunCcx(const std::string& directory, const std::string& ccx, int threads) {
  std::filesystem::remove(directory + "/deck.dat");
  const std::string command = "cd '" + directory + "' && OMP_NUM_THREADS=" +
                              std::to_string(threads) + " nice -n 10 '" + ccx +
                              "' -i deck > ccx.log 2>&1";
  if (std::system(command.c_str()) != 0)
    throw std::runtime_error("fe3d: ccx failed (see " + directory + "/ccx.log)");
}

// The axial reaction R_z [N] of the node set `set` at the end of every step (ccx's "total force
// (fx,fy,fz) for set <set> and time t" blocks of *NODE PRINT, TOTALS=ONLY); empty when the deck
// prints none.
std::vector<double> ReadAxialTotals(const std::string& path, const std::string& set) {
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read (did ccx run?)");
  const std::string header = "total force (fx,fy,fz) for set " + set + " and time";
  std::map<long, double> by_step;  // step (the integral total time) → R_z
  for (std::string line; std::getline(f, line);) {
    const std::size_t at = line.find(header);
    if (at == std::string::npos) continue;
    const double time = std::stod(line.substr(at + header.size()));
    std::string values;
    while (std::getline(f, values) && values.find_first_not_of(' ') == std::string::npos) {
    }
    std::istringstream v(values);
    double fx = 0, fy = 0, fz = 0;
    if (!(v >> fx >> fy >> fz) || !std::isfinite(fz))
      throw std::runtime_error(path + ": cannot read the total force of set " + set + " at time " +
                               line.substr(at + header.size()));
    if (std::abs(time - std::round(time)) < 1e-9) by_step[std::lround(time)] = fz;
  }
  std::vector<double> out;
  for (const auto& [step, fz] : by_step) out.push_back(fz);
  return out;
}

}  // namespace

Fe3dLineLoad ReadLineLoad(const std::string& directory, const Fe3dDeckInfo& info) {
  std::vector<FeStepResult> steps = ReadSteps(directory, info.deck);
  for (FeStepResult& step : steps)
    for (double& force : step.pair_force) force *= info.transverse_factor;  // fe3d.hpp
  const FeSample s = Interpolate(info.deck, steps);
  const std::size_t layers = info.z_edges.size() - 1;
  Fe3dLineLoad r;
  r.angle = info.deck.angle;
  r.face_width = info.z_edges.back() - info.z_edges.front();
  r.misalignment = info.misalignment;
  std::vector<double> force(layers, 0.0);
  for (std::size_t j = 0; j < s.pair_force.size(); ++j) {
    const int l = info.pair_layer[j];
    if (l < 0 || static_cast<std::size_t>(l) >= layers)
      throw std::runtime_error(directory + "/deck3d.info: pair layer " + std::to_string(l) +
                               " outside [0, " + std::to_string(layers) + ")");
    force[static_cast<std::size_t>(l)] += s.pair_force[j];
  }
  for (std::size_t l = 0; l < layers; ++l) {
    const double lo = info.z_edges[l], hi = info.z_edges[l + 1];
    r.z_lo.push_back(lo);
    r.z_hi.push_back(hi);
    r.z.push_back(0.5 * (lo + hi));
    r.line_load.push_back(force[l] / (hi - lo));
    r.total_force += force[l];
  }
  r.rotation = s.rotation;
  r.approach = s.approach;
  const double mean = r.total_force / r.face_width;
  const auto peak = std::max_element(r.line_load.begin(), r.line_load.end());
  r.k_hbeta = *peak / mean;
  r.peak_z = r.z[static_cast<std::size_t>(peak - r.line_load.begin())];
  r.stiffness_per_width = mean / r.approach;
  // q at b/2 between the station centres around it (one station: its own value).
  const double middle = 0.5 * (info.z_edges.front() + info.z_edges.back());
  double q_mid = r.line_load.front();
  for (std::size_t l = 0; l + 1 < layers; ++l) {
    if (r.z[l] <= middle && middle <= r.z[l + 1]) {
      const double u = (middle - r.z[l]) / (r.z[l + 1] - r.z[l]);
      q_mid = (1 - u) * r.line_load[l] + u * r.line_load[l + 1];
    }
  }
  r.middle_stiffness_per_width = q_mid / r.approach;
  r.moment_balance = s.moment_balance;
  r.extrapolated = s.extrapolated;
  r.nodes = info.deck.nodes;
  r.elements = info.deck.elements;
  for (int g = 0; g < 2; ++g) {
    const std::vector<double> fz =
        ReadAxialTotals(directory + "/deck.dat", "AXIAL" + std::to_string(g + 1));
    if (fz.empty()) continue;
    if (fz.size() != steps.size())
      throw std::runtime_error(directory + "/deck.dat: " + std::to_string(fz.size()) +
                               " axial totals of set AXIAL" + std::to_string(g + 1) + " for " +
                               std::to_string(steps.size()) + " steps");
    r.axial_reaction[g] = (1 - s.weight) * fz[s.step] + s.weight * fz[s.step + 1];
  }
  for (double q : r.line_load)
    if (!std::isfinite(q))
      throw std::runtime_error(directory + ": a station's line load is not finite");
  return r;
}

std::vector<std::vector<double>> ReadInfluence(const std::string& directory,
                                               const Fe3dDeckInfo& info) {
  const std::string path = directory + "/deck.dat";
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read (did ccx run?)");
  const std::size_t layers = info.z_edges.size() - 1;
  if (info.read_points.size() != 2 || !(info.influence_force > 0))
    throw std::runtime_error(directory + "/deck3d.info: not an influence deck");
  // Per step (time 1, 2, ...: ccx's static steps have period 1): node id → (u_x, u_y) [mm].
  std::vector<std::map<int, std::array<double, 2>>> steps;
  const std::string header = "displacements (vx,vy,vz) for set READ and time";
  std::string line;
  int step = -1;
  while (std::getline(f, line)) {
    if (line.find(header) != std::string::npos) {
      const double time = std::stod(line.substr(line.rfind("time") + 4));
      step = static_cast<int>(std::lround(time)) - 1;
      if (std::abs(time - std::round(time)) > 1e-9 || step < 0)
        throw std::runtime_error(path + ": a displacement block at time " + line.substr(
                                     line.rfind("time") + 4) + ", not at a step's end");
      if (steps.size() <= static_cast<std::size_t>(step)) steps.resize(step + 1);
      continue;
    }
    std::istringstream s(line);
    int id = 0;
    double ux = 0, uy = 0;
    if (step >= 0 && (s >> id >> ux >> uy)) steps[static_cast<std::size_t>(step)][id] = {ux, uy};
  }
  if (steps.size() != layers)
    throw std::runtime_error(path + ": " + std::to_string(steps.size()) + " of " +
                             std::to_string(layers) + " steps completed (see ccx's log)");
  const double nx = info.normal_x, ny = info.normal_y;
  std::vector<std::vector<double>> g(layers, std::vector<double>(layers, 0.0));
  for (std::size_t j = 0; j < layers; ++j) {
    const auto& u = steps[j];
    auto normal_at = [&](int id) {
      const auto it = u.find(id);
      if (it == u.end())
        throw std::runtime_error(path + ": step " + std::to_string(j + 1) + " lacks node " +
                                 std::to_string(id));
      return it->second[0] * nx + it->second[1] * ny;
    };
    for (std::size_t i = 0; i < layers; ++i) {
      // The station's mean along z at each triangle node: Simpson over the corner nodes'
      // quadratic edge, the mean of the ends at a mid-side node (linear along z in a C3D15).
      double approach = 0;
      for (const Fe3dReadPoint& r : info.read_points) {
        double u_n = 0;
        for (std::size_t k = 0; k < r.weight.size(); ++k) {
          const std::vector<int>& ids = r.levels[k];
          const double lo = normal_at(ids[2 * i]), hi = normal_at(ids[2 * i + 2]);
          const double mean =
              r.corner[k] ? (lo + 4 * normal_at(ids[2 * i + 1]) + hi) / 6 : 0.5 * (lo + hi);
          u_n += r.weight[k] * mean;
        }
        approach += r.gear == 2 ? u_n : -u_n;  // separation along n: gear 2's minus gear 1's
      }
      g[i][j] = approach * 1e-3 / info.influence_force;  // mm/N → m/N
    }
  }
  return g;
}

double SliceApproach(double force, double face_width, double stiffness_per_width,
                     double misalignment) {
  if (!(force > 0) || !(face_width > 0) || !(stiffness_per_width > 0) ||
      !std::isfinite(misalignment))
    throw std::invalid_argument("fe3d: SliceApproach(force " + io::Num(force, 13) + " N, b " +
                                io::Num(face_width, 13) + " m, c' " +
                                io::Num(stiffness_per_width, 13) + " N/m^2, F_beta " +
                                io::Num(misalignment, 13) + " m): needs F, b, c' > 0");
  const double f = std::abs(misalignment);
  const double uniform = force / (stiffness_per_width * face_width);
  // Whole face loaded while δ ≥ F_β/2; else (δ + F_β/2)² b c′/(2 F_β) = F.
  if (uniform >= 0.5 * f) return uniform;
  return std::sqrt(2 * force * f / (stiffness_per_width * face_width)) - 0.5 * f;
}

Fe3dRun RunFe3d(const transmission::Scene& scene, const geometry::GearPair& pair, double torque,
                double angle, double stiffness_per_width, const Fe3dOptions& options,
                const std::string& directory, const std::string& ccx, int threads,
                const std::vector<double>& step_scales) {
  options.Validate();
  if (threads < 1)
    throw std::invalid_argument("fe3d: threads = " + std::to_string(threads) + ": must be >= 1");
  if (step_scales.size() < 2)
    throw std::invalid_argument("fe3d: step_scales: two or more steps bracket the torque");
  const double rb1 = pair.gear1().base_radius();
  const double b = options.face_width > 0 ? options.face_width
                                          : geometry::ContactFaceWidth(pair.gear1(), pair.gear2());
  const double sign = torque > 0 ? 1.0 : -1.0;
  double theta =
      sign * SliceApproach(std::abs(torque) / rb1, b, stiffness_per_width, options.misalignment) /
      rb1;
  Fe3dRun run;
  const auto start = std::chrono::steady_clock::now();
  const double cpu0 = ChildrenCpuSeconds();
  for (run.runs = 1;; ++run.runs) {
    std::vector<double> rotations;
    for (double s : step_scales) rotations.push_back(s * theta);
    run.deck = WriteDeck3d(scene, pair, torque, angle, rotations, options, directory);
    RunCcx(directory, ccx, threads);
    run.result = ReadLineLoad(directory, run.deck);
    if (!run.result.extrapolated || run.runs == 2) break;
    theta = run.result.rotation;  // the first run's extrapolation: the steps around it
  }
  run.cpu_seconds = ChildrenCpuSeconds() - cpu0;
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return run;
}

Fe3dInfluenceRun RunFe3dInfluence(const transmission::Scene& scene,
                                  const geometry::GearPair& pair, double angle,
                                  const Fe3dOptions& options, const std::string& directory,
                                  const std::string& ccx, int threads) {
  if (!options.influence)
    throw std::invalid_argument("fe3d: RunFe3dInfluence needs options.influence");
  if (threads < 1)
    throw std::invalid_argument("fe3d: threads = " + std::to_string(threads) + ": must be >= 1");
  Fe3dInfluenceRun run;
  const auto start = std::chrono::steady_clock::now();
  const double cpu0 = ChildrenCpuSeconds();
  // The deck's torque and rotations are the contact deck's bookkeeping, unused here.
  run.deck = WriteDeck3d(scene, pair, 1.0, angle, {1e-4}, options, directory);
  RunCcx(directory, ccx, threads);
  run.compliance = ReadInfluence(directory, run.deck);
  run.cpu_seconds = ChildrenCpuSeconds() - cpu0;
  run.wall_seconds =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  for (const auto& row : run.compliance)
    for (double g : row)
      if (!std::isfinite(g)) throw std::runtime_error(directory + ": a compliance is not finite");
  return run;
}

}  // namespace epicycle::fe_reference
