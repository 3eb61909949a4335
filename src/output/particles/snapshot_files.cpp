// writers of the snapshot files: VTK XML PolyData, the .pvd collection, the contact CSV
#include "output/particles/snapshot_files.hpp"

#include <zlib.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <ostream>
#include <type_traits>

#include "broadphase/broadphase.hpp"
#include "core/error.hpp"
#include "geometry/polygon.hpp"
#include "view/render_world.hpp"

namespace gs {

std::string snapshot_file(const char* stem, long k, const char* ext) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s_%06ld.%s", stem, k, ext);
  return buf;
}

namespace {

// a periodic coordinate brought into [0, L)
double wrap(double x, double L) { return x - L * std::floor(x / L); }

// RFC 4648 base64, as VTK's inline binary arrays are written
std::string base64(const unsigned char* p, std::size_t n) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((n + 2) / 3 * 4);
  for (std::size_t i = 0; i < n; i += 3) {
    const unsigned v = (unsigned{p[i]} << 16) | (i + 1 < n ? unsigned{p[i + 1]} << 8 : 0u) |
                       (i + 2 < n ? unsigned{p[i + 2]} : 0u);
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < n ? k[(v >> 6) & 63] : '=';
    out += i + 2 < n ? k[v & 63] : '=';
  }
  return out;
}

// the bytes of an array as vtkZLibDataCompressor writes them: a UInt64 header (blocks, block
// size, size of a partial last block or 0, compressed size of each block) and the deflated
// blocks, each part base64-encoded on its own
std::string zlib_blocks(const void* data, std::size_t bytes, const std::string& path) {
  constexpr std::size_t kBlock = std::size_t{1} << 15;
  const auto* in = static_cast<const unsigned char*>(data);
  const std::size_t blocks = (bytes + kBlock - 1) / kBlock;
  std::vector<std::uint64_t> header{blocks, kBlock, bytes % kBlock};
  std::vector<unsigned char> packed;
  std::vector<unsigned char> buf(compressBound(kBlock));
  for (std::size_t b = 0; b < blocks; ++b) {
    const std::size_t len = std::min(kBlock, bytes - b * kBlock);
    uLongf out_len = static_cast<uLongf>(buf.size());
    if (compress2(buf.data(), &out_len, in + b * kBlock, static_cast<uLong>(len),
                  Z_DEFAULT_COMPRESSION) != Z_OK)
      throw OutputError(path + ": zlib could not compress an array");
    header.push_back(out_len);
    packed.insert(packed.end(), buf.begin(), buf.begin() + static_cast<std::ptrdiff_t>(out_len));
  }
  return base64(reinterpret_cast<const unsigned char*>(header.data()),
                header.size() * sizeof(std::uint64_t)) +
         base64(packed.data(), packed.size());
}

template <class T>
constexpr const char* vtk_type() {
  if constexpr (std::is_same_v<T, double>) return "Float64";
  if constexpr (std::is_same_v<T, std::int64_t>) return "Int64";
  return "Int32";
}

// one <DataArray>: ASCII text (`rows` ends each line, e.g. one grain's outline) or zlib
// binary; `name` may be null
template <class T>
void data_array(std::ostream& out, const char* name, int comps, const std::vector<T>& v,
                bool binary, const std::string& path, const std::vector<std::size_t>& rows = {}) {
  out << "        <DataArray type=\"" << vtk_type<T>() << "\"";
  if (name) out << " Name=\"" << name << "\"";
  if (comps > 1) out << " NumberOfComponents=\"" << comps << "\"";
  out << " format=\"" << (binary ? "binary" : "ascii") << "\">\n         ";
  if (binary) {
    out << ' ' << zlib_blocks(v.data(), v.size() * sizeof(T), path);
  } else {
    std::size_t row = 0;
    for (std::size_t k = 0; k < v.size(); ++k) {
      out << ' ' << v[k];
      if (row < rows.size() && k + 1 == rows[row] && k + 1 < v.size()) {
        out << "\n         ";
        ++row;
      }
    }
  }
  out << "\n        </DataArray>\n";
}

}  // namespace

