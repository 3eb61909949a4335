// H5MD 1.1 trajectory through libhdf5: one time-dependent group (step, time, value) per
// element, the step and time datasets hard-linked between them as H5MD allows
#include "output/particles/h5md.hpp"

#include <hdf5.h>

#include <array>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <utility>
#include <vector>

#include "core/error.hpp"
#include "view/render_world.hpp"

#ifndef GS_VERSION
#define GS_VERSION "unknown"
#endif

namespace gs {

static_assert(sizeof(hid_t) == sizeof(std::int64_t), "hid_t is kept as std::int64_t");

namespace {

// the time-dependent datasets, in the order of H5mdWriter::ds_
enum Ds { Step, Time, Edges, Position, Velocity, Theta, Omega, Contacts, Gravity, Tap, Count };
// where each lives ("" for step and time: they sit in the position group)
struct DsInfo {
  const char* path;
  int per_grain;  ///< 0: one value set per frame; else components per grain
  hid_t (*type)();
};
hid_t f64() { return H5T_NATIVE_DOUBLE; }
hid_t i64() { return H5T_NATIVE_INT64; }
hid_t i32() { return H5T_NATIVE_INT32; }
const DsInfo kDs[Count] = {
    {"/particles/all/position/step", 0, i64},   {"/particles/all/position/time", 0, f64},
    {"/particles/all/box/edges/value", 0, f64}, {"/particles/all/position/value", 3, f64},
    {"/particles/all/velocity/value", 3, f64},  {"/particles/all/theta/value", 1, f64},
    {"/particles/all/omega/value", 1, f64},     {"/particles/all/contacts/value", 1, i32},
    {"/observables/gravity/value", 0, f64},     {"/observables/tap/value", 0, i64},
};
// the per-frame shape after the frame axis (per-grain sets: N and the components)
std::vector<hsize_t> frame_shape(int ds, hsize_t n) {
  if (ds == Edges) return {3, 3};
  if (ds == Gravity) return {3};
  if (ds == Step || ds == Time || ds == Tap) return {};
  if (kDs[ds].per_grain == 3) return {n, 3};
  return {n};
}

[[noreturn]] void fail_out(const std::string& path, const std::string& what) {
  throw OutputError(path + ": " + what);
}

// an HDF5 handle closed at the end of its scope
struct Handle {
  hid_t id;
  herr_t (*closer)(hid_t);
  Handle(hid_t i, herr_t (*c)(hid_t)) : id(i), closer(c) {}
  Handle(const Handle&) = delete;
  Handle& operator=(const Handle&) = delete;
  ~Handle() {
    if (id >= 0) closer(id);
  }
  operator hid_t() const { return id; }
};

// no HDF5 error stack on stderr: every failure is reported once, as an OutputError/InputError
void quiet_hdf5() { H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr); }

void check(herr_t r, const std::string& path, const char* what) {
  if (r < 0) fail_out(path, std::string("HDF5 could not ") + what + " (disk full or removed?)");
}

Handle group(hid_t file, const char* name, const std::string& path) {
  Handle gcpl(H5Pcreate(H5P_GROUP_CREATE), H5Pclose);
  H5Pset_obj_track_times(gcpl, 0);  // no creation times: the same run gives the same bytes
  Handle g(H5Gcreate2(file, name, H5P_DEFAULT, gcpl, H5P_DEFAULT), H5Gclose);
  if (g < 0) fail_out(path, std::string("cannot create the group ") + name);
  return Handle(std::exchange(g.id, -1), H5Gclose);
}

// string attributes as variable-length UTF-8, which h5py reads as str (MDAnalysis compares
// the `unit` attributes with str)
Handle vlen_string_type() {
  Handle type(H5Tcopy(H5T_C_S1), H5Tclose);
  H5Tset_size(type, H5T_VARIABLE);
  H5Tset_cset(type, H5T_CSET_UTF8);
  return Handle(std::exchange(type.id, -1), H5Tclose);
}

void attr_strings(hid_t obj, const char* name, const std::vector<std::string>& values,
                  const std::string& path, bool scalar = false) {
  std::vector<const char*> ptr;
  for (const auto& v : values) ptr.push_back(v.c_str());
  Handle type = vlen_string_type();
  const hsize_t dims[1] = {values.size()};
  Handle space(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, dims, nullptr), H5Sclose);
  Handle a(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  check(a < 0 ? -1 : H5Awrite(a, type, ptr.data()), path, "write an attribute");
}

void attr_string(hid_t obj, const char* name, const std::string& value, const std::string& path) {
  attr_strings(obj, name, {value}, path, true);
}

template <class T>
void attr_ints(hid_t obj, const char* name, const std::vector<T>& v, hid_t type,
               const std::string& path) {
  const hsize_t dims[1] = {v.size()};
  Handle space(v.size() == 1 ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, dims, nullptr),
               H5Sclose);
  Handle a(H5Acreate2(obj, name, type, space, H5P_DEFAULT, H5P_DEFAULT), H5Aclose);
  check(a < 0 ? -1 : H5Awrite(a, type, v.data()), path, "write an attribute");
}

