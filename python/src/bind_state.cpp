// a state that can be set from Python: positions, velocities, orientations and angular
// velocities (checked, then the simulation restarts from them), snapshots as dicts of copies,
// checkpoints written and read back, and the snapshot and trajectory files of a run
#include <pybind11/stl.h>

#include <cmath>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

#include "bindings.hpp"
#include "core/bytes.hpp"
#include "core/error.hpp"
#include "drive/schedule.hpp"
#include "output/particles/h5md.hpp"
#include "output/particles/snapshot_files.hpp"
#include "output/particles/trajectory.hpp"
#include "sim/checkpoint.hpp"

namespace gs::py_bind {

namespace {

using Column = py::array_t<double, py::array::c_style | py::array::forcecast>;

// an N×2 array (or a list of pairs) of finite numbers, for `what` (positions, velocities)
std::vector<Vec2> pairs_of(const py::object& value, std::size_t n, const char* what,
                           const char* unit) {
  const auto a = value.cast<Column>();
  if (a.ndim() != 2 || a.shape(1) != 2 || static_cast<std::size_t>(a.shape(0)) != n)
    throw InputError("Simulation", what,
                     std::string("must be an N×2 array with N = ") + std::to_string(n) +
                         " (one row (x, y) in " + unit + " per particle)");
  const auto v = a.unchecked<2>();
  std::vector<Vec2> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = {v(i, 0), v(i, 1)};
    if (!std::isfinite(out[i].x) || !std::isfinite(out[i].y))
      throw InputError("Simulation", what,
                       "row " + std::to_string(i) + " is not finite (" + std::to_string(out[i].x) +
                           ", " + std::to_string(out[i].y) + ")");
  }
  return out;
}

// a length-N array of finite numbers, for `what` (theta, omega)
std::vector<double> column_of(const py::object& value, std::size_t n, const char* what,
                              const char* unit) {
  const auto a = value.cast<Column>();
  if (a.ndim() != 1 || static_cast<std::size_t>(a.shape(0)) != n)
    throw InputError(
        "Simulation", what,
        std::string("must be a 1-D array of N = ") + std::to_string(n) + " values in " + unit);
  const auto v = a.unchecked<1>();
  std::vector<double> out(n);
  for (std::size_t i = 0; i < n; ++i) {
    out[i] = v(i);
    if (!std::isfinite(out[i]))
      throw InputError("Simulation", what, "entry " + std::to_string(i) + " is not finite");
  }
  return out;
}

// set what is given (None: kept), each checked before anything changes, then restart the
// simulation from the new state; the World's arrays stay in place, so views remain valid
void set_state(PySim& s, const py::object& positions, const py::object& velocities,
               const py::object& theta, const py::object& omega) {
  World& w = s.sim->world();
  const std::size_t n = w.size();
  std::optional<std::vector<Vec2>> pos, vel;
  std::optional<std::vector<double>> th, om;
  if (!positions.is_none()) pos = pairs_of(positions, n, "positions", "m");
  if (!velocities.is_none()) vel = pairs_of(velocities, n, "velocities", "m/s");
  if (!theta.is_none()) th = column_of(theta, n, "theta", "rad");
  if (!omega.is_none()) om = column_of(omega, n, "omega", "rad/s");
  // a walled box holds every centre (a periodic box or a ring takes any position)
  const BoxSpec& box = s.scene.box;
  if (pos && box.kind == BoxKind::Walls)
    for (std::size_t i = 0; i < n; ++i) {
      const Vec2 p = (*pos)[i];
      if (!(p.x >= 0.0 && p.x <= box.width && p.y >= 0.0 && (!box.lid || p.y <= box.height)))
        throw InputError("Simulation", "positions",
                         "particle " + std::to_string(i) + " at (" + std::to_string(p.x) + ", " +
                             std::to_string(p.y) + ") m is outside the box [0, " +
                             std::to_string(box.width) + "] × [0, " +
                             (box.lid ? std::to_string(box.height) + "]" : std::string("∞)")) +
                             " m");
    }
  // without rotation (frictionless disks) ω is never integrated: a spin would be silently lost
  if (om && !w.rotation)
    for (std::size_t i = 0; i < n; ++i)
      if ((*om)[i] != 0.0)
        throw InputError("Simulation", "omega",
                         "this scene does not integrate rotation (no torques can arise); "
                         "angular velocities must stay 0");
  State& st = w.s;
  for (std::size_t i = 0; i < n; ++i) {
    if (pos) {
      st.x[i] = (*pos)[i].x;
      st.y[i] = (*pos)[i].y;
      st.wrap_x[i] = st.wrap_y[i] = 0;
    }
    if (vel) {
      st.vx[i] = (*vel)[i].x;
      st.vy[i] = (*vel)[i].y;
    }
    if (th) st.th[i] = (*th)[i];
    if (om) st.omega[i] = (*om)[i];
  }
  if (pos) w.rewrap();
  s.sim->restart_from_state();
}

template <class T>
py::array_t<T> copy_of(const std::vector<T>& v) {
  return py::array_t<T>(static_cast<py::ssize_t>(v.size()), v.data());
}

py::dict snapshot_of(const PySim& s) {
  const World& w = s.sim->world();
  py::dict d;
  d["t"] = w.s.t;
  d["step"] = w.s.step;
  d["box"] = py::make_tuple(w.Lx, w.Ly);
  d["periodic"] = w.box != BoxKind::Walls;
  d["positions"] = pairs(w.s.x, w.s.y);
  d["velocities"] = pairs(w.s.vx, w.s.vy);
  d["theta"] = copy_of(w.s.th);
  d["omega"] = copy_of(w.s.omega);
  d["species"] = copy_of(w.sp);
  d["ids"] = copy_of(w.id);
  d["radius"] = copy_of(w.radius);
  d["mass"] = copy_of(w.mass);
  std::vector<std::string> names;
  for (const Species& sp : w.species) names.push_back(sp.name);
  d["species_names"] = names;
  return d;
}

// a snapshot's grains must be this simulation's (same count, species and labels, slot by slot)
void set_snapshot(PySim& s, const py::dict& snap) {
  const World& w = s.sim->world();
  auto same = [&](const char* key, const auto& mine) {
    if (!snap.contains(key)) return;
    using T = typename std::decay_t<decltype(mine)>::value_type;
    const auto a = snap[key].cast<py::array_t<T, py::array::forcecast>>();
    bool ok = a.ndim() == 1 && static_cast<std::size_t>(a.shape(0)) == mine.size();
    for (std::size_t i = 0; ok && i < mine.size(); ++i) ok = a.at(i) == mine[i];
    if (!ok)
      throw InputError("set_snapshot", key,
                       std::string("differs from this simulation's '") + key +
                           "': a snapshot sets the state of the same grains (slot by slot)");
  };
  same("species", w.sp);
  same("ids", w.id);
  for (const char* key : {"t", "step"})
    if (snap.contains(key)) {
      const double v = snap[key].cast<double>();
      const double mine = std::string(key) == "t" ? w.s.t : static_cast<double>(w.s.step);
      if (v != mine)
        throw InputError("set_snapshot", key,
                         std::string("the snapshot's ") + key + " is " + std::to_string(v) +
                             ", this simulation's " + std::to_string(mine) +
                             ": the clock is not set from a snapshot (from_checkpoint restores "
                             "a whole run); drop the key to set the grains at this time");
    }
  auto get = [&](const char* key) {
    return snap.contains(key) ? snap[key] : py::object(py::none());
  };
  set_state(s, get("positions"), get("velocities"), get("theta"), get("omega"));
}

// the checkpoint extras the run loop writes for its protocol clock, so that `gransim run`'s
// checkpoints and these read each other; the health check's energy yardstick beside it
constexpr const char* kClockEntry = "run/clock";
constexpr const char* kYardstickEntry = "sim/energy_yardstick";

void save(const PySim& s, const std::string& path) {
  CheckpointExtras ex;
  ByteWriter clock;
  s.clock->save(clock);
  ex.entries[kClockEntry] = clock.out;
  ByteWriter energy;
  const auto [ref, slack] = s.sim->energy_yardstick();
  energy.f64(ref);
  energy.f64(slack);
  ex.entries[kYardstickEntry] = energy.out;
  write_checkpoint(*s.sim, s.scene, ex, path);
}

long tap_now(const PySim& s) {
  const World& w = s.sim->world();
  const DrivePhase p = drive_phase(s.sim->settings().drive, w.clock_origin, w.s.t + s.sim->dt());
  return p.settling ? -1L : p.tap;
}

// `path` for writing: OutputError naming it when it cannot be opened
std::ofstream open_for_writing(const std::string& path, std::ios::openmode mode) {
  std::ofstream f(path, mode);
  if (!f) throw OutputError(path + ": cannot open for writing");
  return f;
}

void write_snapshot(const PySim& s, const std::string& path) {
  const World& w = s.sim->world();
  const auto dot = path.rfind('.');
  const std::string ext = dot == std::string::npos ? "" : path.substr(dot);
  const long tap = tap_now(s);
  if (ext == ".vtp") {
    write_vtp(path, w, s.sim->contacts(), tap);
  } else if (ext == ".xyz") {
    auto f = open_for_writing(path, std::ios::trunc);
    write_trajectory_frame(f, w, &s.sim->contacts(), s.sim->gravity(),
                           tap >= 0 ? std::optional<long>(tap) : std::nullopt);
    if (!f.flush()) throw OutputError(path + ": write failed");
  } else if (ext == ".csv") {
    auto f = open_for_writing(path, std::ios::trunc);
    write_contacts_csv(f, w, s.sim->contacts());
    if (!f.flush()) throw OutputError(path + ": write failed");
  } else {
    throw InputError("write_snapshot", "path",
                     "'" + path +
                         "': the extension names the format: .vtp (VTK PolyData: "
                         "outlines, ParaView), .xyz (extended XYZ: ASE, OVITO) or .csv (contacts)");
  }
}

/// an extended-XYZ trajectory written frame by frame (the run's trajectory.xyz format)
struct TrajectoryWriter {
  std::string path;
  std::ofstream out;
  long frames = 0;
  TrajectoryWriter(const std::string& p, bool append)
      : path(p), out(open_for_writing(p, append ? std::ios::app : std::ios::trunc)) {}
  void write(const PySim& s) {
    if (!out.is_open()) throw OutputError(path + ": the trajectory is closed");
    const long tap = tap_now(s);
    write_trajectory_frame(out, s.sim->world(), &s.sim->contacts(), s.sim->gravity(),
                           tap >= 0 ? std::optional<long>(tap) : std::nullopt);
    if (!out.flush()) throw OutputError(path + ": write failed (disk full?)");
    ++frames;
  }
};

/// an H5MD trajectory (HDF5: h5py, MDAnalysis) written frame by frame (the run's
/// trajectory.h5md format); the file is made at the first frame, when the grains are known
struct H5mdTrajectoryWriter {
  std::string path;
  bool append = false;
  H5mdWriter h5;
  bool closed = false;
  H5mdTrajectoryWriter(const std::string& p, bool a) : path(p), append(a) {}
  void write(const PySim& s) {
    if (closed) throw OutputError(path + ": the trajectory is closed");
    const World& w = s.sim->world();
    if (!h5.is_open()) {
      std::ifstream exists(path);
      if (append && exists.good())
        h5.reopen(path, w, -1);
      else
        h5.create(path, w);
    }
    const long tap = tap_now(s);
    h5.write(w, &s.sim->contacts(), s.sim->gravity(),
             tap >= 0 ? std::optional<long>(tap) : std::nullopt);
  }
  void close() {
    h5.close();
    closed = true;
  }
};

}  // namespace

