// gransim._gransim: the compiled part of the gransim Python package (docs/python-module.md).
// Library errors become Python exceptions with the CLI's messages: InputError (a ValueError,
// with .where and .key), HealthError, OutputError, RenderError.
#include "bindings.hpp"
#include "core/error.hpp"
#include "render/renderer.hpp"

namespace py = pybind11;

PYBIND11_MODULE(_gransim, m) {
  m.doc() = "gransim: 2D granular dynamics (compiled part; import gransim instead)";
  m.attr("__version__") = GS_VERSION;
  static py::exception<gs::InputError> input_error(m, "InputError", PyExc_ValueError);
  static py::exception<gs::HealthError> health_error(m, "HealthError", PyExc_RuntimeError);
  static py::exception<gs::OutputError> output_error(m, "OutputError", PyExc_OSError);
  static py::exception<gs::RenderError> render_error(m, "RenderError", PyExc_RuntimeError);
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) std::rethrow_exception(p);
    } catch (const gs::InputError& e) {
      py::object err = py::reinterpret_borrow<py::object>(input_error)(e.what());
      err.attr("where") = e.where();
      err.attr("key") = e.key();
      PyErr_SetObject(input_error.ptr(), err.ptr());
    } catch (const gs::HealthError& e) {
      PyErr_SetString(health_error.ptr(), e.what());
    } catch (const gs::OutputError& e) {
      PyErr_SetString(output_error.ptr(), e.what());
    } catch (const gs::RenderError& e) {
      PyErr_SetString(render_error.ptr(), e.what());
    }
  });
  gs::py_bind::bind_scene_sim(m);
  gs::py_bind::bind_state(m);
  gs::py_bind::bind_render(m);
  gs::py_bind::bind_tapping(m);
  gs::py_bind::bind_rfm(m);
}
