// the files of one configuration snapshot (docs/rendering.md, "Snapshots"): VTK XML PolyData
// (ASCII or compressed binary) with each grain's outline as a polygon cell, the ParaView
// collection (.pvd) that lists them with their times, and one CSV row per contact with its
// point, normal and forces
#pragma once
#include <cstdint>
#include <fstream>
#include <iosfwd>
#include <string>
#include <vector>

#include "contact/contact_set.hpp"
#include "world/world.hpp"

namespace gs {

/// vertices of a disk's outline in the .vtp (enough for a round look; radius is cell data)
inline constexpr int kDiskOutlineVertices = 32;

/// one snapshot of a run, as listed by the collection and the index
struct SnapshotEntry {
  double t = 0.0;  ///< s
  std::int64_t step = 0;
  long tap = -1;         ///< the taps.csv tap of a measurement snapshot, −1 otherwise
  bool at_tap = false;   ///< taken at a tap's measurement
  bool at_time = false;  ///< taken at a scheduled time
};

/// DIR/snapshots file name of snapshot k: snap_000012.vtp, contacts_000012.csv
std::string snapshot_file(const char* stem, long k, const char* ext);

/// how the arrays of a .vtp are stored: ASCII text (10 significant digits) or binary, zlib
/// compressed and base64 encoded in the XML (vtkZLibDataCompressor: exact and smaller)
enum class VtpEncoding : std::uint8_t { Ascii, Binary };

/// the grains as VTK XML PolyData: one polygon cell per grain (its true outline; disks as
/// kDiskOutlineVertices-gons) with cell data id, species, radius, sides, theta, velocity,
/// omega, speed, contacts; centres wrapped into periodic boxes. Throws OutputError
void write_vtp(const std::string& path, const World& w, const ContactSet& c, long tap,
               VtpEncoding enc = VtpEncoding::Ascii);

/// the contact CSV's header line (pandas.read_csv reads the file as is)
std::vector<std::string> contact_columns();
/// one row per contact of the last step (ContactSet::records, as `render --chains` uses them)
void write_contacts_csv(std::ostream& out, const World& w, const ContactSet& c);

/// the ParaView collection DIR/snapshots/snapshots.pvd, kept valid after every added entry
class PvdFile {
 public:
  /// write the collection of `entries` (snapshots 0, 1, …) afresh (a resumed run rewrites
  /// what it keeps)
  void open(const std::string& path, const std::vector<SnapshotEntry>& entries);
  /// add snapshot k's .vtp at its time (the closing tags are rewritten after it)
  void add(const SnapshotEntry& e, long k);
  void close() { f_.close(); }

 private:
  std::string path_;
  std::fstream f_;
};

}  // namespace gs
