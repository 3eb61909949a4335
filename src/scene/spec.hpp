// SceneSpec: the plain-data description of a scene, validated once by the parser.
// Every field says its unit. Parsing lives in parse.hpp; nothing here knows TOML.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "core/integrator_kind.hpp"

namespace gs {

enum class ShapeKind : std::uint8_t { Disk, Polygon };
enum class ModelKind : std::uint8_t {
  Polygon,  ///< "P": polygon DEM, overlap-area normal force + Cundall–Strack (docs/physics.md §2)
  Disk,     ///< "S": soft disks, linear spring–dashpot (docs/physics.md §3)
};
enum class BoxKind : std::uint8_t {
  Walls,     ///< closed box of wall rectangles (optionally without lid)
  Periodic,  ///< periodic rectangle, minimum image
  Ring1D,    ///< periodic line (1D RFM)
};
enum class PlacementKind : std::uint8_t {
  LooseColumn,  ///< random non-overlapping positions/orientations in a column, seeded
  Hexagonal,
  Square,
  Uniform,  ///< each particle gets an equal share of the box (thesis fig. 2.4c)
  Random,   ///< uniform random non-overlapping positions in the whole box
};
enum class DriveKind : std::uint8_t {
  None,
  Gravity,      ///< constant gravity g (vector)
  NegativeG,    ///< pulses of negative gravity (P.37)
  RotatingG,    ///< rotating gravity (P.38)
  RandomForce,  ///< white-noise kicks (T.2.16, T.2.23)
};
enum class BroadPhaseKind : std::uint8_t { Auto, Box2DTree, CellGrid };

/// a material: Model P uses E, γ, μ; Model S uses ε_n, ε_t, k_s, μ
struct MaterialSpec {
  std::string name;
  double E = 1000.0;   ///< Model P 2D modulus, N/m
  double gamma = 0.5;  ///< Model P damping, dimensionless
  double mu = 0.6;     ///< friction coefficient (Model S: 0 = off)
  double ks = 5e5;     ///< Model S normal stiffness, N/m
  double eps_n = 0.6;  ///< Model S normal restitution
  double eps_t = 1.0;  ///< Model S tangential restitution (1 = no tangential dashpot)
  int line = 0;        ///< line in the scene file, for messages
};

/// one species of grains
struct SpeciesSpec {
  std::string name;
  ShapeKind shape = ShapeKind::Polygon;
  int sides = 10;         ///< regular n-gon sides (polygons)
  double radius = 0.009;  ///< circumradius (polygons) or radius (disks), m
  int count = 0;
  double density = 1.0;        ///< areal density ρ, kg/m² (used when mass is not given)
  std::optional<double> mass;  ///< mass per grain, kg (overrides density)
  std::string material;        ///< name of a MaterialSpec (default: the first material)
  int line = 0;
  /// count written in the file (with preparation.from_state it may be left out: the saved
  /// state's grains of this species then set it)
  bool count_given = true;
};

struct BoxSpec {
  BoxKind kind = BoxKind::Walls;
  double width = 0.48;                   ///< inner width W, m (ring: length L)
  double height = 1.0;                   ///< inner height (lid height when lid = true), m
  bool lid = false;                      ///< closed top (rotating g)
  double wall_thickness = 0.05;          ///< m
  std::optional<double> reduced_length;  ///< 1D ring L′ = L − N·d, m (overrides width)
  std::string material;                  ///< wall material name (default: first material)
};

struct PreparationSpec {
  PlacementKind placement = PlacementKind::LooseColumn;
  std::uint64_t seed = 1;
  double column_height = 0.0;       ///< loose column height, m (0 = automatic, ~2× packed)
  double velocity_amplitude = 0.0;  ///< initial velocity components U(−a/2, a/2), m/s
  double settle_time = 0.0;         ///< let it settle under gravity for this long first, s
  /// explicit particles (tests, collision scenes): overrides placement when non-empty
  struct Particle {
    std::string species;
    double x = 0, y = 0, theta = 0, vx = 0, vy = 0, omega = 0;
  };
  std::vector<Particle> particles;
  /// start from a saved state (a state file, a checkpoint, or a run directory: its newest
  /// checkpoint, else its state.csv) instead of placing grains; an absolute path once parsed
  /// (docs/scene-format.md). Read by sim/saved_state.hpp, not by the parser.
  std::string from_state;
  std::string from_state_where;  ///< "file:line" of the key, for messages
};

struct ModelSpec {
  ModelKind kind = ModelKind::Polygon;
  bool hdot_finite_difference = false;  ///< Model P: ḣ_eff by finite difference (else analytic)
  /// Model P: spread the normal dashpot along the contact line, so it also damps relative
  /// rotation (a couple γ√(E m⊥)·L³/(12 l)·ω_rel); the paper's point dashpot leaves rocking
  /// on a face undamped (docs/physics.md §2.2)
  bool rocking_damping = true;
  bool clip_attractive = false;  ///< Model S: clip attractive normal force
  bool rotation = true;          ///< integrate rotation (auto-off for frictionless disks)
};

struct IntegratorSpec {
  IntegratorKind kind = IntegratorKind::Gear6;
  double dt = 5e-5;  ///< time step, s
  BroadPhaseKind broad_phase = BroadPhaseKind::Auto;
  /// spatial sort of the particles every K steps (cache locality of large disk systems):
  /// −1 = auto (every kAutoSortEvery steps for 2D Model S scenes of at least
  /// kAutoSortMinParticles particles, else never), 0 = never
  int sort_every = -1;
};
inline constexpr int kAutoSortEvery = 1000;
inline constexpr std::size_t kAutoSortMinParticles = 50000;

struct DriveSpec {
  DriveKind kind = DriveKind::Gravity;
  double g = 9.81;             ///< gravity magnitude, m/s²
  double gx = 0.0, gy = -1.0;  ///< gravity direction (constant gravity), normalised on use
  // negative g (P.37)
  double g_p = 6.0;     ///< pulse strength in units of g
  double t1 = 0.1;      ///< pulse duration, s
  double period = 3.0;  ///< period T, s
  // rotating g (P.38)
  double f = 1.0;      ///< rotation frequency f = ω/2π, Hz
  double relax = 3.0;  ///< rest time after the rotation, s (T = 1/f + relax)
  // random force (T.2.16)
  double D = 1e-8;              ///< noise strength, N² s
  int com_removal_every = 100;  ///< 2D: subtract centre-of-mass velocity every K steps
  // early rest: end a relaxation early when max speed and KE stay low for hold time
  bool early_rest = false;
  double rest_speed = 1e-3;   ///< m/s
  double rest_energy = 1e-6;  ///< J
  double rest_hold = 0.1;     ///< s
  // quench: kinetic damping (zero every velocity at each kinetic-energy peak) during a
  // relaxation once the largest speed has stayed below quench_speed for quench_hold
  bool quench = false;
  double quench_speed = 0.05;  ///< m/s
  double quench_hold = 0.3;    ///< s
  // taps
  int taps = 0;  ///< number of taps (0 = run for duration)
};

struct HealthSpec {
  double max_overlap = 0.2;     ///< stop when h_eff or δ exceeds this fraction of grain size
  int check_every = 100;        ///< steps between checks
  bool allow_unstable = false;  ///< skip the up-front Δt check
};

/// [output.snapshots]: the configuration (and its contact forces) at chosen times and at every
/// tap's measurement, written to DIR/snapshots/ (app/render/snapshot_observer.cpp,
/// docs/scene-format.md)
struct SnapshotSpec {
  bool given = false;         ///< the scene has the table (it is then written back)
  double every_time = 0.0;    ///< s between snapshots from t = 0 (0 = off)
  std::vector<double> times;  ///< further snapshot times, s, ascending
  bool at_taps = false;       ///< at each tap's measurement (tapping drives)
  bool vtp = true;            ///< formats: VTK XML PolyData (+ the .pvd collection)
  bool xyz = true;            ///< formats: extended XYZ
  bool vtp_binary = true;     ///< .vtp arrays zlib-compressed binary (false: ASCII text)
  bool contacts = true;       ///< one CSV row per contact
  bool enabled() const { return every_time > 0.0 || !times.empty() || at_taps; }
};

struct OutputSpec {
  int series_every = 100;  ///< steps between series.csv rows
  bool final_state = true;
  double test_rect[4] = {0.04, 0.04, 0.44, 0.44};  ///< x0, y0, x1, y1 of the φ window, m
  int discard_taps = 10;
  // checkpoints (docs/robustness.md): DIR/checkpoint-<step>.gsck, the newest two kept, written
  // on every trigger that is on (0 = off) and when the run stops
  double checkpoint_minutes = 10.0;   ///< wall-clock minutes between checkpoints
  int checkpoint_taps = 0;            ///< taps between checkpoints (tapping scenes)
  std::int64_t checkpoint_steps = 0;  ///< steps between checkpoints
  SnapshotSpec snapshots;
};

/// when the frame recorder takes a picture ([render] schedule)
enum class RenderSchedule : std::uint8_t {
  Time,   ///< fps·slowmo frames per simulated second
  Steps,  ///< every N steps
  Taps,   ///< at the start of each excitation and just before the next one
  Rest,   ///< only just before each excitation (one frame per tap, the pile at rest)
};

/// [render]: frames and movies recorded while the scene runs, and the trajectory export
/// (parsed in scene/render_section.cpp; names checked against render/ by tests/app)
struct RenderSpec {
  bool enabled = false;  ///< record frames and/or a movie while the scene runs
  bool frames = false;   ///< write DIR/frames/frame_NNNNNN.png
  bool movie = true;     ///< write DIR/movie.mp4 (H.264, in-process)
  RenderSchedule schedule = RenderSchedule::Time;
  int every = 1000;                ///< steps between frames (schedule "steps")
  int fps = 30;                    ///< movie frame rate, 1/s
  double slowmo = 1.0;             ///< video seconds per simulated second (schedule "time")
  double start = 0.0;              ///< no frames before this simulated time, s
  int width = 1280, height = 720;  ///< frame size, px
  int msaa = 4;                    ///< samples per pixel (GL backend)
  std::optional<std::array<double, 4>> region;  ///< camera x0, y0, x1, y1, m (none: fit box)
  double margin = 0.04;            ///< camera margin around the box, fraction of its larger side
  std::string color_by = "speed";  ///< speed, speed_rms, species, vy, contacts, pressure, uniform
  std::string colormap = "viridis";
  std::optional<std::array<double, 2>> range;  ///< fixed colour range lo, hi (none: automatic)
  bool colorbar = true;
  bool force_chains = false;      ///< contact force chains (line width ∝ normal force)
  bool gravity_arrow = false;     ///< default: true for negative_g / rotating_g
  bool test_rect = false;         ///< draw output.test_rect; default: true for tapping drives
  bool clock = true;              ///< print "t = … s" (and the tap number when tapping)
  std::string title;              ///< a header line ("" = none)
  int crf = 20;                   ///< x264 quality (0 best … 51 worst)
  std::string preset = "medium";  ///< x264 speed preset
  std::string renderer = "auto";  ///< "auto", "gl", "software"
  int trajectory_every = 0;       ///< steps between trajectory frames (0 = off)
  bool trajectory_xyz = true;     ///< trajectory formats: DIR/trajectory.xyz (extended XYZ)
  bool trajectory_h5md = false;   ///< trajectory formats: DIR/trajectory.h5md (H5MD on HDF5)
};

/// [rfm]: the Random Force Model measurements (docs/physics.md §5.3), taken by read-only observers
/// on a sampling interval (parsed in scene/rfm_section.cpp; measure/rfm_observer.hpp; docs/rfm.md)
struct RfmSpec {
  bool given = false;         ///< the scene has an [rfm] section (not a key)
  bool enabled = false;       ///< measure (default: true with [rfm] or drive.kind = "random_force")
  int sample_every = 1000;    ///< steps between samples
  double discard_time = 1.0;  ///< transient left out of every statistic, s
  int blocks = 10;            ///< blocks of the T.2.20 averages and of the moment errors
  double v_max = 0.0;         ///< velocity histogram half-range, m/s (0: 12 σ at the first sample)
  int v_bins = 400;           ///< velocity histogram bins (one Cartesian component)
  int structure_every = 10;   ///< samples between S(k) and g(R) snapshots (the costly ones)
  int sk_nmax = 0;            ///< S(k) cutoff |n| = |k|L/2π (0: 1.2 L/d, at most 96)
  int gr_bins = 200;          ///< g(R) bins on [0, gr_rmax)
  double gr_rmax = 0.0;       ///< g(R) range, m (0: L/4)
  int path_bins = 90;         ///< free-path log bins
  double path_min = 0.0;      ///< free-path lowest bin edge, m (0: 1e-4·d)
  double path_max = 0.0;      ///< free-path highest bin edge, m (0: L, 1D: L′)
  int gap_bins = 120;         ///< 1D G_h(R) log bins of R/L′ on [gap_min, 1)
  double gap_min = 1e-12;     ///< lowest G_h bin edge, units of L′
};

struct SceneSpec {
  std::string path;  ///< file it came from
  std::string name;
  std::string description;
  ModelSpec model;
  std::vector<MaterialSpec> materials;
  std::vector<SpeciesSpec> species;
  BoxSpec box;
  PreparationSpec prep;
  IntegratorSpec integrator;
  DriveSpec drive;
  HealthSpec health;
  OutputSpec output;
  RenderSpec render;
  RfmSpec rfm;
  double duration = 1.0;  ///< simulated time, s (ignored when drive.taps > 0)
  /// every key as written, resolved with defaults, for run.json (key path → TOML value text)
  std::map<std::string, std::string> resolved;
};

}  // namespace gs