void write_vtp(const std::string& path, const World& w, const ContactSet& c, long tap,
               VtpEncoding enc) {
  const std::size_t n = w.size();
  const bool binary = enc == VtpEncoding::Binary;
  // cells in label order, as the XYZ and the contact CSV number the grains
  std::vector<std::size_t> order(n);
  const std::vector<std::uint32_t> slot = w.slots_by_id();
  for (std::size_t label = 0; label < n; ++label)
    order[label] = slot.size() == n ? slot[label] : label;
  const bool px = w.box == BoxKind::Periodic || w.box == BoxKind::Ring1D;
  const bool py = w.box == BoxKind::Periodic;
  // each grain's outline: the contact model's polygon placed at (x, θ), or a disk's many-gon
  std::vector<double> points;
  std::vector<std::int64_t> connectivity, offsets;
  std::vector<std::size_t> point_rows;  // where each grain's coordinates end
  for (std::size_t label = 0; label < n; ++label) {
    const std::size_t i = order[label];
    const Species& k = w.species[w.sp[i]];
    const Vec2 centre{px ? wrap(w.s.x[i], w.Lx) : w.s.x[i], py ? wrap(w.s.y[i], w.Ly) : w.s.y[i]};
    const Poly p = k.shape == ShapeKind::Polygon
                       ? place(k.body, centre, w.s.th[i])
                       : regular_polygon(kDiskOutlineVertices, w.radius[i], centre, w.s.th[i]);
    for (int v = 0; v < p.n; ++v) {
      connectivity.push_back(static_cast<std::int64_t>(points.size() / 3));
      points.insert(points.end(), {p[v].x, p[v].y, 0.0});
    }
    point_rows.push_back(points.size());
    offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
  }
  const std::vector<double> z = contact_counts(w, c);
  std::vector<std::int64_t> ids(n);
  std::vector<std::int32_t> species(n), sides(n), contacts(n);
  std::vector<double> radius(n), theta(n), velocity(3 * n), omega(n), speed(n);
  for (std::size_t label = 0; label < n; ++label) {
    const std::size_t i = order[label];
    const Species& k = w.species[w.sp[i]];
    ids[label] = static_cast<std::int64_t>(label);
    species[label] = w.sp[i];
    radius[label] = w.radius[i];
    sides[label] = k.shape == ShapeKind::Polygon ? k.sides : 0;
    theta[label] = w.s.th[i];
    velocity[3 * label] = w.s.vx[i];
    velocity[3 * label + 1] = w.s.vy[i];
    omega[label] = w.s.omega[i];
    speed[label] = std::hypot(w.s.vx[i], w.s.vy[i]);
    contacts[label] = static_cast<std::int32_t>(z[i]);
  }
  std::vector<std::size_t> conn_rows(offsets.begin(), offsets.end());

  std::ofstream out(path);
  if (!out) throw OutputError(path + ": cannot write the snapshot");
  out.precision(10);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\""
      << (binary ? " compressor=\"vtkZLibDataCompressor\"" : "") << ">\n  <PolyData>\n"
      << "    <FieldData>\n"
      << "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
         "format=\"ascii\">"
      << w.s.t << "</DataArray>\n"
      << "      <DataArray type=\"Int64\" Name=\"Step\" NumberOfTuples=\"1\" format=\"ascii\">"
      << w.s.step << "</DataArray>\n"
      << "      <DataArray type=\"Int64\" Name=\"Tap\" NumberOfTuples=\"1\" format=\"ascii\">"
      << tap << "</DataArray>\n    </FieldData>\n"
      << "    <Piece NumberOfPoints=\"" << points.size() / 3
      << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
      << "NumberOfStrips=\"0\" NumberOfPolys=\"" << n << "\">\n      <Points>\n";
  data_array(out, nullptr, 3, points, binary, path, point_rows);
  out << "      </Points>\n      <Polys>\n";
  data_array(out, "connectivity", 1, connectivity, binary, path, conn_rows);
  data_array(out, "offsets", 1, offsets, binary, path);
  out << "      </Polys>\n      <CellData Scalars=\"species\" Vectors=\"velocity\">\n";
  data_array(out, "id", 1, ids, binary, path);
  data_array(out, "species", 1, species, binary, path);
  data_array(out, "radius", 1, radius, binary, path);
  data_array(out, "sides", 1, sides, binary, path);
  data_array(out, "theta", 1, theta, binary, path);
  data_array(out, "velocity", 3, velocity, binary, path);
  data_array(out, "omega", 1, omega, binary, path);
  data_array(out, "speed", 1, speed, binary, path);
  data_array(out, "contacts", 1, contacts, binary, path);
  out << "      </CellData>\n    </Piece>\n  </PolyData>\n</VTKFile>\n";
  out.close();
  if (!out) throw OutputError(path + ": write failed (disk full or removed?)");
}

