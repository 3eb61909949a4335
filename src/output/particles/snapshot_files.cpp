// writers of the snapshot files: VTK XML PolyData, the .pvd collection, the contact CSV
#include "output/particles/snapshot_files.hpp"

#include <cmath>
#include <cstdio>
#include <ostream>

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

// one <DataArray> of cell data, values from f(i) per particle slot in label order
template <class F>
void cell_array(std::ostream& out, const char* type, const char* name, int comps,
                const std::vector<std::size_t>& order, F&& f) {
  out << "        <DataArray type=\"" << type << "\" Name=\"" << name << "\" NumberOfComponents=\""
      << comps << "\" format=\"ascii\">\n         ";
  for (std::size_t i : order) out << ' ' << f(i);
  out << "\n        </DataArray>\n";
}

}  // namespace

void write_vtp(const std::string& path, const World& w, const ContactSet& c, long tap) {
  const std::size_t n = w.size();
  // cells in label order, as the XYZ and the contact CSV number the grains
  std::vector<std::size_t> order(n);
  const std::vector<std::uint32_t> slot = w.slots_by_id();
  for (std::size_t label = 0; label < n; ++label)
    order[label] = slot.size() == n ? slot[label] : label;
  const bool px = w.box == BoxKind::Periodic || w.box == BoxKind::Ring1D;
  const bool py = w.box == BoxKind::Periodic;
  // each grain's outline: the contact model's polygon placed at (x, θ), or a disk's many-gon
  std::vector<Poly> outline(n);
  std::size_t points = 0;
  for (std::size_t label = 0; label < n; ++label) {
    const std::size_t i = order[label];
    const Species& k = w.species[w.sp[i]];
    const Vec2 centre{px ? wrap(w.s.x[i], w.Lx) : w.s.x[i], py ? wrap(w.s.y[i], w.Ly) : w.s.y[i]};
    outline[label] = k.shape == ShapeKind::Polygon
                         ? place(k.body, centre, w.s.th[i])
                         : regular_polygon(kDiskOutlineVertices, w.radius[i], centre, w.s.th[i]);
    points += static_cast<std::size_t>(outline[label].n);
  }
  const std::vector<double> z = contact_counts(w, c);

  std::ofstream out(path);
  if (!out) throw OutputError(path + ": cannot write the snapshot");
  out.precision(10);
  out << "<?xml version=\"1.0\"?>\n"
      << "<VTKFile type=\"PolyData\" version=\"1.0\" byte_order=\"LittleEndian\" "
         "header_type=\"UInt64\">\n  <PolyData>\n    <FieldData>\n"
      << "      <DataArray type=\"Float64\" Name=\"TimeValue\" NumberOfTuples=\"1\" "
         "format=\"ascii\">"
      << w.s.t << "</DataArray>\n"
      << "      <DataArray type=\"Int64\" Name=\"Step\" NumberOfTuples=\"1\" format=\"ascii\">"
      << w.s.step << "</DataArray>\n"
      << "      <DataArray type=\"Int64\" Name=\"Tap\" NumberOfTuples=\"1\" format=\"ascii\">"
      << tap << "</DataArray>\n    </FieldData>\n"
      << "    <Piece NumberOfPoints=\"" << points << "\" NumberOfVerts=\"0\" NumberOfLines=\"0\" "
      << "NumberOfStrips=\"0\" NumberOfPolys=\"" << n << "\">\n"
      << "      <Points>\n        <DataArray type=\"Float64\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n";
  for (const Poly& p : outline) {
    out << "         ";
    for (int v = 0; v < p.n; ++v) out << ' ' << p[v].x << ' ' << p[v].y << " 0";
    out << '\n';
  }
  out << "        </DataArray>\n      </Points>\n      <Polys>\n"
      << "        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
  std::size_t next = 0;
  for (const Poly& p : outline) {
    out << "         ";
    for (int v = 0; v < p.n; ++v) out << ' ' << next++;
    out << '\n';
  }
  out << "        </DataArray>\n"
      << "        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n         ";
  next = 0;
  for (const Poly& p : outline) out << ' ' << (next += static_cast<std::size_t>(p.n));
  out << "\n        </DataArray>\n      </Polys>\n      <CellData Scalars=\"species\" "
         "Vectors=\"velocity\">\n";
  std::vector<std::size_t> labels(n);
  for (std::size_t label = 0; label < n; ++label) labels[label] = label;
  cell_array(out, "Int64", "id", 1, labels, [](std::size_t label) { return label; });
  cell_array(out, "Int32", "species", 1, order, [&](std::size_t i) { return w.sp[i]; });
  cell_array(out, "Float64", "radius", 1, order, [&](std::size_t i) { return w.radius[i]; });
  cell_array(out, "Int32", "sides", 1, order, [&](std::size_t i) {
    const Species& k = w.species[w.sp[i]];
    return k.shape == ShapeKind::Polygon ? k.sides : 0;
  });
  cell_array(out, "Float64", "theta", 1, order, [&](std::size_t i) { return w.s.th[i]; });
  out << "        <DataArray type=\"Float64\" Name=\"velocity\" NumberOfComponents=\"3\" "
         "format=\"ascii\">\n         ";
  for (std::size_t i : order) out << ' ' << w.s.vx[i] << ' ' << w.s.vy[i] << " 0";
  out << "\n        </DataArray>\n";
  cell_array(out, "Float64", "omega", 1, order, [&](std::size_t i) { return w.s.omega[i]; });
  cell_array(out, "Float64", "speed", 1, order,
             [&](std::size_t i) { return std::hypot(w.s.vx[i], w.s.vy[i]); });
  cell_array(out, "Int32", "contacts", 1, order,
             [&](std::size_t i) { return static_cast<int>(z[i]); });
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