// a fixed-in-time dataset of one value per grain
template <class T>
void fixed(hid_t file, const char* name, hid_t type, const std::vector<T>& v, const char* unit,
           const std::string& path) {
  const hsize_t dims[1] = {v.size()};
  Handle space(H5Screate_simple(1, dims, nullptr), H5Sclose);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_obj_track_times(dcpl, 0);
  Handle d(H5Dcreate2(file, name, type, space, H5P_DEFAULT, dcpl, H5P_DEFAULT), H5Dclose);
  check(d < 0 ? -1 : H5Dwrite(d, type, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data()), path,
        "write a dataset");
  if (unit) attr_string(d, "unit", unit, path);
}

// an extensible time series: per-grain sets one frame a chunk, shuffled and deflated; the
// few numbers of a frame (step, time, box, gravity, tap) 512 frames a chunk, uncompressed, so
// that a chunk is allocated once and each flush rewrites it in place
void series(hid_t file, int ds, hsize_t n, const char* unit, const std::string& path) {
  const bool grains = kDs[ds].per_grain > 0;
  std::vector<hsize_t> dims{0}, max{H5S_UNLIMITED}, chunk{grains ? 1u : 512u};
  for (hsize_t d : frame_shape(ds, n)) {
    dims.push_back(d);
    max.push_back(d);
    chunk.push_back(std::max<hsize_t>(d, 1));
  }
  Handle space(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), max.data()), H5Sclose);
  Handle dcpl(H5Pcreate(H5P_DATASET_CREATE), H5Pclose);
  H5Pset_obj_track_times(dcpl, 0);
  H5Pset_chunk(dcpl, static_cast<int>(chunk.size()), chunk.data());
  if (grains) {
    H5Pset_shuffle(dcpl);
    H5Pset_deflate(dcpl, 4);
  }
  Handle d(H5Dcreate2(file, kDs[ds].path, kDs[ds].type(), space, H5P_DEFAULT, dcpl, H5P_DEFAULT),
           H5Dclose);
  if (d < 0) fail_out(path, std::string("cannot create ") + kDs[ds].path);
  if (unit) attr_string(d, "unit", unit, path);
}

// one time-dependent group: its value dataset, step and time linked from the position group
void element(hid_t file, const std::string& grp, int ds, hsize_t n, const char* unit,
             const std::string& path) {
  if (grp != "/particles/all/position") group(file, grp.c_str(), path);
  series(file, ds, n, unit, path);
  if (grp == "/particles/all/position") return;
  for (const char* k : {"step", "time"})
    check(H5Lcreate_hard(file, (std::string("/particles/all/position/") + k).c_str(), file,
                         (grp + "/" + k).c_str(), H5P_DEFAULT, H5P_DEFAULT),
          path, "link step and time");
}

// the grains' values in label order (as the extended XYZ and the VTP number them)
std::vector<std::size_t> label_order(const World& w) {
  const std::size_t n = w.size();
  const std::vector<std::uint32_t> slot = w.slots_by_id();
  std::vector<std::size_t> order(n);
  for (std::size_t label = 0; label < n; ++label)
    order[label] = slot.size() == n ? slot[label] : label;
  return order;
}

}  // namespace

H5mdWriter::~H5mdWriter() {
  try {
    close();
  } catch (...) {  // a destructor reports nothing; write() has flushed every frame already
  }
}

void H5mdWriter::close() {
  for (std::int64_t& d : ds_)
    if (d >= 0) H5Dclose(std::exchange(d, -1));
  if (file_ >= 0) H5Fclose(std::exchange(file_, -1));
}

