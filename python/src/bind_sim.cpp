// scenes, the simulation and its state as NumPy arrays (views onto the World's structure of
// arrays where the layout allows), contacts and the per-tap measurement
#include <pybind11/stl.h>

#include <cmath>
#include <stdexcept>
#include <string>

#include "arguments.hpp"
#include "bindings.hpp"
#include "core/error.hpp"
#include "drive/schedule.hpp"
#include "measure/packing.hpp"
#include "measure/tap_measure.hpp"
#include "scene/names.hpp"
#include "scene/parse.hpp"
#include "sim/prepare.hpp"

namespace gs::py_bind {

namespace {

// steps run between two looks for Ctrl-C (the GIL is released in between)
constexpr std::int64_t kSignalEvery = 512;

/// a read-only 1-D view of a vector, keeping `owner` (the Python Simulation) alive
template <class T>
py::array view(const py::object& owner, const std::vector<T>& v) {
  py::array_t<T> a({static_cast<py::ssize_t>(v.size())}, {static_cast<py::ssize_t>(sizeof(T))},
                   v.data(), owner);
  a.attr("setflags")(py::arg("write") = false);
  return a;
}

py::dict contacts_dict(const Simulation& sim) {
  const ContactSet& cs = sim.contacts();
  const auto n = static_cast<py::ssize_t>(cs.records.size());
  const auto np = static_cast<std::uint32_t>(sim.world().size());
  py::array_t<std::int64_t> i({n}), j({n}), wall({n});
  py::array_t<double> point({n, py::ssize_t{2}}), normal({n, py::ssize_t{2}}), fn({n}), ft({n}),
      overlap({n});
  auto I = i.mutable_unchecked<1>(), J = j.mutable_unchecked<1>(), W = wall.mutable_unchecked<1>();
  auto P = point.mutable_unchecked<2>(), N = normal.mutable_unchecked<2>();
  auto FN = fn.mutable_unchecked<1>(), FT = ft.mutable_unchecked<1>(),
       O = overlap.mutable_unchecked<1>();
  for (py::ssize_t k = 0; k < n; ++k) {
    const ContactRecord& r = cs.records[static_cast<std::size_t>(k)];
    const std::uint32_t kj = key_j(r.key);
    I(k) = key_i(r.key);
    J(k) = kj < np ? static_cast<std::int64_t>(kj) : -1;
    W(k) = kj < np ? -1 : static_cast<std::int64_t>(kj - np);
    P(k, 0) = r.s.x;
    P(k, 1) = r.s.y;
    N(k, 0) = r.n.x;
    N(k, 1) = r.n.y;
    FN(k) = r.fn;
    FT(k) = r.ft;
    O(k) = r.overlap;
  }
  py::dict d;
  d["i"] = i;
  d["j"] = j;
  d["wall"] = wall;
  d["point"] = point;
  d["normal"] = normal;
  d["fn"] = fn;
  d["ft"] = ft;
  d["overlap"] = overlap;
  return d;
}

py::dict tap_dict(const World& w, const TapMeasurement& m, long tap) {
  py::dict d;
  d["tap"] = tap;
  d["t"] = w.s.t;
  d["phi"] = m.phi;
  d["phi_left"] = m.phi_left;
  d["phi_right"] = m.phi_right;
  d["kinetic_energy"] = m.kinetic_energy;
  d["max_speed"] = m.max_speed;
  d["z_mean"] = m.z_mean;
  for (std::size_t k = 0; k < w.species.size() && k < m.z_species.size(); ++k)
    d[py::str("z_" + w.species[k].name)] = m.z_species[k];
  d["coordination"] = m.coordination;
  d["S"] = py::make_tuple(m.S[0], m.S[1], m.S[2], m.S[3]);
  return d;
}

std::array<double, 4> rect_or_scene(const SceneSpec& scene, const py::object& rect) {
  if (rect.is_none())
    return {scene.output.test_rect[0], scene.output.test_rect[1], scene.output.test_rect[2],
            scene.output.test_rect[3]};
  const Args args("rect");
  std::vector<double> r;
  try {
    r = rect.cast<std::vector<double>>();
  } catch (const py::cast_error&) {
    args.fail("rect", "must be [x0, y0, x1, y1], four numbers");
  }
  if (r.size() != 4 || !(r[2] > r[0]) || !(r[3] > r[1]))
    throw InputError("rect", "rect", "must be [x0, y0, x1, y1] with x1 > x0 and y1 > y0");
  args.all_finite("rect", r);
  return {r[0], r[1], r[2], r[3]};
}

}  // namespace

PySim::PySim(const SceneSpec& spec) {
  // as `gransim run` builds its simulation (sim/prepare.hpp)
  PreparedRun r = prepare_run(spec);
  scene = std::move(r.scene);
  sim = std::move(r.sim);
  clock = std::move(r.clock);
}

void PySim::advance(std::int64_t n) {
  if (n < 0) throw InputError("step", "n", "must be >= 0 (got " + std::to_string(n) + ")");
  while (n > 0) {
    const std::int64_t m = std::min(n, kSignalEvery);
    {
      py::gil_scoped_release unlocked;
      if (clock->watches_steps()) {
        for (std::int64_t k = 0; k < m; ++k) {
          sim->step();
          if (clock->after_step(sim->world()) == ClockEvent::Quench) sim->zero_velocities();
        }
      } else {
        sim->run(m);
      }
    }
    n -= m;
    if (PyErr_CheckSignals() != 0) throw py::error_already_set();
  }
}

void bind_scene_sim(py::module_& m) {
  py::class_<SceneSpec>(m, "Scene", "a parsed and validated scene (docs/scene-format.md)")
      .def_readonly("path", &SceneSpec::path, "the file it came from (or the name given)")
      .def_readonly("name", &SceneSpec::name)
      .def_readonly("description", &SceneSpec::description)
      .def_readonly("duration", &SceneSpec::duration, "simulated time, s")
      .def_readonly("resolved", &SceneSpec::resolved,
                    "every key with its value as TOML text, defaults included")
      .def_property_readonly("dt", [](const SceneSpec& s) { return s.integrator.dt; })
      .def_property_readonly("taps", [](const SceneSpec& s) { return s.drive.taps; })
      .def_property_readonly("test_rect",
                             [](const SceneSpec& s) {
                               return py::make_tuple(s.output.test_rect[0], s.output.test_rect[1],
                                                     s.output.test_rect[2], s.output.test_rect[3]);
                             })
      .def("to_toml", &scene_to_toml, "a complete TOML scene that parses back to this one")
      .def("__repr__", [](const SceneSpec& s) {
        return "<gransim.Scene '" + s.name + "' from " + s.path + ">";
      });

  m.def("parse_scene_file", &parse_scene_file, py::arg("path"),
        py::arg("overrides") = std::vector<std::string>{},
        "parse a scene file; overrides are 'dotted.key=value' strings as with --set");
  m.def("parse_scene_string", &parse_scene_string, py::arg("text"), py::arg("name"),
        py::arg("overrides") = std::vector<std::string>{},
        "parse scene TOML text; `name` stands in for the file name in messages");

  py::class_<PySim>(m, "Simulation", "a simulation as `gransim run` sets it up")
      .def(py::init<const SceneSpec&>(), py::arg("scene"))
      .def("step", &PySim::advance, py::arg("n") = 1, "advance n time steps")
      .def(
          "run",
          [](PySim& s, double t) {
            const Args args("Simulation.run");
            args.non_negative("t", t);
            // as many steps as an int64 counts, with room to spare (10¹⁵ steps are years)
            const double steps = std::round(t / s.sim->dt());
            args.require(steps <= 1e15, "t",
                         Args::text(t) + " s is " + Args::text(steps) + " steps of " +
                             Args::text(s.sim->dt()) + " s; at most 1e15 steps at once");
            s.advance(static_cast<std::int64_t>(steps));
          },
          py::arg("t"), "advance by simulated time t (s), rounded to whole steps")
      .def(
          "run_to_tap",
          [](PySim& s, long k) {
            const World& w = s.sim->world();
            const DriveSpec& d = s.sim->settings().drive;
            if (!is_tapping(d))
              throw InputError(s.scene.path, "drive.kind",
                               "run_to_tap needs a tapping protocol (negative_g or rotating_g)");
            const double dt = s.sim->dt();
            auto at = [&] {
              const World& ww = s.sim->world();
              return excitation_starts_next(s.sim->settings().drive, ww.clock_origin, ww.s.t, dt) &&
                     drive_phase(s.sim->settings().drive, ww.clock_origin, ww.s.t + dt).tap == k;
            };
            const DrivePhase p = drive_phase(d, w.clock_origin, w.s.t + dt);
            if (k < 0 || (!p.settling && p.tap > k) || (!p.settling && p.tap == k && !at()))
              throw InputError("run_to_tap", "k",
                               "tap " + std::to_string(k) + " is past (the pile is in period " +
                                   std::to_string(p.tap) + ")");
            while (!at()) {
              const World& ww = s.sim->world();
              const std::int64_t m = s.clock->watches_steps()
                                         ? 1
                                         : 1 + steps_before_excitation(s.sim->settings().drive,
                                                                       ww.clock_origin, ww.s.t, dt);
              s.advance(std::max<std::int64_t>(1, m));
            }
            return tap_dict(
                s.sim->world(),
                measure_tap(s.sim->world(), s.sim->contacts(), s.scene.output.test_rect), k);
          },
          py::arg("k"),
          "run until just before the excitation after k taps (k = 0: the settled pile) and "
          "measure the pile there, as taps.csv's row k")
      .def(
          "measure_tap",
          [](const PySim& s, const py::object& rect) {
            const World& w = s.sim->world();
            const auto r = rect_or_scene(s.scene, rect);
            const DrivePhase p =
                drive_phase(s.sim->settings().drive, w.clock_origin, w.s.t + s.sim->dt());
            return tap_dict(w, measure_tap(w, s.sim->contacts(), r.data()), p.settling ? 0 : p.tap);
          },
          py::arg("rect") = py::none(), "the per-tap measurement of the pile now")
      .def(
          "phi",
          [](const PySim& s, const py::object& rect) {
            const auto r = rect_or_scene(s.scene, rect);
            return phi_in_rect(s.sim->world(), r[0], r[1], r[2], r[3]);
          },
          py::arg("rect") = py::none(),
          "volume fraction in [x0, y0, x1, y1] (default: output.test_rect)")
      .def_property_readonly("scene", [](const PySim& s) { return s.scene; })
      .def_property_readonly("t", [](const PySim& s) { return s.sim->world().s.t; })
      .def_property_readonly("step_count", [](const PySim& s) { return s.sim->world().s.step; })
      .def_property_readonly("dt", [](const PySim& s) { return s.sim->dt(); })
      .def("__len__", [](const PySim& s) { return s.sim->world().size(); })
      .def_property_readonly("box",
                             [](const PySim& s) {
                               const World& w = s.sim->world();
                               return py::make_tuple(w.Lx, w.Ly);
                             })
      .def_property_readonly("periodic",
                             [](const PySim& s) { return s.sim->world().box != BoxKind::Walls; })
      .def_property_readonly(
          "gravity",
          [](const PySim& s) { return py::make_tuple(s.sim->gravity().x, s.sim->gravity().y); })
      .def_property_readonly(
          "tap",
          [](const PySim& s) {
            const World& w = s.sim->world();
            const DrivePhase p =
                drive_phase(s.sim->settings().drive, w.clock_origin, w.s.t + s.sim->dt());
            return p.settling ? -1L : p.tap;
          },
          "the period the next step is in (taps completed before it); -1 while settling")
      .def_property_readonly("kinetic_energy",
                             [](const PySim& s) { return s.sim->world().kinetic_energy(); })
      .def_property_readonly("sort_every", [](const PySim& s) { return s.sim->sort_every(); })
      .def_property_readonly("order_generation",
                             [](const PySim& s) { return s.sim->order_generation(); })
      .def_property_readonly("species_names",
                             [](const PySim& s) {
                               std::vector<std::string> names;
                               for (const Species& sp : s.sim->world().species)
                                 names.push_back(sp.name);
                               return names;
                             })
      // views: the arrays of the World itself, read-only, alive as long as the Simulation
      .def_property_readonly(
          "x", [](py::object self) { return view(self, self.cast<PySim&>().sim->world().s.x); })
      .def_property_readonly(
          "y", [](py::object self) { return view(self, self.cast<PySim&>().sim->world().s.y); })
      .def_property_readonly(
          "vx", [](py::object self) { return view(self, self.cast<PySim&>().sim->world().s.vx); })
      .def_property_readonly(
          "vy", [](py::object self) { return view(self, self.cast<PySim&>().sim->world().s.vy); })
      .def_property_readonly(
          "theta",
          [](py::object self) { return view(self, self.cast<PySim&>().sim->world().s.th); })
      .def_property_readonly(
          "omega",
          [](py::object self) { return view(self, self.cast<PySim&>().sim->world().s.omega); })
      .def_property_readonly(
          "species",
          [](py::object self) { return view(self, self.cast<PySim&>().sim->world().sp); })
      .def_property_readonly(
          "radius",
          [](py::object self) { return view(self, self.cast<PySim&>().sim->world().radius); })
      .def_property_readonly(
          "mass", [](py::object self) { return view(self, self.cast<PySim&>().sim->world().mass); })
      .def_property_readonly(
          "ids", [](py::object self) { return view(self, self.cast<PySim&>().sim->world().id); })
      // copies: N×2 arrays built from two separate vectors
      .def_property_readonly(
          "positions", [](const PySim& s) { return pairs(s.sim->world().s.x, s.sim->world().s.y); })
      .def_property_readonly(
          "velocities",
          [](const PySim& s) { return pairs(s.sim->world().s.vx, s.sim->world().s.vy); })
      .def(
          "contacts", [](const PySim& s) { return contacts_dict(*s.sim); },
          "the last step's touching contacts as arrays (copies)");
}

py::array_t<double> pairs(const std::vector<double>& a, const std::vector<double>& b) {
  py::array_t<double> out({static_cast<py::ssize_t>(a.size()), py::ssize_t{2}});
  auto o = out.mutable_unchecked<2>();
  for (std::size_t i = 0; i < a.size(); ++i) {
    o(i, 0) = a[i];
    o(i, 1) = b[i];
  }
  return out;
}

}  // namespace gs::py_bind
