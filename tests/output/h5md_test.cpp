// the H5MD trajectory writer: what it writes reads back bit for bit through libhdf5 (values,
// time, step, box, fixed-in-time data, the H5MD attributes), and a reopened file keeps exactly
// the frames asked for before new ones follow
#include "output/particles/h5md.hpp"

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "core/error.hpp"
#include "scene/parse.hpp"
#include "world/prepare.hpp"

namespace gs {
namespace {

namespace fs = std::filesystem;

// three grains of two species (a heptagon and two disks) in a periodic box
const char* kScene = R"(
[[species]]
name = "hept"
radius = 0.006
sides = 7

[[species]]
name = "disk"
radius = 0.004

[box]
kind = "periodic"
width = 0.2
height = 0.3

[[preparation.particle]]
species = "hept"
x = 0.05
y = 0.1
theta = 0.3
vx = 0.25

[[preparation.particle]]
species = "disk"
x = 0.1
y = 0.15
vy = -0.5
omega = 2.0

[[preparation.particle]]
species = "disk"
x = 0.15
y = 0.2
)";

World world() {
  const SceneSpec s = parse_scene_string(kScene, "t.toml", {});
  World w = make_world(s);
  place_particles(w, s);
  return w;
}

fs::path temp(const std::string& name) {
  return fs::temp_directory_path() / ("gs_h5md_" + std::to_string(::getpid()) + "_" + name);
}

// a whole dataset of doubles / int64s
std::vector<double> doubles(hid_t f, const char* name, std::vector<hsize_t>* shape = nullptr) {
  const hid_t d = H5Dopen2(f, name, H5P_DEFAULT);
  EXPECT_GE(d, 0) << name;
  const hid_t s = H5Dget_space(d);
  hsize_t dims[4] = {1, 1, 1, 1};
  const int rank = H5Sget_simple_extent_dims(s, dims, nullptr);
  std::size_t n = 1;
  for (int k = 0; k < rank; ++k) n *= dims[k];
  if (shape) shape->assign(dims, dims + rank);
  std::vector<double> v(n);
  if (n) H5Dread(d, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, v.data());
  H5Sclose(s);
  H5Dclose(d);
  return v;
}

// the state that frame k writes: the world moved by k steps of a made-up motion
void advance(World& w, int k) {
  for (std::size_t i = 0; i < w.size(); ++i) {
    w.s.x[i] += 1e-3 * k + 1e-9 * static_cast<double>(i);
    w.s.vy[i] -= 0.01 * k;
    w.s.th[i] += 0.1 * k;
    w.s.omega[i] = 0.5 * k - static_cast<double>(i);
  }
  w.s.step = 100 * k;
  w.s.t = 1e-4 * 100 * k;
}

TEST(H5md, FramesReadBackExactlyWithTheH5mdLayout) {
  const fs::path path = temp("frames.h5md");
  World w = world();
  std::vector<World> states;
  {
    H5mdWriter h5;
    h5.create(path.string(), w);
    for (int k = 0; k < 3; ++k) {
      advance(w, k);
      states.push_back(w);
      h5.write(w, nullptr, {0.0, -9.81 * (k + 1)}, k == 1 ? std::optional<long>(4) : std::nullopt);
    }
    EXPECT_EQ(h5.frames(), 3);
  }
  const hid_t f = H5Fopen(path.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  std::vector<hsize_t> shape;
  const auto pos = doubles(f, "/particles/all/position/value", &shape);
  ASSERT_EQ(shape, (std::vector<hsize_t>{3, 3, 3}));
  const auto vel = doubles(f, "/particles/all/velocity/value");
  const auto th = doubles(f, "/particles/all/theta/value");
  const auto om = doubles(f, "/particles/all/omega/value");
  const auto time = doubles(f, "/particles/all/position/time");
  const auto step = doubles(f, "/particles/all/position/step");
  const auto vel_time = doubles(f, "/particles/all/velocity/time");  // the hard link
  const auto box = doubles(f, "/particles/all/box/edges/value", &shape);
  ASSERT_EQ(shape, (std::vector<hsize_t>{3, 3, 3}));
  const auto g = doubles(f, "/observables/gravity/value");
  const auto tap = doubles(f, "/observables/tap/value");
  for (int k = 0; k < 3; ++k) {
    const World& s = states[static_cast<std::size_t>(k)];
    EXPECT_EQ(time[k], s.s.t);
    EXPECT_EQ(vel_time[k], s.s.t);
    EXPECT_EQ(step[k], static_cast<double>(s.s.step));
    EXPECT_EQ(box[9 * k], 0.2);
    EXPECT_EQ(box[9 * k + 4], 0.3);
    EXPECT_EQ(box[9 * k + 8], 1.0);
    EXPECT_EQ(g[3 * k + 1], -9.81 * (k + 1));
    EXPECT_EQ(tap[k], k == 1 ? 4.0 : -1.0);
    const std::vector<std::uint32_t> slot = s.slots_by_id();
    for (std::size_t label = 0; label < 3; ++label) {
      const std::size_t i = slot.size() == 3 ? slot[label] : label;
      const std::size_t at = 9 * k + 3 * label;
      EXPECT_EQ(pos[at], s.s.x[i]);
      EXPECT_EQ(pos[at + 1], s.s.y[i]);
      EXPECT_EQ(pos[at + 2], 0.0);
      EXPECT_EQ(vel[at], s.s.vx[i]);
      EXPECT_EQ(vel[at + 1], s.s.vy[i]);
      EXPECT_EQ(th[3 * k + label], s.s.th[i]);
      EXPECT_EQ(om[3 * k + label], s.s.omega[i]);
    }
  }
  // fixed in time: species indices and radii per label
  const auto species = doubles(f, "/particles/all/species");
  const auto radius = doubles(f, "/particles/all/radius");
  EXPECT_EQ(species, (std::vector<double>{0, 1, 1}));
  EXPECT_EQ(radius[1], 0.004);
  // the H5MD attributes: version 1.1, a three-dimensional box periodic in x and y (the slab's
  // thickness is not)
  int version[2] = {0, 0};
  const hid_t h5md = H5Gopen2(f, "/h5md", H5P_DEFAULT);
  const hid_t va = H5Aopen(h5md, "version", H5P_DEFAULT);
  H5Aread(va, H5T_NATIVE_INT, version);
  EXPECT_EQ(version[0], 1);
  EXPECT_EQ(version[1], 1);
  EXPECT_GT(H5Lexists(f, "/h5md/creator", H5P_DEFAULT), 0);
  EXPECT_GT(H5Lexists(f, "/h5md/author", H5P_DEFAULT), 0);
  const hid_t boxg = H5Gopen2(f, "/particles/all/box", H5P_DEFAULT);
  int dim = 0;
  const hid_t da = H5Aopen(boxg, "dimension", H5P_DEFAULT);
  H5Aread(da, H5T_NATIVE_INT, &dim);
  EXPECT_EQ(dim, 3);
  // variable-length strings (h5py reads them as str)
  const hid_t ba = H5Aopen(boxg, "boundary", H5P_DEFAULT);
  const hid_t bt = H5Aget_type(ba);
  EXPECT_TRUE(H5Tis_variable_str(bt) > 0);
  char* b[3] = {nullptr, nullptr, nullptr};
  H5Aread(ba, bt, b);
  EXPECT_STREQ(b[0], "periodic");
  EXPECT_STREQ(b[1], "periodic");
  EXPECT_STREQ(b[2], "none");
  for (char* p : b) H5free_memory(p);
  for (hid_t a : {va, da, ba}) H5Aclose(a);
  H5Tclose(bt);
  H5Gclose(boxg);
  H5Gclose(h5md);
  // chunked and deflated
  const hid_t d = H5Dopen2(f, "/particles/all/position/value", H5P_DEFAULT);
  const hid_t dcpl = H5Dget_create_plist(d);
  EXPECT_EQ(H5Pget_layout(dcpl), H5D_CHUNKED);
  bool deflate = false;
  for (int k = 0; k < H5Pget_nfilters(dcpl); ++k) {
    unsigned flags = 0;
    std::size_t n = 0;
    deflate |= H5Pget_filter2(dcpl, static_cast<unsigned>(k), &flags, &n, nullptr, 0, nullptr,
                              nullptr) == H5Z_FILTER_DEFLATE;
  }
  EXPECT_TRUE(deflate);
  H5Pclose(dcpl);
  H5Dclose(d);
  H5Fclose(f);
  fs::remove(path);
}

TEST(H5md, ReopenKeepsTheFramesAskedForThenAppends) {
  const fs::path path = temp("reopen.h5md");
  World w = world();
  {
    H5mdWriter h5;
    h5.create(path.string(), w);
    for (int k = 0; k < 4; ++k) {
      advance(w, k);
      h5.write(w, nullptr, {0.0, -9.81}, std::nullopt);
    }
  }
  {
    H5mdWriter h5;
    h5.reopen(path.string(), w, 2);  // frames 2 and 3 were written after the "checkpoint"
    EXPECT_EQ(h5.frames(), 2);
    w.s.step = 777;
    w.s.t = 0.0777;
    h5.write(w, nullptr, {0.0, -9.81}, std::nullopt);
    EXPECT_EQ(h5.frames(), 3);
  }
  const hid_t f = H5Fopen(path.string().c_str(), H5F_ACC_RDONLY, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  std::vector<hsize_t> shape;
  const auto step = doubles(f, "/particles/all/position/step");
  EXPECT_EQ(step, (std::vector<double>{0, 100, 777}));
  const auto vel_step = doubles(f, "/particles/all/velocity/step");
  EXPECT_EQ(vel_step, step);
  doubles(f, "/particles/all/omega/value", &shape);
  EXPECT_EQ(shape, (std::vector<hsize_t>{3, 3}));
  doubles(f, "/observables/tap/value", &shape);
  EXPECT_EQ(shape, (std::vector<hsize_t>{3}));
  H5Fclose(f);

  // a checkpoint that counts more frames than the file holds, another number of grains, a
  // file that is not HDF5: refused with the file named
  H5mdWriter h5;
  EXPECT_THROW(h5.reopen(path.string(), w, 9), InputError);
  World fewer = world();
  fewer.clear_particles();
  try {
    h5.reopen(path.string(), fewer, 1);
    ADD_FAILURE() << "another number of grains was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("3 grains"), std::string::npos) << e.what();
  }
  const fs::path text = temp("not.h5md");
  std::ofstream(text) << "not HDF5\n";
  EXPECT_THROW(h5.reopen(text.string(), w, 0), InputError);
  EXPECT_THROW(h5.write(w, nullptr, {0, 0}, std::nullopt), OutputError);
  fs::remove(path);
  fs::remove(text);
}

}  // namespace
}  // namespace gs