std::vector<std::string> contact_columns() {
  return {"i", "j", "wall", "x", "y", "nx", "ny", "fn", "ft", "fx", "fy", "overlap", "sliding"};
}

void write_contacts_csv(std::ostream& out, const World& w, const ContactSet& c) {
  const std::size_t n = w.size();
  const auto cols = contact_columns();
  for (std::size_t k = 0; k < cols.size(); ++k) out << (k ? "," : "") << cols[k];
  out << '\n';
  auto label = [&](std::size_t slot) -> long long {
    return w.id.size() == n ? w.id[slot] : static_cast<long long>(slot);
  };
  char buf[512];
  // full precision (as series.csv): the values are the records' own, bit for bit
  for (const ContactRecord& r : c.records) {
    const std::size_t i = key_i(r.key), j = key_j(r.key);
    if (i >= n) continue;
    const bool wall = j >= n;
    const Vec2 f = r.n * r.fn + perp(r.n) * r.ft;  // on j (or the wall), N
    // sliding: the tangential force sits on the Coulomb cap μ F_n (μ the pair's mean)
    const double mu_i = w.materials[w.species[w.sp[i]].material].mu;
    const double mu_j = w.materials[wall ? w.wall_material : w.species[w.sp[j]].material].mu;
    const double cap = 0.5 * (mu_i + mu_j) * std::max(r.fn, 0.0);
    const bool sliding = cap > 0.0 && std::abs(r.ft) >= cap * (1.0 - 1e-12);
    std::snprintf(buf, sizeof buf,
                  "%lld,%lld,%lld,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%.17g,%d\n",
                  label(i), wall ? -1LL : label(j), wall ? static_cast<long long>(j - n) : -1LL,
                  r.s.x, r.s.y, r.n.x, r.n.y, r.fn, r.ft, f.x, f.y, r.overlap, sliding ? 1 : 0);
    out << buf;
  }
}

// ---------------------------------------------------------------------------------------------
// the .pvd collection

namespace {

constexpr const char* kPvdHead =
    "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" "
    "byte_order=\"LittleEndian\">\n  <Collection>\n";
constexpr const char* kPvdTail = "  </Collection>\n</VTKFile>\n";

std::string pvd_line(const SnapshotEntry& e, long k) {
  char buf[160];
  std::snprintf(buf, sizeof buf, "    <DataSet timestep=\"%.10g\" part=\"0\" file=\"%s\"/>\n", e.t,
                snapshot_file("snap", k, "vtp").c_str());
  return buf;
}

}  // namespace

void PvdFile::open(const std::string& path, const std::vector<SnapshotEntry>& entries) {
  path_ = path;
  f_.close();
  {
    std::ofstream out(path, std::ios::trunc);
    out << kPvdHead;
    for (std::size_t k = 0; k < entries.size(); ++k)
      out << pvd_line(entries[k], static_cast<long>(k));
    out << kPvdTail;
    if (!out) throw OutputError(path + ": cannot write the snapshot collection");
  }
  f_.open(path, std::ios::in | std::ios::out);
  if (!f_) throw OutputError(path + ": cannot reopen the snapshot collection");
}

void PvdFile::add(const SnapshotEntry& e, long k) {
  // overwrite the closing tags with the new entry, then write them again
  const auto tail = static_cast<std::streamoff>(std::char_traits<char>::length(kPvdTail));
  f_.seekp(-tail, std::ios::end);
  f_ << pvd_line(e, k) << kPvdTail;
  f_.flush();
  if (!f_) throw OutputError(path_ + ": write failed (disk full or removed?)");
}

}  // namespace gs
