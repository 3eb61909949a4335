// frames of a simulation as NumPy images (the [render] section's backend: OSMesa where built
// and working, else the software rasteriser), PNG files, and MP4 movies through the encoder
#include <pybind11/stl.h>

#include <cstring>
#include <limits>
#include <string>

#include "arguments.hpp"
#include "bindings.hpp"
#include "core/error.hpp"
#include "output/png.hpp"
#include "scene/parse.hpp"
#include "view/frame_maker.hpp"
#if defined(GS_HAVE_FFMPEG)
#include "output/movie/movie.hpp"
#endif

namespace gs::py_bind {

namespace {
// a side longer than this is no frame (16K video is 15360 wide)
constexpr py::ssize_t kMaxSide = 16384;
}  // namespace

py::array image_to_array(Image img, int channels) {
  if (channels != 3 && channels != 4)
    throw InputError("render", "channels",
                     "must be 3 (RGB) or 4 (RGBA), got " + std::to_string(channels));
  auto* owned = new Image(std::move(img));
  py::capsule free_it(owned, [](void* p) { delete static_cast<Image*>(p); });
  const py::ssize_t h = owned->height, w = owned->width;
  // RGB is a strided view of the RGBA buffer: no copy either way
  return py::array_t<std::uint8_t>({h, w, py::ssize_t{channels}},
                                   {w * 4, py::ssize_t{4}, py::ssize_t{1}}, owned->rgba.data(),
                                   free_it);
}

Image array_to_image(const py::array& any) {
  const auto a = py::array_t<std::uint8_t, py::array::c_style | py::array::forcecast>::ensure(any);
  if (!a || a.ndim() != 3 || (a.shape(2) != 3 && a.shape(2) != 4))
    throw InputError("image", "image", "must be an H×W×3 or H×W×4 uint8 array");
  if (a.shape(0) < 1 || a.shape(1) < 1 || a.shape(0) > kMaxSide || a.shape(1) > kMaxSide)
    throw InputError("image", "image",
                     "must be 1 to " + std::to_string(kMaxSide) + " pixels on each side (got " +
                         std::to_string(a.shape(1)) + "×" + std::to_string(a.shape(0)) + ")");
  Image img(static_cast<int>(a.shape(1)), static_cast<int>(a.shape(0)));
  const auto c = static_cast<std::size_t>(a.shape(2));
  const std::uint8_t* src = a.data();
  for (std::size_t p = 0; p < static_cast<std::size_t>(img.width) * img.height; ++p) {
    std::memcpy(&img.rgba[p * 4], src + p * c, c);
    if (c == 3) img.rgba[p * 4 + 3] = 255;
  }
  return img;
}

namespace {

/// a FrameMaker with the simulation's [render] section, `overrides` ("render.width=320", …)
/// applied through the scene parser so that bad values get the parser's messages
struct PyRenderer {
  std::unique_ptr<FrameMaker> maker;
  ViewSettings view;
  PyRenderer(const SceneSpec& scene, const std::vector<std::string>& overrides) {
    SceneSpec s =
        overrides.empty() ? scene : parse_scene_string(scene_to_toml(scene), scene.path, overrides);
    maker = std::make_unique<FrameMaker>(s.render, scene.path);
    view = ViewSettings::from(s);
  }
  py::array render(const PySim& s, int channels) {
    Args("Renderer.render").count("channels", channels, 3, 4);
    const Simulation& sim = *s.sim;
    const World& w = sim.world();
    Image img;
    {
      py::gil_scoped_release unlocked;
      img = maker->render(w, &sim.contacts(), frame_info(w, view, sim.gravity()));
    }
    return image_to_array(std::move(img), channels);
  }
};

#if defined(GS_HAVE_FFMPEG)
struct PyMovie {
  MovieEncoder enc;
};
#endif

}  // namespace

void bind_render(py::module_& m) {
  py::class_<PyRenderer>(m, "Renderer",
                         "draws frames of a simulation with its scene's [render] settings")
      .def(py::init([](const PySim& s, const std::vector<std::string>& overrides) {
             return std::make_unique<PyRenderer>(s.scene, overrides);
           }),
           py::arg("sim"), py::arg("overrides") = std::vector<std::string>{})
      .def("render", &PyRenderer::render, py::arg("sim"), py::arg("channels") = 3,
           "the frame as an H×W×channels uint8 array (top row first)")
      .def_property_readonly("backend", [](const PyRenderer& r) { return r.maker->describe(); })
      .def_property_readonly("width", [](const PyRenderer& r) { return r.maker->spec().width; })
      .def_property_readonly("height", [](const PyRenderer& r) { return r.maker->spec().height; });

  m.def(
      "write_png",
      [](const std::string& path, const py::array& a) { write_png(path, array_to_image(a)); },
      py::arg("path"), py::arg("image"), "write an H×W×3 or H×W×4 uint8 image as PNG");
  m.def(
      "read_png",
      [](const std::string& path, int channels) {
        Args("read_png").count("channels", channels, 3, 4);
        return image_to_array(read_png(path), channels);
      },
      py::arg("path"), py::arg("channels") = 4, "read a PNG as an H×W×channels uint8 array");

#if defined(GS_HAVE_FFMPEG)
  m.attr("have_movie") = true;
  py::class_<PyMovie>(m, "MovieEncoder", "MP4 (H.264, else MPEG-4) from uint8 frames")
      .def(py::init([](const std::string& path, int width, int height, int fps, int crf,
                       const std::string& preset, const std::string& codec) {
             Args("MovieEncoder")
                 .count("width", width, 2, kMaxSide)
                 .count("height", height, 2, kMaxSide)
                 .count("fps", fps, 1, 1000)
                 .count("crf", crf, 0, 51);
             auto p = std::make_unique<PyMovie>();
             MovieOptions o;
             o.fps = fps;
             o.crf = crf;
             o.preset = preset;
             o.codec = codec;
             p->enc.open(path, width, height, o);
             return p;
           }),
           py::arg("path"), py::arg("width"), py::arg("height"), py::arg("fps") = 30,
           py::arg("crf") = 20, py::arg("preset") = "medium", py::arg("codec") = "")
      .def(
          "add_frame", [](PyMovie& p, const py::array& a) { p.enc.add_frame(array_to_image(a)); },
          py::arg("frame"))
      .def("close", [](PyMovie& p) { p.enc.close(); })
      .def_property_readonly("frames", [](const PyMovie& p) { return p.enc.frames(); })
      .def_property_readonly("codec", [](const PyMovie& p) { return p.enc.codec_name(); });
  m.def(
      "probe_movie",
      [](const std::string& path) {
        const MovieInfo i = probe_movie(path);
        py::dict d;
        d["width"] = i.width;
        d["height"] = i.height;
        d["frames"] = i.frames;
        d["duration"] = i.duration;
        d["fps"] = i.fps;
        d["codec"] = i.codec;
        d["pixel_format"] = i.pixel_format;
        return d;
      },
      py::arg("path"), "decode a movie and say what it holds");
  m.def(
      "movie_frame",
      [](const std::string& path, int index, int channels) {
        Args("movie_frame")
            .count("index", index, 0, std::numeric_limits<int>::max())
            .count("channels", channels, 3, 4);
        return image_to_array(movie_frame(path, index), channels);
      },
      py::arg("path"), py::arg("index"), py::arg("channels") = 3);
#else
  m.attr("have_movie") = false;
#endif
#if defined(GS_HAVE_OSMESA)
  m.attr("have_osmesa") = true;
#else
  m.attr("have_osmesa") = false;
#endif
}

}  // namespace gs::py_bind
