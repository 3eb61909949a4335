# the modules in data-path order (docs/architecture.md): each uses only those above it
gs_module(core DEPS Eigen3::Eigen)
gs_module(geometry DEPS gs_core)
gs_module(integrate DEPS gs_core)
gs_module(scene DEPS gs_geometry tomlplusplus::tomlplusplus)
gs_module(world DEPS gs_scene gs_geometry)
gs_module(broadphase DEPS gs_world box2d::box2d)
gs_module(contact DEPS gs_broadphase)
# force/: the pair loop; force/laws/: the laws (header-only pure functions) and their pair evaluators
gs_module(force DIRS force force/laws DEPS gs_contact)
gs_module(drive DEPS gs_world)
gs_module(sim DEPS gs_force gs_integrate gs_drive nlohmann_json::nlohmann_json)
# measure: read-only observers; they hand their rows to a RecordSink (core/records.hpp) and never
# use output/ (the run gives them its CSV writer)
gs_module(measure DEPS gs_sim gs_analysis)
gs_module(analysis DEPS gs_core nlohmann_json::nlohmann_json)
if(FFTW3_FOUND)
  target_link_libraries(gs_analysis PUBLIC PkgConfig::FFTW3)
  target_compile_definitions(gs_analysis PUBLIC GS_HAVE_FFTW=1)
endif()

# auxiliary models of the thesis (bisection, single-particle walks, cascades): cheap exact checks
gs_module(models DEPS gs_analysis)

# render: the GL-free frame builder always; the OSMesa backend only where OSMesa is found
gs_module(render DEPS gs_geometry)
if(OSMESA_FOUND)
  file(GLOB gl_srcs CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/render/gl/*.cpp)
  if(gl_srcs)
    add_library(gs_render_gl STATIC ${gl_srcs})
    target_link_libraries(gs_render_gl PUBLIC gs_render PkgConfig::OSMESA)
    if(FREETYPE_FOUND)
      target_link_libraries(gs_render_gl PUBLIC PkgConfig::FREETYPE)
      target_compile_definitions(gs_render_gl PUBLIC GS_HAVE_FREETYPE=1)
    endif()
    target_compile_definitions(gs_render_gl PUBLIC GS_HAVE_OSMESA=1
      GS_SHADER_DIR="${CMAKE_SOURCE_DIR}/shaders")
  endif()
endif()

# view: World (+ contacts) → frame data and images, the adapter between the engine and render/
gs_module(view DEPS gs_contact gs_drive gs_render)
if(TARGET gs_render_gl)
  target_link_libraries(gs_view PUBLIC gs_render_gl)
endif()

# output: CSV/JSON, PNG, checkpoints; the movie encoder only where FFmpeg is found
gs_module(output DEPS gs_core PkgConfig::PNG nlohmann_json::nlohmann_json)
if(FFMPEG_FOUND)
  file(GLOB movie_srcs CONFIGURE_DEPENDS ${CMAKE_SOURCE_DIR}/src/output/movie/*.cpp)
  if(movie_srcs)
    add_library(gs_movie STATIC ${movie_srcs})
    target_link_libraries(gs_movie PUBLIC gs_output PkgConfig::FFMPEG)
    target_compile_definitions(gs_movie PUBLIC GS_HAVE_FFMPEG=1)
  endif()
endif()

# per-particle files of a configuration (trajectory.xyz, VTK snapshots, contact CSVs): writers
# of output/ that read the World, hence a library of their own above view/
gs_module(particle_files DIRS output/particles DEPS gs_output gs_view)
target_link_libraries(gs_particle_files PUBLIC HDF5::HDF5 ZLIB::ZLIB)
target_compile_definitions(gs_particle_files PRIVATE GS_VERSION="${PROJECT_VERSION}")

# app/ by capability: run, sweep, study, analyze, render, reproduce (each folder's README.md)
gs_module(app DIRS app app/run app/sweep app/study app/analyze app/render app/reproduce
  DEPS gs_measure gs_view gs_render gs_output gs_particle_files gs_analysis gs_models CLI11::CLI11
  Threads::Threads nlohmann_json::nlohmann_json)
# the Python package and scenes of the source tree, for a build tree that is not beside them;
# the installed package's folder relative to the prefix
set_property(SOURCE ${CMAKE_SOURCE_DIR}/src/app/locations.cpp APPEND PROPERTY
  COMPILE_DEFINITIONS GS_SOURCE_DIR_OF_BUILD="${CMAKE_SOURCE_DIR}"
  GS_PYTHON_INSTALL_DIR="${GS_PYTHON_INSTALL_DIR}")
if(TARGET gs_render_gl)
  target_link_libraries(gs_app PUBLIC gs_render_gl)
endif()
if(TARGET gs_movie)
  target_link_libraries(gs_app PUBLIC gs_movie)
endif()
# MPI: `mpirun -np K gransim sweep …` spreads a sweep's runs over the ranks (app/sweep/sweep_mpi.cpp)
if(MPI_CXX_FOUND)
  target_link_libraries(gs_app PUBLIC MPI::MPI_CXX)
  target_compile_definitions(gs_app PUBLIC GS_HAVE_MPI=1)
endif()
# OpenMP: parallel loops over particles and pairs (core/parallel.hpp); results are bitwise independent of the thread count
if(OpenMP_CXX_FOUND)
  foreach(m integrate broadphase force drive sim)
    target_link_libraries(gs_${m} PUBLIC OpenMP::OpenMP_CXX)
  endforeach()
endif()
