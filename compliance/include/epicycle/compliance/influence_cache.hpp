// A disk cache of gear influence tables, keyed by a hash of everything that defines a table.
#pragma once

#include <cstdint>
#include <string>

#include "epicycle/compliance/damaged_influence.hpp"
#include "epicycle/compliance/influence_table.hpp"

namespace epicycle::compliance {

/// Version of the table file format and of the table's construction; part of the key, so a
/// change of either makes every older file stale.
inline constexpr std::uint32_t kInfluenceTableFormat = 3;

/// 64-bit FNV-1a hash of everything that defines a table: kInfluenceTableFormat, every field of
/// the gear spec that shapes the body (kind, z, m, b, α, x, tip and root radii and roundings, hub
/// or rim radius, cutter data, tip-thickness limit; not the name, not the thickness error: the
/// table is that of the nominal body, NominalBody), the material (E, ν, b, plane) and the table
/// options that change its values (mesh options, join depth, layer term, fillet stress; not the
/// solve batch).
/// Doubles enter bit-exactly.
std::uint64_t InfluenceTableKey(const geometry::GearSpec& spec, const ElasticMaterial& material,
                                const InfluenceTableOptions& options);

/// The gear without its tooth-thickness error: the body the influence table of `gear` is built on.
/// A thickness error Δs turns each flank σ by σ·Δs/(2 r_b) about the centre (a rigid µm offset of
/// the surface, like relief); it enters the model through the flanks' overlap (the initial
/// separation of the contact problem), while the body's compliance is that of the nominal tooth,
/// changed by the error only to relative order 3|Δs|/s (s the tooth thickness, bending ∝ 1/s³).
geometry::Gear NominalBody(const geometry::Gear& gear);

/// What the cache did.
enum class CacheOutcome {
  kLoaded,   ///< a valid file was read
  kBuilt,    ///< no file: built and written
  kRebuilt,  ///< a damaged or stale file was found, reported, rebuilt and replaced
};

/// The outcome and a message for the user (names the file and, for kRebuilt, what was wrong).
struct CacheReport {
  CacheOutcome outcome = CacheOutcome::kBuilt;
  std::string file;
  std::string message;
};

/// The file of a table in `directory`: "<directory>/influence-<key as 16 hex digits>.ilt".
std::string InfluenceTableFile(const std::string& directory, std::uint64_t key);

/// File layout (little-endian as written by this machine):
///   magic "EPICYCLE-ILT\0\0\0\0" (16 bytes) | format u32 | key u64 | payload size u64 |
///   payload (InfluenceTable::WritePayload) | FNV-1a 64 of the payload u64.
/// Loads the table of (gear, material, options) from `directory` if its file is present and
/// valid (magic, format, key and checksum all match, payload consistent); otherwise builds it
/// (on NominalBody(gear)) and writes the file atomically: a temporary file of a name unique to
/// the process and call, renamed onto the file, so that processes building the same table at
/// once all end with a valid file. A damaged or stale file is never
/// used: it is reported in `report` and replaced.
/// @throws std::invalid_argument for bad input (as InfluenceTable::Build) or an empty
///         directory name; std::runtime_error if the file cannot be written.
InfluenceTable LoadOrBuildInfluenceTable(const geometry::Gear& gear,
                                         const ElasticMaterial& material,
                                         const InfluenceTableOptions& options,
                                         const std::string& directory, CacheReport* report);

/// The key of a body's damaged rows (DamagedInfluence::Build): the healthy table's key
/// (InfluenceTableKey with fillet_stress off, as the rows are built) and every field of the crack
/// (tooth, side, start arc, each segment's length and angle), the neighbours K and the crack mesh
/// options, doubles bit-exactly.
std::uint64_t DamagedInfluenceKey(const geometry::GearSpec& spec, const ElasticMaterial& material,
                                  const InfluenceTableOptions& options, const RootCrack& crack,
                                  int neighbours, const CrackMeshOptions& crack_options);

/// The file of a body's damaged rows: "<directory>/damaged-<key as 16 hex digits>.ilt".
std::string DamagedInfluenceFile(const std::string& directory, std::uint64_t key);

/// As LoadOrBuildInfluenceTable, for the damaged rows of `gear` with `crack` (the same file
/// layout, the payload DamagedInfluence::WritePayload; built on NominalBody(gear)): loaded when
/// its file is valid, otherwise built, written atomically, and a damaged or stale file reported
/// and replaced.
/// @throws std::invalid_argument as DamagedInfluence::Build or for an empty directory name;
///         std::runtime_error if the file cannot be written.
DamagedInfluence LoadOrBuildDamagedInfluence(const geometry::Gear& gear,
                                             const ElasticMaterial& material,
                                             const RootCrack& crack,
                                             const InfluenceTableOptions& options, int neighbours,
                                             const CrackMeshOptions& crack_options,
                                             const std::string& directory, CacheReport* report);

}  // namespace epicycle::compliance
