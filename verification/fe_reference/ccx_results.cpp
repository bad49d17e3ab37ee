// Reading CalculiX's .dat output (ccx 2.20): the node-print blocks
//   " forces (fx,fy,fz) for set HUB1 and time  0.1000000E+01" followed by "node fx fy fz" rows,
// and the contact statistics of each pair
//   " statistics for slave set G1T3, master set G2T5 and time  0.1000000E+01" ...
// with its "normal force" line.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <limits>
#include <map>
#include <sstream>
#include <stdexcept>

#include "fe_deck.hpp"

namespace epicycle::fe_reference {

namespace {

bool StartsWith(const std::string& line, const std::string& text) {
  const std::size_t i = line.find_first_not_of(' ');
  return i != std::string::npos && line.compare(i, text.size(), text) == 0;
}

// The number after "and time" in a block header.
double TimeOf(const std::string& line) {
  const std::size_t i = line.rfind("time");
  return std::stod(line.substr(i + 4));
}

bool IsStepEnd(double time) { return std::abs(time - std::round(time)) < 1e-9 && time > 0.5; }

}  // namespace

std::vector<FeStepResult> ReadSteps(const std::string& directory, const FeDeckInfo& info) {
  const std::string path = directory + "/deck.dat";
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read (did ccx run?)");
  std::vector<std::string> lines;
  for (std::string line; std::getline(f, line);) lines.push_back(line);
  std::map<int, std::pair<double, double>> hub;  // id → (x, y) relative to c_1 [mm]
  for (std::size_t i = 0; i < info.hub_nodes.size(); ++i)
    hub[info.hub_nodes[i]] = {info.hub_x[i], info.hub_y[i]};
  std::map<std::string, std::size_t> pair_of;
  for (std::size_t j = 0; j < info.pairs.size(); ++j) pair_of[info.pairs[j].slave] = j;
  // Per unit slab thickness to the whole face width; the slab is 1 mm, forces in N, lengths mm.
  const double width_factor = info.face_width / info.thickness;

  // Blocks are printed per increment; a step's results are the blocks at its end (integral
  // total time, CalculiX's static steps having period 1).
  std::vector<FeStepResult> steps;
  std::map<double, std::size_t> step_at;
  auto step_for = [&](double time) -> FeStepResult* {
    if (!IsStepEnd(time)) return nullptr;
    auto [it, fresh] = step_at.try_emplace(time, steps.size());
    if (fresh) {
      FeStepResult r;
      r.time = time;
      r.pair_force.assign(info.pairs.size(), std::numeric_limits<double>::quiet_NaN());
      steps.push_back(r);
    }
    return &steps[it->second];
  };
  for (std::size_t i = 0; i < lines.size(); ++i) {
    const std::string& line = lines[i];
    if (StartsWith(line, "forces (fx,fy,fz) for set HUB1")) {
      FeStepResult* step = step_for(TimeOf(line));
      double moment = 0;  // [N·mm] per slab
      std::size_t k = i + 1;
      for (; k < lines.size(); ++k) {
        std::istringstream s(lines[k]);
        int id = 0;
        double fx = 0, fy = 0;
        if (!(s >> id >> fx >> fy)) {
          if (k > i + 1 && lines[k].find_first_not_of(' ') != std::string::npos) break;
          continue;
        }
        const auto it = hub.find(id);
        if (it == hub.end())
          throw std::runtime_error(path + ":" + std::to_string(k + 1) + ": node " +
                                   std::to_string(id) + " is not a hub node of deck.info");
        moment += it->second.first * fy - it->second.second * fx;
      }
      if (step) step->moment = moment * width_factor * 1e-3;  // → N·m
      i = k - 1;
    } else if (StartsWith(line, "statistics for slave set")) {
      FeStepResult* step = step_for(TimeOf(line));
      const std::size_t a = line.find("slave set") + 10, b = line.find(',', a);
      const std::string slave = line.substr(a, b - a);
      for (std::size_t k = i + 1; k < lines.size() && k < i + 20; ++k) {
        if (!StartsWith(lines[k], "area,")) continue;
        std::istringstream s(lines[k + 1 < lines.size() ? k + 1 : k]);
        double area = 0, normal = 0;
        // The value line may follow a blank line.
        std::size_t v = k + 1;
        while (v < lines.size() && lines[v].find_first_not_of(' ') == std::string::npos) ++v;
        // A pair out of contact has area 0 and a NaN normal force (ccx prints "NaN").
        std::istringstream values(v < lines.size() ? lines[v] : "");
        std::string area_text, normal_text;
        values >> area_text >> normal_text;
        char* end = nullptr;
        area = std::strtod(area_text.c_str(), &end);
        if (area_text.empty() || *end != '\0')
          throw std::runtime_error(path + ":" + std::to_string(v + 1) +
                                   ": cannot read the contact area of " + slave);
        normal = area > 0 ? std::strtod(normal_text.c_str(), &end) : 0.0;
        if (area > 0 && (normal_text.empty() || *end != '\0' || !std::isfinite(normal)))
          throw std::runtime_error(path + ":" + std::to_string(v + 1) +
                                   ": cannot read the normal force of " + slave);
        const auto it = pair_of.find(slave);
        if (it == pair_of.end())
          throw std::runtime_error(path + ": contact statistics of an unknown slave set " + slave);
        // "normal force (+ = tension)": a compressive contact force is negative.
        if (step) step->pair_force[it->second] = -normal * width_factor;
        break;
      }
    }
  }
  if (steps.size() != info.rotations.size())
    throw std::runtime_error(path + ": " + std::to_string(steps.size()) + " of " +
                             std::to_string(info.rotations.size()) +
                             " steps completed (see ccx's log)");
  for (std::size_t k = 0; k < steps.size(); ++k) {
    steps[k].rotation = info.rotations[k];
    for (std::size_t j = 0; j < info.pairs.size(); ++j) {
      if (!std::isfinite(steps[k].pair_force[j]))
        throw std::runtime_error(path + ": step " + std::to_string(k + 1) +
                                 " lacks the contact statistics of " + info.pairs[j].slave);
    }
  }
  return steps;
}

FeSample Interpolate(const FeDeckInfo& info, const std::vector<FeStepResult>& steps) {
  if (steps.size() < 2)
    throw std::invalid_argument("fe reference: " + std::to_string(steps.size()) +
                                " steps: two or more bracket the torque");
  const double target = std::abs(info.torque);
  for (std::size_t k = 0; k < steps.size(); ++k) {
    const bool rising = k == 0 || (std::abs(steps[k].rotation) > std::abs(steps[k - 1].rotation) &&
                                   std::abs(steps[k].moment) > std::abs(steps[k - 1].moment));
    if (!rising || !(std::abs(steps[k].moment) > 0))
      throw std::runtime_error("fe reference: the moment does not rise with the rotation at step " +
                               std::to_string(k + 1));
  }
  // The bracketing pair of steps, or the nearest end pair (extrapolation).
  std::size_t i = 0;
  while (i + 2 < steps.size() && std::abs(steps[i + 1].moment) < target) ++i;
  const FeStepResult& a = steps[i];
  const FeStepResult& b = steps[i + 1];
  FeSample s;
  s.angle = info.angle;
  s.extrapolated = target < std::abs(a.moment) || target > std::abs(b.moment);
  // θ ∝ M^p between the two steps (the contact's mild hardening): log-log interpolation.
  const double la = std::log(std::abs(a.moment)), lb = std::log(std::abs(b.moment));
  const double w = (std::log(target) - la) / (lb - la);
  const double theta_a = std::abs(a.rotation), theta_b = std::abs(b.rotation);
  const double theta = std::exp(std::log(theta_a) + w * (std::log(theta_b) - std::log(theta_a)));
  const double sign = a.rotation > 0 ? 1.0 : -1.0;
  s.rotation = sign * theta;
  s.approach = theta * info.base_radius1;
  s.mesh_stiffness = target / info.base_radius1 / s.approach;
  const double u = (theta - theta_a) / (theta_b - theta_a);
  s.step = i;
  s.weight = u;
  s.pair_force.resize(info.pairs.size());
  for (std::size_t j = 0; j < info.pairs.size(); ++j) {
    s.pair_force[j] = a.pair_force[j] + u * (b.pair_force[j] - a.pair_force[j]);
    s.force_sum += s.pair_force[j];
  }
  double sum_last = 0;
  for (double fj : steps.back().pair_force) sum_last += fj;
  s.moment_balance = std::abs(sum_last * info.base_radius1 - std::abs(steps.back().moment)) /
                     std::abs(steps.back().moment);
  return s;
}

std::vector<std::vector<double>> ReadFilletStresses(const std::string& directory,
                                                    const FeDeckInfo& info) {
  // CalculiX's ASCII .frd: per output increment a "100CL" header whose third field is the total
  // time, then for "-4  STRESS" the rows " -1" + node (10 columns) + SXX SYY SZZ SXY SYZ SZX
  // (12 columns each, which may touch), ended by " -3".
  const std::string path = directory + "/deck.frd";
  std::ifstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot be read (did ccx run?)");
  std::map<int, std::size_t> slot;
  for (std::size_t j = 0; j < info.fillet_nodes.size(); ++j) slot[info.fillet_nodes[j].node] = j;
  std::map<double, std::map<int, std::array<double, 3>>> at_time;  // time → node → xx, yy, xy
  double time = -1;
  bool stress = false;
  std::string line;
  std::size_t number = 0;
  while (std::getline(f, line)) {
    ++number;
    if (StartsWith(line, "100CL")) {
      std::istringstream h(line);
      std::string tag, code;
      h >> tag >> code >> time;
      stress = false;
    } else if (StartsWith(line, "-4")) {
      stress = line.find("STRESS") != std::string::npos;
    } else if (StartsWith(line, "-3")) {
      stress = false;
    } else if (stress && line.size() >= 13 + 6 * 12 && line.compare(0, 3, " -1") == 0) {
      if (!IsStepEnd(time)) continue;
      const int node = std::stoi(line.substr(3, 10));
      if (!slot.count(node)) continue;
      std::array<double, 6> v{};
      for (int c = 0; c < 6; ++c) {
        const std::string field = line.substr(13 + 12 * c, 12);
        char* end = nullptr;
        v[c] = std::strtod(field.c_str(), &end);
        if (end == field.c_str() || !std::isfinite(v[c]))
          throw std::runtime_error(path + ":" + std::to_string(number) +
                                   ": cannot read the stress of node " + std::to_string(node));
      }
      at_time[time][node] = {v[0], v[1], v[3]};
    }
  }
  if (at_time.size() != info.rotations.size())
    throw std::runtime_error(path + ": stresses of " + std::to_string(at_time.size()) + " of " +
                             std::to_string(info.rotations.size()) + " steps");
  std::vector<std::vector<double>> out;
  for (const auto& [t, nodes] : at_time) {
    std::vector<double> sigma(info.fillet_nodes.size());
    for (std::size_t j = 0; j < info.fillet_nodes.size(); ++j) {
      const FeFilletNode& n = info.fillet_nodes[j];
      const auto it = nodes.find(n.node);
      if (it == nodes.end())
        throw std::runtime_error(path + ": no stress of fillet node " + std::to_string(n.node) +
                                 " at time " + std::to_string(t));
      const auto& [xx, yy, xy] = it->second;
      // tᵀσt [MPa → Pa]
      sigma[j] = (n.tx * n.tx * xx + n.ty * n.ty * yy + 2 * n.tx * n.ty * xy) * 1e6;
    }
    out.push_back(std::move(sigma));
  }
  return out;
}

std::vector<FeToothFillet> FilletExtremes(const FeDeckInfo& info, const FeSample& sample,
                                          const std::vector<std::vector<double>>& sigma) {
  if (sample.step + 1 >= sigma.size())
    throw std::invalid_argument("fe reference: fillet stresses of " +
                                std::to_string(sigma.size()) + " steps, step " +
                                std::to_string(sample.step + 2) + " needed");
  const std::vector<double>& a = sigma[sample.step];
  const std::vector<double>& b = sigma[sample.step + 1];
  std::map<std::pair<int, int>, FeToothFillet> teeth;
  for (std::size_t j = 0; j < info.fillet_nodes.size(); ++j) {
    const FeFilletNode& n = info.fillet_nodes[j];
    const double v = a[j] + sample.weight * (b[j] - a[j]);
    auto [it, fresh] = teeth.try_emplace({n.gear, n.tooth});
    FeToothFillet& t = it->second;
    if (fresh) {
      t.gear = n.gear;
      t.tooth = n.tooth;
      t.tension = -std::numeric_limits<double>::infinity();
      t.compression = std::numeric_limits<double>::infinity();
    }
    if (v > t.tension) {
      t.tension = v;
      t.tension_side = n.side;
      t.tension_arc = n.arc_length;
    }
    if (v < t.compression) {
      t.compression = v;
      t.compression_side = n.side;
      t.compression_arc = n.arc_length;
    }
  }
  std::vector<FeToothFillet> out;
  for (auto& [key, t] : teeth) out.push_back(t);
  return out;
}

}  // namespace epicycle::fe_reference
