#include "epicycle/transmission/root_stress.hpp"

#include <algorithm>
#include <stdexcept>
#include <string>

namespace epicycle::transmission {

namespace {

FilletSpot Spot(const compliance::FilletStress& f, std::size_t m) {
  return {f.tooth, f.side, f.table->fillet_points()[m].arc_length};
}

}  // namespace

std::vector<GearRootStress> SummariseRootStress(
    const std::vector<compliance::FilletStress>& fillets, int bodies) {
  std::vector<GearRootStress> out(static_cast<std::size_t>(bodies));
  for (int b = 0; b < bodies; ++b) out[b].body = b;
  for (const compliance::FilletStress& f : fillets) {
    GearRootStress& g = out.at(static_cast<std::size_t>(f.body));
    for (std::size_t m = 0; m < f.sigma.size(); ++m) {
      if (f.sigma[m] > g.tension) {
        g.tension = f.sigma[m];
        g.tension_at = Spot(f, m);
      }
      if (f.sigma[m] < g.compression) {
        g.compression = f.sigma[m];
        g.compression_at = Spot(f, m);
      }
    }
  }
  return out;
}

void RootStressEnvelope::Add(const std::vector<compliance::FilletStress>& fillets) {
  ++states_;
  for (const compliance::FilletStress& f : fillets) {
    if (points_.size() <= static_cast<std::size_t>(f.body))
      points_.resize(static_cast<std::size_t>(f.body) + 1);
    std::vector<Point>& body = points_[static_cast<std::size_t>(f.body)];
    if (body.empty()) body.resize(2 * static_cast<std::size_t>(f.table->teeth()));
    Point& p = body.at(2 * static_cast<std::size_t>(f.tooth) + static_cast<std::size_t>(f.side));
    if (p.table == nullptr) {
      p.table = f.table;
      p.max.assign(f.sigma.size(), 0.0);
      p.min.assign(f.sigma.size(), 0.0);
    }
    for (std::size_t m = 0; m < f.sigma.size(); ++m) {
      p.max[m] = std::max(p.max[m], f.sigma[m]);
      p.min[m] = std::min(p.min[m], f.sigma[m]);
    }
  }
}

std::vector<RootStressEnvelope::Range> RootStressEnvelope::Ranges() const {
  std::vector<Range> out(static_cast<std::size_t>(bodies_));
  for (int b = 0; b < bodies_; ++b) out[b].body = b;
  for (std::size_t body = 0; body < points_.size(); ++body) {
    for (std::size_t key = 0; key < points_[body].size(); ++key) {
      const Point& p = points_[body][key];
      if (p.table == nullptr) continue;
      Range& r = out.at(body);
      for (std::size_t m = 0; m < p.max.size(); ++m) {
        // max and min start at 0: a state that did not compute the point counts as unloaded.
        if (p.max[m] - p.min[m] > r.range) {
          r.range = p.max[m] - p.min[m];
          r.at = {static_cast<int>(key / 2), static_cast<int>(key % 2),
                  p.table->fillet_points()[m].arc_length};
          r.max = p.max[m];
          r.min = p.min[m];
        }
      }
    }
  }
  return out;
}

void RootStressTracker::Add(const std::vector<compliance::FilletStress>& fillets, double x) {
  if (fillets.empty()) return;
  Add(fillets, SummariseRootStress(fillets, bodies_), x);
}

void RootStressTracker::Add(const std::vector<compliance::FilletStress>& fillets,
                            const std::vector<GearRootStress>& extremes, double x) {
  if (fillets.empty()) return;
  if (extremes.size() != static_cast<std::size_t>(bodies_))
    throw std::invalid_argument("RootStressTracker: extremes of " +
                                std::to_string(extremes.size()) + " bodies for " +
                                std::to_string(bodies_) + " gears");
  if (summary_.empty()) {
    summary_.resize(static_cast<std::size_t>(bodies_));
    for (int b = 0; b < bodies_; ++b) {
      summary_[static_cast<std::size_t>(b)].gear = gears_[static_cast<std::size_t>(b)];
      summary_[static_cast<std::size_t>(b)].extremes.body = b;
    }
  }
  envelope_.Add(fillets);
  for (std::size_t b = 0; b < extremes.size(); ++b) {
    RootStressSummary& g = summary_[b];
    if (extremes[b].tension > g.extremes.tension) {
      g.extremes.tension = extremes[b].tension;
      g.extremes.tension_at = extremes[b].tension_at;
      g.tension_x = x;
    }
    if (extremes[b].compression < g.extremes.compression) {
      g.extremes.compression = extremes[b].compression;
      g.extremes.compression_at = extremes[b].compression_at;
      g.compression_x = x;
    }
  }
}

std::vector<RootStressSummary> RootStressTracker::Result() const {
  std::vector<RootStressSummary> out = summary_;
  if (out.empty()) return out;
  const std::vector<RootStressEnvelope::Range> ranges = envelope_.Ranges();
  for (std::size_t b = 0; b < out.size(); ++b) out[b].range = ranges[b];
  return out;
}

}  // namespace epicycle::transmission
