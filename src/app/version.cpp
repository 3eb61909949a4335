#include "app/version.hpp"

#include "git_commit.hpp"

namespace gs {

std::string_view program_version() { return GS_VERSION; }

std::string version_text() {
  std::string features;
  auto add = [&](bool on, const char* name) {
    if (on) features += features.empty() ? name : std::string(", ") + name;
  };
#ifdef GS_HAVE_OSMESA
  add(true, "OSMesa");
#endif
#ifdef GS_HAVE_FFMPEG
  add(true, "FFmpeg");
#endif
#ifdef GS_HAVE_MPI
  add(true, "MPI");
#endif
#ifdef GS_HAVE_FFTW
  add(true, "FFTW");
#endif
#ifdef _OPENMP
  add(true, "OpenMP");
#endif
#ifdef GS_HAVE_FREETYPE
  add(true, "FreeType");
#endif
  return std::string("gransim ") + GS_VERSION + " (commit " + GS_GIT_COMMIT +
         ")\nfeatures: " + (features.empty() ? std::string("none") : features) +
         "\nlicense: GPL-3.0-or-later (LICENSE)";
}

}  // namespace gs
