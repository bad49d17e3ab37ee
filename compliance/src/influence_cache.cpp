#include "epicycle/compliance/influence_cache.hpp"

#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "epicycle/compliance/gmsh_mesher.hpp"

namespace epicycle::compliance {
namespace {

constexpr char kMagic[16] = {'E', 'P', 'I', 'C', 'Y', 'C', 'L', 'E',
                             '-', 'I', 'L', 'T', 0,   0,   0,   0};

class Fnv1a {
 public:
  void Bytes(const void* data, std::size_t size) {
    const auto* p = static_cast<const unsigned char*>(data);
    for (std::size_t k = 0; k < size; ++k) {
      hash_ ^= p[k];
      hash_ *= 0x100000001b3ULL;
    }
  }
  template <typename T>
  void Value(const T& v) {
    Bytes(&v, sizeof(T));
  }
  std::uint64_t hash() const { return hash_; }

 private:
  std::uint64_t hash_ = 0xcbf29ce484222325ULL;
};

std::string Hex(std::uint64_t v) {
  char buf[17];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(v));
  return buf;
}

}  // namespace

std::uint64_t InfluenceTableKey(const geometry::GearSpec& s, const ElasticMaterial& m,
                                const InfluenceTableOptions& o) {
  // Not the thickness error: the table is that of the nominal body (NominalBody), so that sampled
  // thickness errors share one table; the error acts through the geometry (the flanks' overlap).
  Fnv1a h;
  h.Value(kInfluenceTableFormat);
  h.Value(static_cast<int>(s.kind));
  h.Value(s.teeth);
  for (double v :
       {s.module, s.face_width, s.pressure_angle, s.profile_shift, s.tip_radius, s.tip_round_radius,
        s.root_radius, s.root_round_radius, s.hub_radius, s.min_tip_thickness}) {
    h.Value(v);
  }
  h.Value(s.rack.has_value());
  if (s.rack) {
    for (double v : {s.rack->addendum, s.rack->dedendum, s.rack->tip_radius}) h.Value(v);
  }
  h.Value(s.shaper.has_value());
  if (s.shaper) {
    h.Value(s.shaper->teeth);
    for (double v : {s.shaper->profile_shift, s.shaper->tip_radius, s.shaper->tip_round_radius}) {
      h.Value(v);
    }
  }
  for (double v : {m.youngs_modulus, m.poisson_ratio, m.thickness}) h.Value(v);
  h.Value(static_cast<int>(m.plane));
  const GearMeshOptions& g = o.mesh;
  for (int v : {g.involute_elements, g.tip_round_elements, g.tip_land_elements, g.fillet_elements,
                g.band_layers, g.rim_layers, g.refinement}) {
    h.Value(v);
  }
  for (double v :
       {g.band_grading, g.band_depth_fraction, g.rim_grading, g.root_block_depth, o.join_depth}) {
    h.Value(v);
  }
  // The mesher enters only when it is not the mapped one, so that the keys of mapped-mesh tables
  // are those of the format before the choice existed; a gmsh mesh also depends on gmsh's version.
  if (g.mesher != "mapped") {
    const std::string version = g.mesher == "gmsh" ? GmshMesher::LibraryVersion() : "";
    for (const std::string* text : {&g.mesher, &version}) {
      h.Value(text->size());
      h.Bytes(text->data(), text->size());
    }
  }
  // The layer term enters only when switched off (a comparison run), like the mesher above; the
  // factor on the default h only when it is not 1 and selects h (join_depth 0), for the same
  // reason: the keys of default tables stay those of the format before the factor existed.
  if (!o.layer_term) h.Value(o.layer_term);
  if (o.join_depth == 0.0 && o.join_depth_factor != 1.0) h.Value(o.join_depth_factor);
  // Fillet stresses only when tabulated (a table with them is a different payload).
  if (o.fillet_stress) {
    const std::string tag = "fillet-stress";
    h.Value(tag.size());
    h.Bytes(tag.data(), tag.size());
  }
  return h.hash();
}

geometry::Gear NominalBody(const geometry::Gear& gear) {
  geometry::GearSpec spec = gear.spec();
  spec.thickness_error = 0.0;
  return geometry::Gear(spec);
}

std::string InfluenceTableFile(const std::string& directory, std::uint64_t key) {
  return (std::filesystem::path(directory) / ("influence-" + Hex(key) + ".ilt")).string();
}