void H5mdWriter::create(const std::string& path, const World& w) {
  close();
  quiet_hdf5();
  path_ = path;
  n_ = static_cast<std::int64_t>(w.size());
  frames_ = 0;
  file_ = H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  if (file_ < 0) fail_out(path, "cannot create the H5MD trajectory");
  const hid_t f = file_;
  {
    Handle h5md = group(f, "/h5md", path);
    attr_ints<int>(h5md, "version", {1, 1}, H5T_NATIVE_INT, path);
    Handle author = group(f, "/h5md/author", path);
    const char* user = std::getenv("USER");
    attr_string(author, "name", user && *user ? user : "unknown", path);
    Handle creator = group(f, "/h5md/creator", path);
    attr_string(creator, "name", "gransim", path);
    attr_string(creator, "version", GS_VERSION, path);
  }
  group(f, "/particles", path);
  group(f, "/particles/all", path);
  {
    Handle box = group(f, "/particles/all/box", path);
    attr_ints<int>(box, "dimension", {3}, H5T_NATIVE_INT, path);
    const bool px = w.box == BoxKind::Periodic || w.box == BoxKind::Ring1D;
    const bool py = w.box == BoxKind::Periodic;
    attr_strings(box, "boundary", {px ? "periodic" : "none", py ? "periodic" : "none", "none"},
                 path);
  }
  const hsize_t n = static_cast<hsize_t>(n_);
  group(f, "/particles/all/position", path);
  series(f, Step, n, nullptr, path);
  series(f, Time, n, "s", path);
  // lengths (m) carry no unit attribute: MDAnalysis refuses the files whose length unit it
  // lacks, and its table has no metre
  element(f, "/particles/all/position", Position, n, nullptr, path);
  element(f, "/particles/all/box/edges", Edges, n, nullptr, path);
  element(f, "/particles/all/velocity", Velocity, n, "m s-1", path);
  element(f, "/particles/all/theta", Theta, n, "rad", path);
  element(f, "/particles/all/omega", Omega, n, "rad s-1", path);
  element(f, "/particles/all/contacts", Contacts, n, nullptr, path);
  group(f, "/observables", path);
  element(f, "/observables/gravity", Gravity, n, "m s-2", path);
  element(f, "/observables/tap", Tap, n, nullptr, path);

  // fixed in time: species index (names in its attribute), radius, label, sides
  const std::vector<std::size_t> order = label_order(w);
  std::vector<int> species, sides;
  std::vector<double> radius;
  std::vector<std::int64_t> id;
  for (std::size_t label = 0; label < order.size(); ++label) {
    const std::size_t i = order[label];
    const Species& k = w.species[static_cast<std::size_t>(w.sp[i])];
    species.push_back(w.sp[i]);
    radius.push_back(w.radius[i]);
    id.push_back(static_cast<std::int64_t>(label));
    sides.push_back(k.shape == ShapeKind::Polygon ? k.sides : 0);
  }
  fixed(f, "/particles/all/species", H5T_NATIVE_INT, species, nullptr, path);
  {
    std::vector<std::string> names;
    for (const Species& k : w.species) names.push_back(k.name);
    Handle d(H5Dopen2(f, "/particles/all/species", H5P_DEFAULT), H5Dclose);
    attr_strings(d, "names", names, path);
  }
  fixed(f, "/particles/all/radius", H5T_NATIVE_DOUBLE, radius, nullptr, path);
  fixed(f, "/particles/all/id", H5T_NATIVE_INT64, id, nullptr, path);
  fixed(f, "/particles/all/sides", H5T_NATIVE_INT, sides, nullptr, path);
  open_datasets();
  check(H5Fflush(f, H5F_SCOPE_GLOBAL), path, "flush the file");
}

void H5mdWriter::open_datasets() {
  for (int k = 0; k < Count; ++k) {
    ds_[k] = H5Dopen2(file_, kDs[k].path, H5P_DEFAULT);
    if (ds_[k] < 0)
      throw InputError(path_, "", std::string("not a gransim H5MD trajectory: no ") + kDs[k].path);
  }
}

