// the pieces of the gransim Python module (module.cpp puts them together)
#pragma once
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <cstdint>
#include <memory>
#include <vector>

#include "core/image.hpp"
#include "core/vec.hpp"
#include "drive/protocol.hpp"
#include "sim/checkpoint.hpp"
#include "sim/simulation.hpp"

namespace gs::py_bind {

namespace py = pybind11;

/// a Simulation with the protocol clock that drives it, as `gransim run` sets them up; both on
/// the heap so that NumPy views onto the World's arrays stay valid while the object lives
struct PySim {
  SceneSpec scene;  ///< the scene it was made from (Scene.scene, the render's [render] section)
  std::unique_ptr<Simulation> sim;
  std::unique_ptr<ProtocolClock> clock;
  explicit PySim(const SceneSpec& scene);
  /// the simulation a checkpoint holds, continuing bitwise (bind_state.cpp)
  explicit PySim(const Checkpoint& checkpoint);
  /// n steps, the protocol clock after each where it watches them (early rest, quench)
  void advance(std::int64_t n);
};

/// an Image as an H×W×channels uint8 array that owns it (no copy); channels 3 or 4
py::array image_to_array(Image img, int channels);
/// an H×W×3 or H×W×4 uint8 array as an Image (opaque alpha for 3 channels)
Image array_to_image(const py::array& a);
/// two vectors side by side as an N×2 array (a copy: the World keeps them apart)
py::array_t<double> pairs(const std::vector<double>& a, const std::vector<double>& b);
/// an N×2 float array (or a list of pairs) as points, m
std::vector<Vec2> to_points(
    const py::array_t<double, py::array::c_style | py::array::forcecast>& a);

void bind_scene_sim(py::module_& m);
void bind_render(py::module_& m);
void bind_tapping(py::module_& m);
void bind_rfm(py::module_& m);
/// state setters, snapshots, checkpoints and files on the Simulation (after bind_scene_sim)
void bind_state(py::module_& m);

}  // namespace gs::py_bind