namespace {

// Reads and checks a cache file; returns false with `problem` set when it must not be used (no
// file: false with `problem` empty). The payload is parsed by the caller.
bool TryReadFile(const std::string& file, std::uint64_t key, std::string* payload,
                 std::string* problem) {
  std::ifstream in(file, std::ios::binary);
  if (!in) return false;
  char magic[16];
  in.read(magic, sizeof magic);
  if (!in || std::memcmp(magic, kMagic, sizeof magic) != 0) {
    *problem = "damaged: not an influence-table file (bad magic)";
    return false;
  }
  std::uint32_t format = 0;
  std::uint64_t stored_key = 0, size = 0;
  in.read(reinterpret_cast<char*>(&format), sizeof format);
  in.read(reinterpret_cast<char*>(&stored_key), sizeof stored_key);
  in.read(reinterpret_cast<char*>(&size), sizeof size);
  if (!in) {
    *problem = "damaged: truncated header";
    return false;
  }
  if (format != kInfluenceTableFormat) {
    *problem = "stale: format " + std::to_string(format) + ", this build reads format " +
               std::to_string(kInfluenceTableFormat);
    return false;
  }
  if (stored_key != key) {
    *problem = "stale: built for key " + Hex(stored_key) + ", this table has key " + Hex(key);
    return false;
  }
  if (size > (std::uint64_t{1} << 34)) {
    *problem = "damaged: implausible payload size " + std::to_string(size) + " bytes";
    return false;
  }
  payload->assign(size, '\0');
  in.read(payload->data(), static_cast<std::streamsize>(size));
  std::uint64_t checksum = 0;
  in.read(reinterpret_cast<char*>(&checksum), sizeof checksum);
  if (!in) {
    *problem = "damaged: truncated (payload of " + std::to_string(size) + " bytes announced)";
    return false;
  }
  if (in.peek() != std::char_traits<char>::eof()) {
    *problem = "damaged: trailing bytes after the checksum";
    return false;
  }
  Fnv1a h;
  h.Bytes(payload->data(), payload->size());
  if (h.hash() != checksum) {
    *problem =
        "damaged: checksum " + Hex(h.hash()) + " of the payload, " + Hex(checksum) + " stored";
    return false;
  }
  return true;
}

// A cache file read and parsed by `parse` (which throws std::runtime_error for a payload that
// does not hold what it should); false with `problem` set when it must not be used.
template <typename Parse>
bool TryLoad(const std::string& file, std::uint64_t key, std::string* problem, Parse&& parse) {
  std::string payload;
  if (!TryReadFile(file, key, &payload, problem)) return false;
  try {
    std::istringstream body(std::move(payload));  // C++20: takes the buffer, no copy
    parse(body);
  } catch (const std::runtime_error& e) {
    *problem = std::string("damaged: ") + e.what();
    return false;
  }
  return true;
}

void Write(const std::string& file, std::uint64_t key, const std::string& payload) {
  Fnv1a h;
  h.Bytes(payload.data(), payload.size());
  // A name of this process and call alone, so that processes (or threads) building the same table
  // at once never write into each other's file; the rename is atomic, the last one wins and every
  // reader sees a complete file.
  static std::atomic<unsigned> counter{0};
  const std::string tmp =
      file + "." + std::to_string(::getpid()) + "." + std::to_string(counter.fetch_add(1)) + ".tmp";
  {
    errno = 0;
    std::ofstream out(tmp, std::ios::binary | std::ios::trunc);
    const std::uint32_t format = kInfluenceTableFormat;
    const std::uint64_t size = payload.size(), checksum = h.hash();
    out.write(kMagic, sizeof kMagic);
    out.write(reinterpret_cast<const char*>(&format), sizeof format);
    out.write(reinterpret_cast<const char*>(&key), sizeof key);
    out.write(reinterpret_cast<const char*>(&size), sizeof size);
    out.write(payload.data(), static_cast<std::streamsize>(payload.size()));
    out.write(reinterpret_cast<const char*>(&checksum), sizeof checksum);
    out.close();
    if (!out) {
      const std::string reason = errno != 0 ? std::strerror(errno) : "the stream failed";
      std::error_code ignored;
      std::filesystem::remove(tmp, ignored);
      throw std::runtime_error("influence-table cache: cannot write '" + tmp + "': " + reason);
    }
  }
  std::error_code error;
  std::filesystem::rename(tmp, file, error);
  if (error) {
    std::error_code ignored;  // the rename's reason is the one to report
    std::filesystem::remove(tmp, ignored);
    throw std::runtime_error("influence-table cache: cannot rename '" + tmp + "' to '" + file +
                             "': " + error.message());
  }
}

}  // namespace