void H5mdWriter::reopen(const std::string& path, const World& w, std::int64_t frames) {
  close();
  quiet_hdf5();
  path_ = path;
  // a file a kill damaged inside a write: say how to go on without it
  const std::string aside =
      " (damaged, or not written by this run); move it aside and resume again to start a new "
      "one at the checkpoint";
  if (H5Fis_hdf5(path.c_str()) <= 0) throw InputError(path, "", "not an HDF5 file" + aside);
  file_ = H5Fopen(path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  if (file_ < 0)
    throw InputError(path, "", "cannot open the H5MD trajectory for appending" + aside);
  open_datasets();
  hsize_t dims[3] = {0, 0, 0};
  Handle space(H5Dget_space(ds_[Position]), H5Sclose);
  H5Sget_simple_extent_dims(space, dims, nullptr);
  n_ = static_cast<std::int64_t>(dims[1]);
  if (n_ != static_cast<std::int64_t>(w.size()))
    throw InputError(path, "",
                     "holds frames of " + std::to_string(n_) + " grains, the run has " +
                         std::to_string(w.size()));
  if (static_cast<std::int64_t>(dims[0]) < frames)
    throw InputError(path, "",
                     "holds " + std::to_string(dims[0]) + " frames, fewer than the " +
                         std::to_string(frames) + " of the checkpoint");
  if (frames < 0) frames = static_cast<std::int64_t>(dims[0]);
  // the frames after the checkpoint go
  for (int k = 0; k < Count; ++k) {
    std::vector<hsize_t> size{static_cast<hsize_t>(frames)};
    for (hsize_t d : frame_shape(k, static_cast<hsize_t>(n_))) size.push_back(d);
    check(H5Dset_extent(ds_[k], size.data()), path, "drop the frames after the checkpoint");
  }
  frames_ = frames;
  check(H5Fflush(file_, H5F_SCOPE_GLOBAL), path, "flush the file");
}

namespace {
// append one frame's values to a dataset at frame index f
void append(hid_t d, int ds, hsize_t f, hsize_t n, const void* data, const std::string& path) {
  const std::vector<hsize_t> shape = frame_shape(ds, n);
  std::vector<hsize_t> size{f + 1}, start{f}, count{1};
  for (hsize_t s : shape) {
    size.push_back(s);
    start.push_back(0);
    count.push_back(s);
  }
  check(H5Dset_extent(d, size.data()), path, "extend a dataset");
  Handle file_space(H5Dget_space(d), H5Sclose);
  H5Sselect_hyperslab(file_space, H5S_SELECT_SET, start.data(), nullptr, count.data(), nullptr);
  Handle mem(H5Screate_simple(static_cast<int>(count.size()), count.data(), nullptr), H5Sclose);
  hsize_t total = 1;
  for (hsize_t c : count) total *= c;
  const herr_t r = total == 0 ? 0 : H5Dwrite(d, kDs[ds].type(), mem, file_space, H5P_DEFAULT, data);
  check(r, path, "write a frame");
}
}  // namespace

void H5mdWriter::write(const World& w, const ContactSet* contacts, Vec2 gravity,
                       std::optional<long> tap) {
  if (file_ < 0) throw OutputError(path_ + ": the H5MD trajectory is closed");
  const std::size_t n = w.size();
  if (static_cast<std::int64_t>(n) != n_)
    throw OutputError(path_ + ": the number of grains changed from " + std::to_string(n_) + " to " +
                      std::to_string(n) + "; an H5MD trajectory keeps one number");
  const std::vector<std::size_t> order = label_order(w);
  const std::vector<double> z = contacts ? contact_counts(w, *contacts) : std::vector<double>(n);
  std::vector<double> pos(3 * n), vel(3 * n), th(n), om(n);
  std::vector<std::int32_t> cn(n);
  for (std::size_t label = 0; label < n; ++label) {
    const std::size_t i = order[label];
    pos[3 * label] = w.s.x[i];
    pos[3 * label + 1] = w.s.y[i];
    vel[3 * label] = w.s.vx[i];
    vel[3 * label + 1] = w.s.vy[i];
    th[label] = w.s.th[i];
    om[label] = w.s.omega[i];
    cn[label] = static_cast<std::int32_t>(z[i]);
  }
  const std::int64_t step = w.s.step, tp = tap ? *tap : -1;
  const double edges[9] = {w.Lx, 0, 0, 0, w.Ly, 0, 0, 0, 1};
  const double g[3] = {gravity.x, gravity.y, 0.0};
  const void* data[Count] = {&step,     &w.s.t,    edges,     pos.data(), vel.data(),
                             th.data(), om.data(), cn.data(), g,          &tp};
  const hsize_t f = static_cast<hsize_t>(frames_), nn = static_cast<hsize_t>(n);
  for (int k = 0; k < Count; ++k) append(ds_[k], k, f, nn, data[k], path_);
  // a frame on disk is a frame kept, whatever happens next
  check(H5Fflush(file_, H5F_SCOPE_GLOBAL), path_, "flush the file");
  ++frames_;
}

}  // namespace gs
