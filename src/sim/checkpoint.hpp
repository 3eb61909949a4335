// bitwise checkpoints: a versioned, checksummed, little-endian binary file holding everything
// a run needs to continue exactly where it stopped (byte layout: docs/robustness.md)
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <string_view>
#include <vector>

#include "contact/contact_set.hpp"
#include "sim/simulation.hpp"
#include "world/world.hpp"

namespace gs {

/// "GSCKPT\0\1": the first eight bytes of every checkpoint
inline constexpr char kCheckpointMagic[8] = {'G', 'S', 'C', 'K', 'P', 'T', '\0', '\1'};
inline constexpr std::uint32_t kCheckpointVersion = 2;  ///< 2: particle labels (1 is read too)
/// written as a little-endian u32; a big-endian writer would leave 01 02 03 04 on disk
inline constexpr std::uint32_t kCheckpointEndian = 0x01020304u;
/// magic, version, endianness marker, payload size, payload checksum
inline constexpr std::size_t kCheckpointHeader = 32;

/// opaque data stored by the caller next to the simulation: observer accumulators, output
/// file offsets (taps.csv), RNG positions… key → bytes, written in key order
struct CheckpointExtras {
  std::map<std::string, std::string> entries;
};

/// the decoded contents of a checkpoint file
struct Checkpoint {
  std::string path;           ///< file it was read from (for messages)
  std::string scene_toml;     ///< scene_to_toml of the scene the run was built from
  double clock_origin = 0.0;  ///< World::clock_origin (run state, not a scene key), s
  // per-particle constants (kept, not recomputed, so nothing depends on re-derivation)
  std::vector<std::int32_t> sp;
  std::vector<double> radius, mass, inv_mass, inv_inertia;
  State s;                       ///< positions, velocities, accelerations, wraps, t, step
  std::vector<std::int32_t> id;  ///< each slot's particle label (version 1: the slot itself)
  std::uint8_t integrator = 0;   ///< IntegratorKind of the history below
  std::vector<double> integ;     ///< Integrator::save()
  std::vector<PairKey> keys;     ///< persistent contacts, ascending (i, j, image)
  std::vector<ContactState> contact_state;  ///< parallel to keys, or empty (Model S)
  std::uint64_t degenerate = 0;             ///< ContactSet::degenerate
  CheckpointExtras extras;
};

/// FNV-1a, 64 bit: the payload checksum
std::uint64_t fnv1a64(std::string_view bytes);

/// the checkpoint of `sim`, built from `scene` (stored with it), as bytes (header + payload)
std::string encode_checkpoint(const Simulation& sim, const SceneSpec& scene,
                              const CheckpointExtras& extras);
/// write atomically (temporary file, fsync, rename); InputError naming the path on failure
void write_checkpoint(const Simulation& sim, const SceneSpec& scene, const CheckpointExtras& extras,
                      const std::string& path);

/// decode bytes; InputError naming `name_for_messages` and the byte offset of the problem
Checkpoint decode_checkpoint(std::string_view bytes, const std::string& name_for_messages);
/// read and validate a file (magic, version, endianness, sizes, checksum)
Checkpoint read_checkpoint(const std::string& path);

/// the scene stored in a checkpoint (InputError naming the checkpoint when it does not parse)
SceneSpec checkpoint_scene(const Checkpoint& c);
/// rebuild the World from the stored scene and continue bitwise: the next step() gives the
/// same state as the uninterrupted run. InputError when the contents do not fit together.
Simulation restore_simulation(const Checkpoint& c);
/// put a checkpoint's history into a Simulation built on its state: accelerations, integrator
/// history and persistent contacts (with the degenerate-contact counter when asked), replacing
/// what the constructor's force evaluation produced
void load_checkpoint_history(Simulation& sim, const Checkpoint& c, bool degenerate_count);

}  // namespace gs
