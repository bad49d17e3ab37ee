// epicycle.Scene: a scene's TOML text and the scene the reader made of it (transmission::
// ParseScene: every value checked there, with its messages), changed only through its keys (the
// text is edited and read again), and the models built from it once and shared by the drivers.
#pragma once

#include <memory>
#include <mutex>
#include <optional>
#include <sstream>
#include <string>

#include <pybind11/pybind11.h>
#include <toml++/toml.h>

#include "common.hpp"
#include "epicycle/dynamics/dynamic_model.hpp"
#include "epicycle/geometry/stage.hpp"
#include "epicycle/transmission/fe_compliance.hpp"
#include "epicycle/transmission/scene.hpp"
#include "epicycle/transmission/stage_model.hpp"
#include "epicycle/transmission/stage_rig.hpp"

namespace epicycle::python {

/// A stage scene's geometry and FE compliance, built once per scene (transmission/).
using transmission::StageRig;

/// The tooth-pair columns of a driver's results (a quasi-static position's or a dynamic step's
/// loaded contacts): where (carrier angle or time), mesh, kind, flank, teeth.
struct PairColumns {
  std::vector<double> x;
  std::vector<int> tooth_a, tooth_b;
  pybind11::list mesh, kind, flank;
  Interned names;
  void Add(double at, const transmission::StageContact& c);
  /// Into `out` under their names, `x` as `x_name` (e.g. "carrier_deg", "time_s").
  void Fill(pybind11::dict& out, const char* x_name);
};

/// The columns every stage run has per position or step: LSR_i and L_i (rows × planets), K_γ, the
/// transmission error [µrad] and the sun centre's displacement [µm].
struct RunColumns {
  std::vector<double> lsr, factor, k_gamma, te_urad, sun_x_um, sun_y_um;
  /// One row: the ratios [-], TE [rad] and the sun centre [m] (converted to the names' units).
  void Add(const std::vector<double>& load_sharing, const std::vector<double>& factors, double kg,
           double te_rad, double sun_x_m, double sun_y_m);
  void Fill(pybind11::dict& out, int planets);
};

/// The influence-table options of a cache folder: "" in memory only; the default folder when
/// `cache_dir` is None (transmission::DefaultCacheDirectory, $EPICYCLE_CACHE_DIR first).
transmission::FeComplianceOptions TableOptions(const std::optional<std::string>& cache_dir);

/// Raises ValueError(message) with `text` as its scene_text attribute.
[[noreturn]] void RaiseRefused(const std::string& message, const std::string& text);

class Scene {
 public:
  /// @throws std::invalid_argument with the reader's message.
  static std::shared_ptr<Scene> Load(const std::string& path);
  static std::shared_ptr<Scene> Parse(const std::string& text, const std::string& source);

  const std::string& text() const { return text_; }
  const transmission::Scene& scene() const { return *scene_; }
  const toml::table& table() const { return table_; }

  /// A copy with `edit` applied to its TOML table, read again by the scene reader.
  /// @throws std::invalid_argument with the reader's message (this scene unchanged).
  /// The ValueError carries the refused text as its `scene_text` (its lines are the message's).
  template <typename Edit>
  std::shared_ptr<Scene> Edited(Edit&& edit) const {
    toml::table t = table_;
    edit(t);
    std::ostringstream text;
    text << t << "\n";
    try {
      return Parse(text.str(), scene_->source);
    } catch (const std::invalid_argument& e) {
      RaiseRefused(e.what(), text.str());
    }
  }
  /// Replaces this scene's text, table and parsed scene with `other`'s (caches dropped).
  void Assign(const Scene& other);

  /// The stage's geometry and compliance, built on first use (`cache_dir` as TableOptions).
  /// @throws std::invalid_argument for a gear-pair scene, naming the command.
  std::shared_ptr<const StageRig> Rig(const std::optional<std::string>& cache_dir,
                                      const char* command) const;
  /// The dynamic model of the scene (dynamics::StageDynamics), built on first use.
  std::shared_ptr<const dynamics::StageDynamics> Dynamics(
      const std::optional<std::string>& cache_dir, const char* command) const;

 private:
  std::string text_;
  toml::table table_;
  std::shared_ptr<const transmission::Scene> scene_;
  mutable std::mutex mutex_;
  mutable std::shared_ptr<const StageRig> rig_;
  mutable std::string rig_cache_;
  mutable std::shared_ptr<const dynamics::StageDynamics> dynamics_;
  mutable std::string dynamics_cache_;
};

/// The scene of a run with stresses (docs/stresses.md): `s` itself if its [model] stresses is on,
/// else a copy with it on.
std::shared_ptr<Scene> WithStresses(const std::shared_ptr<Scene>& s);

/// The scene of a command that needs a stage. @throws std::invalid_argument for a pair scene.
void RequireStage(const transmission::Scene& scene, const char* command);

}  // namespace epicycle::python
