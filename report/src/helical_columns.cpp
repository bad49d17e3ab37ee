#include "helical_columns.hpp"

#include <array>
#include <cstddef>

#include <fmt/format.h>

#include "epicycle/report/files.hpp"

namespace epicycle::report {

namespace {

// The planet fields of the columns (kPlanetHelicalFields' indices): the meshes' axial forces and
// the whole tilting moment; the planet's net axial force and the axial forces' share of the
// moment are in the records (JSON, Python) only.
constexpr std::array<std::size_t, 4> kColumnPlanetFields = {0, 1, 5, 6};

// `cell(name, unit, mean, max_abs, planet)` for every member field (planet 0) and the planets'
// fields named in kColumnPlanetFields (planet i ≥ 1), in the columns' order.
template <typename Cell>
void ForEachHelicalColumn(int planets, const transmission::HelicalLoadRange* range, Cell&& cell) {
  for (const auto& f : transmission::kHelicalMemberFields)
    cell(f.name, f.unit, range ? range->mean.*f.value : 0.0, range ? range->max_abs.*f.value : 0.0,
         0);
  for (int i = 0; i < planets; ++i)
    for (std::size_t k : kColumnPlanetFields) {
      const auto& f = transmission::kPlanetHelicalFields[k];
      const auto p = static_cast<std::size_t>(i);
      const bool has = range && p < range->mean.planets.size();
      cell(f.name, f.unit, has ? range->mean.planets[p].*f.value : 0.0,
           has ? range->max_abs.planets[p].*f.value : 0.0, i + 1);
    }
}

}  // namespace

std::string HelicalRangeColumns(int planets) {
  std::string head;
  ForEachHelicalColumn(
      planets, nullptr, [&](const char* name, const char* unit, double, double, int planet) {
        const std::string tail = planet > 0 ? fmt::format("_{}", planet) : "";
        head += fmt::format(",{0}_mean_{1}{2},{0}_max_abs_{1}{2}", name, unit, tail);
      });
  return head;
}

std::string HelicalRangeCells(int planets, const transmission::HelicalLoadRange& range, bool has) {
  std::string cells;
  ForEachHelicalColumn(planets, &range,
                       [&](const char*, const char*, double mean, double max_abs, int) {
                         cells += ",";
                         if (has) AppendCell(cells, mean);
                         cells += ",";
                         if (has) AppendCell(cells, max_abs);
                       });
  return cells;
}

}  // namespace epicycle::report
