// trajectory export as H5MD 1.1 on HDF5 (docs/rendering.md, "Trajectory"): the grains'
// positions, velocities, angles, angular velocities and contact counts frame after frame in
// chunked, deflate-compressed datasets that h5py, MDAnalysis and other H5MD readers open
#pragma once
#include <cstdint>
#include <optional>
#include <string>

#include "contact/contact_set.hpp"
#include "core/vec.hpp"
#include "world/world.hpp"

namespace gs {

/// the H5MD particle group the frames go to: /particles/all
inline constexpr const char* kH5mdParticles = "/particles/all";

/// an H5MD trajectory file open for appending frames. The plane is stored as a slab of unit
/// thickness (positions (x, y, 0), box edges diag(Lx, Ly, 1), dimension 3), as the extended XYZ
/// does, because the H5MD readers of the field take three-dimensional boxes only. Every frame
/// is flushed to disk before write() returns, so a killed run keeps the frames written.
class H5mdWriter {
 public:
  H5mdWriter() = default;
  H5mdWriter(const H5mdWriter&) = delete;
  H5mdWriter& operator=(const H5mdWriter&) = delete;
  ~H5mdWriter();

  /// create `path` afresh for the grains of `w` (their number, species, radii and labels are
  /// fixed for the file's life); OutputError when it cannot be written
  void create(const std::string& path, const World& w);
  /// reopen a file this writer made and keep its first `frames` frames only (a resumed run
  /// drops what was written after its checkpoint; −1 keeps them all); InputError when the file
  /// is not such a file, holds fewer frames, or was made for another number of grains
  void reopen(const std::string& path, const World& w, std::int64_t frames);
  /// append the world's state as the next frame; `contacts` gives the contact counts (null:
  /// zeros), `tap` the tap in progress (none: −1 in /observables/tap)
  void write(const World& w, const ContactSet* contacts, Vec2 gravity, std::optional<long> tap);
  /// frames in the file
  std::int64_t frames() const { return frames_; }
  bool is_open() const { return file_ >= 0; }
  void close();

 private:
  void open_datasets();
  std::string path_;
  std::int64_t file_ = -1;  ///< hid_t of the file (−1: closed)
  std::int64_t n_ = 0;      ///< grains per frame
  std::int64_t frames_ = 0;
  /// hid_t of step, time, box edges, position, velocity, theta, omega, contacts, gravity, tap
  std::int64_t ds_[10] = {-1, -1, -1, -1, -1, -1, -1, -1, -1, -1};
};

}  // namespace gs