namespace {

// The cache's one path for every kind of file: `value` read from `file` by `read` when the file is
// valid, otherwise built by `build`, written by `write` and the outcome reported. `what` names
// the value ("influence table of 'sun'"), `rebuilt` the phrase of a rebuild ("the table of 'sun'
// was rebuilt").
template <typename T, typename Read, typename Build, typename WritePayload>
T LoadOrBuildFile(const std::string& directory, const std::string& file, std::uint64_t key,
                  const std::string& what, const std::string& rebuilt, CacheReport* report,
                  Read&& read, Build&& build, WritePayload&& write) {
  CacheReport local;
  CacheReport& r = report != nullptr ? *report : local;
  r.file = file;
  T value;
  std::string problem;
  if (TryLoad(file, key, &problem, [&](std::istream& in) { value = read(in); })) {
    r.outcome = CacheOutcome::kLoaded;
    r.message = what + " loaded from '" + file + "'";
    return value;
  }
  value = build();
  std::filesystem::create_directories(directory);
  std::ostringstream body;
  write(value, body);
  Write(file, key, body.str());
  if (problem.empty()) {
    r.outcome = CacheOutcome::kBuilt;
    r.message = what + " built and written to '" + file + "'";
  } else {
    r.outcome = CacheOutcome::kRebuilt;
    r.message = "influence-table cache file '" + file + "' is " + problem +
                "; not used: " + rebuilt + " and the file replaced";
  }
  return value;
}

}  // namespace

InfluenceTable LoadOrBuildInfluenceTable(const geometry::Gear& gear,
                                         const ElasticMaterial& material,
                                         const InfluenceTableOptions& options,
                                         const std::string& directory, CacheReport* report) {
  if (directory.empty()) {
    throw std::invalid_argument("influence-table cache: directory = '': must name a directory");
  }
  options.Validate();
  material.Validate();
  const std::uint64_t key = InfluenceTableKey(gear.spec(), material, options);
  const std::string file = InfluenceTableFile(directory, key);
  const geometry::Gear nominal = NominalBody(gear);
  return LoadOrBuildFile<InfluenceTable>(
      directory, file, key, "influence table of '" + gear.name() + "'",
      "the table of '" + gear.name() + "' was rebuilt", report,
      [&](std::istream& in) {
        return InfluenceTable::ReadPayload(in, nominal, options.fillet_stress);
      },
      [&] { return InfluenceTable::Build(nominal, material, options); },
      [](const InfluenceTable& t, std::ostream& out) { t.WritePayload(out); });
}

std::uint64_t DamagedInfluenceKey(const geometry::GearSpec& spec, const ElasticMaterial& material,
                                  const InfluenceTableOptions& options, const RootCrack& crack,
                                  int neighbours, const CrackMeshOptions& crack_options) {
  InfluenceTableOptions o = options;
  o.fillet_stress = false;  // the rows are built without them (DamagedInfluence::Build)
  Fnv1a h;
  h.Value(InfluenceTableKey(spec, material, o));
  const std::string tag = "root-crack";
  h.Value(tag.size());
  h.Bytes(tag.data(), tag.size());
  h.Value(crack.tooth);
  h.Value(crack.side);
  h.Value(crack.start_arc);
  h.Value(crack.path.size());
  for (const CrackSegment& g : crack.path) {
    h.Value(g.length);
    h.Value(g.angle);
  }
  h.Value(neighbours);
  h.Value(crack_options.crack_elements);
  h.Value(crack_options.tip_grading);
  h.Value(crack_options.max_element);
  h.Value(crack_options.open);
  return h.hash();
}

std::string DamagedInfluenceFile(const std::string& directory, std::uint64_t key) {
  return (std::filesystem::path(directory) / ("damaged-" + Hex(key) + ".ilt")).string();
}

DamagedInfluence LoadOrBuildDamagedInfluence(const geometry::Gear& gear,
                                             const ElasticMaterial& material,
                                             const RootCrack& crack,
                                             const InfluenceTableOptions& options, int neighbours,
                                             const CrackMeshOptions& crack_options,
                                             const std::string& directory, CacheReport* report) {
  if (directory.empty()) {
    throw std::invalid_argument("influence-table cache: directory = '': must name a directory");
  }
  options.Validate();
  material.Validate();
  crack_options.Validate();
  const geometry::Gear nominal = NominalBody(gear);
  crack.Validate(nominal);
  const std::uint64_t key =
      DamagedInfluenceKey(gear.spec(), material, options, crack, neighbours, crack_options);
  const std::string file = DamagedInfluenceFile(directory, key);
  const std::string what = "damaged rows of '" + gear.name() + "' (root crack in tooth " +
                           std::to_string(crack.tooth) + ")";
  return LoadOrBuildFile<DamagedInfluence>(
      directory, file, key, what, "the " + what + " were rebuilt", report,
      [&](std::istream& in) { return DamagedInfluence::ReadPayload(in, nominal, crack); },
      [&] {
        return DamagedInfluence::Build(nominal, material, crack, options, neighbours,
                                       crack_options);
      },
      [](const DamagedInfluence& d, std::ostream& out) { d.WritePayload(out); });
}

}  // namespace epicycle::compliance