PySim::PySim(const Checkpoint& c) : scene(checkpoint_scene(c)) {
  sim = std::make_unique<Simulation>(restore_simulation(c));
  clock = std::make_unique<ProtocolClock>(scene);
  const auto it = c.extras.entries.find(kClockEntry);
  if (it != c.extras.entries.end()) {
    ByteReader r{it->second, 0, c.path + " [" + kClockEntry + "]"};
    clock->load(r);
  }
  const auto e = c.extras.entries.find(kYardstickEntry);
  if (e != c.extras.entries.end()) {
    ByteReader r{e->second, 0, c.path + " [" + kYardstickEntry + "]"};
    const double ref = r.f64("energy reference");
    sim->set_energy_yardstick(ref, r.f64("energy slack"));
  }
}

void bind_state(py::module_& m) {
  py::class_<Checkpoint>(m, "Checkpoint", "a checkpoint's contents (opaque)")
      .def_readonly("path", &Checkpoint::path);
  m.def("read_checkpoint", &read_checkpoint, py::arg("path"),
        "a checkpoint file read and checked (for Simulation.from_checkpoint)");

  auto cls = py::reinterpret_borrow<py::class_<PySim>>(m.attr("Simulation"));
  cls.def(py::init<const Checkpoint&>(), py::arg("checkpoint"))
      .def("set_state", &set_state, py::arg("positions") = py::none(),
           py::arg("velocities") = py::none(), py::arg("theta") = py::none(),
           py::arg("omega") = py::none(),
           "set positions (N×2, m), velocities (N×2, m/s), orientations theta (N, rad) and "
           "angular velocities omega (N, rad/s); None keeps one. Checked first (shape, finite, "
           "inside a walled box, no spin where rotation is not integrated); then the run "
           "continues from this state as a new simulation would (contacts afresh, the "
           "integrator's history restarted); views stay valid")
      .def("get_snapshot", &snapshot_of,
           "the state as a dict of copies: t (s), step, box (m), periodic, positions, velocities, "
           "theta, omega, species, ids, radius, mass, species_names")
      .def("set_snapshot", &set_snapshot, py::arg("snapshot"),
           "set the grains' state from a get_snapshot() dict (positions, velocities, theta, "
           "omega; species and ids, when present, must be this simulation's)")
      .def("save", &save, py::arg("path"),
           "write a checkpoint (the complete state, integrator history and contact springs, the "
           "protocol clock): Simulation.from_checkpoint(path) continues bitwise")
      .def("write_snapshot", &write_snapshot, py::arg("path"),
           "write the configuration now: .vtp (VTK PolyData with outlines, ParaView), .xyz "
           "(one extended-XYZ frame: ASE, OVITO) or .csv (one row per contact)");

  py::class_<TrajectoryWriter>(m, "TrajectoryWriter",
                               "an extended-XYZ trajectory (ASE, OVITO) written frame by frame")
      .def(py::init<const std::string&, bool>(), py::arg("path"), py::arg("append") = false)
      .def("write", &TrajectoryWriter::write, py::arg("sim"), "append the simulation's frame now")
      .def("close", [](TrajectoryWriter& t) { t.out.close(); })
      .def_readonly("path", &TrajectoryWriter::path)
      .def_readonly("frames", &TrajectoryWriter::frames, "frames written")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](TrajectoryWriter& t, const py::args&) { t.out.close(); });

  py::class_<H5mdTrajectoryWriter>(
      m, "H5mdTrajectoryWriter",
      "an H5MD trajectory (HDF5: h5py, MDAnalysis) written frame by frame; each frame is on "
      "disk when write() returns")
      .def(py::init<const std::string&, bool>(), py::arg("path"), py::arg("append") = false)
      .def("write", &H5mdTrajectoryWriter::write, py::arg("sim"),
           "append the simulation's frame now (the first frame fixes the number of grains)")
      .def("close", &H5mdTrajectoryWriter::close)
      .def_readonly("path", &H5mdTrajectoryWriter::path)
      .def_property_readonly(
          "frames", [](const H5mdTrajectoryWriter& t) { return t.h5.frames(); },
          "frames in the file")
      .def("__enter__", [](py::object self) { return self; })
      .def("__exit__", [](H5mdTrajectoryWriter& t, const py::args&) { t.close(); });
}

}  // namespace gs::py_bind
