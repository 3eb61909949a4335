// `gransim study`: speed against accuracy (docs/speed-accuracy.md). A study file lists reference
// problems and a matrix of integrators × Δt (in contact times) × broad phase × model switches;
// every combination runs in-process and study.csv/json record its cost and its error; an optional
// Δt sweep finds the largest stable Δt per integrator and model (docs/speed-accuracy.md)
#pragma once
#include <string>
#include <vector>

#include "integrate/integrator.hpp"
#include "scene/spec.hpp"

namespace CLI {
class App;
}

namespace gs {

struct StudyOptions {
  std::string file;    ///< study file (TOML)
  std::string out;     ///< output directory (default runs/study-<name>)
  bool force = false;  ///< reuse a non-empty output directory
  bool quiet = false;  ///< no per-row progress lines
};

/// the reference problems (docs/speed-accuracy.md)
enum class StudyProblem : std::uint8_t {
  TwoDisk,         ///< head-on two-disk collision, Model S: realised ε against the exact ε
  TwoDecagon,      ///< face-to-face two-decagon collision, Model P: against the reference Δt
  GasEnergy,       ///< elastic periodic disk gas: relative energy drift per simulated second
  Haff,            ///< freely cooling disk gas: Haff slope against the 2D Enskog value
  Pile,            ///< small decagon pile settling: φ against the reference Δt, final KE
  Tapping,         ///< short negative-g tapping run: φ̄ and σ_φ against a small-Δt reference
  RfmTemperature,  ///< randomly forced periodic disk fluid: steady T against a small-Δt reference
};
std::string_view to_string(StudyProblem p);

/// one set of model switches (each only matters for its model; see study_switches_text)
struct StudySwitches {
  bool hdot_fd = false;     ///< Model P: ḣ_eff by finite difference
  bool rocking = true;      ///< Model P: rocking damping
  bool clip = false;        ///< Model S: clip the attractive normal force
  bool early_rest = false;  ///< tapping: end a relaxation once the pile is at rest
};

/// sizes and lengths of the problems (their own tables in the study file)
struct StudySizes {
  double disk_eps = 0.5;        ///< two_disk: restitution ε_n
  double disk_speed = 1.0;      ///< two_disk: approach speed, m/s
  double decagon_speed = 0.5;   ///< two_decagon: approach speed, m/s
  int gas_n = 200;              ///< gas_energy: disks
  double gas_phi = 0.2;         ///< gas_energy: area fraction
  double gas_speed = 1.0;       ///< gas_energy: initial velocity amplitude, m/s
  double gas_duration = 0.02;   ///< gas_energy: simulated time, s
  int haff_n = 400;             ///< haff: disks (φ = 0.1, ε = 0.9 as tests/sim/test_gas.cpp)
  double haff_duration = 0.07;  ///< haff: sampled cooling time after 0.015 s relaxation, s
  int pile_n = 60;              ///< pile: decagons
  double pile_width = 0.12;     ///< pile: box width, m
  double pile_duration = 1.0;   ///< pile: settling time, s
  std::uint64_t seed = 7;       ///< seed of the gas and pile placements
  // tapping (negative g, P.37, as scenes/tap_small_negative_g.toml)
  int tap_n = 60;                  ///< tapping: decagons (paper mix 544:640 of 9 : 6.36 mm)
  double tap_width = 0.12;         ///< tapping: box width, m
  int tap_taps = 24;               ///< tapping: taps after settling
  int tap_discard = 4;             ///< tapping: first taps left out of φ̄ and σ_φ
  double tap_g_p = 6.0;            ///< tapping: pulse strength, units of g
  double tap_t1 = 0.01;            ///< tapping: pulse length, s
  double tap_period = 1.5;         ///< tapping: period T, s (60 grains rest ≈ 1 s after a pulse)
  double tap_settle = 1.0;         ///< tapping: settling under gravity before the first tap, s
  std::uint64_t tap_seed = 7;      ///< tapping: placement seed
  double tap_reference_dt = 1e-5;  ///< tapping: Δt of the Gear 6 reference, s
  // random force model, 2D (as scenes/rfm2d_reference.toml)
  int rfm_n = 400;                        ///< rfm_temperature: disks
  double rfm_phi = 0.353;                 ///< rfm_temperature: area fraction
  double rfm_eps = 0.6;                   ///< rfm_temperature: ε_n = ε_t
  double rfm_D = 1e-8;                    ///< rfm_temperature: noise strength, N² s
  double rfm_duration = 0.6;              ///< rfm_temperature: sampled time after the transient, s
  double rfm_discard = 0.05;              ///< rfm_temperature: transient left out, s
  double rfm_sample = 1e-3;               ///< rfm_temperature: time between T samples, s
  int rfm_blocks = 10;                    ///< rfm_temperature: blocks of the T average (T.2.20)
  std::uint64_t rfm_seed = 1;             ///< rfm_temperature: placement and noise seed
  double rfm_reference_dt_over_tc = 0.0;  ///< Gear 6 reference Δt/t_c (0: the study's)
};

struct StudySpec {
  std::string file;  ///< path, for messages
  std::string name = "study";
  std::vector<StudyProblem> problems;
  std::vector<IntegratorKind> integrators;
  std::vector<double> dt_over_tc;            ///< Δt / contact time
  std::vector<BroadPhaseKind> broad_phases;  ///< only walled problems (pile) vary it
  std::vector<bool> hdot_fd;                 ///< Model P: false analytic, true finite difference
  std::vector<bool> clip;                    ///< Model S (ε < 1 problems)
  std::vector<bool> rocking;                 ///< Model P
  std::vector<bool> early_rest;              ///< tapping only
  double reference_dt_over_tc = 0.0;         ///< reference Δt (0: smallest of the matrix / 2)
  std::vector<double> tap_dt_over_tc;        ///< tapping's own Δt list (empty: the matrix's)
  std::vector<double> rfm_dt_over_tc;        ///< rfm_temperature's own Δt list (empty: matrix)
  StudySizes sizes;
  // stability map: Δt sweep from start, ×factor, until blow-up or max
  bool stability = false;
  std::vector<StudyProblem> stability_problems;
  double stability_start = 0.05;
  double stability_factor = 1.25;
  double stability_max = 3.0;
};

/// parse and validate a study file; InputError names file:line and key
StudySpec parse_study_file(const std::string& path);

/// "hdot=analytic rocking=on", "clip=off", or "-" for the switches relevant to a problem
std::string study_switches_text(StudyProblem p, const StudySwitches& s);

/// register `gransim study` on the app (app/study/study_cli.cpp); cli.cpp dispatches when it is
/// given
CLI::App* add_study_command(CLI::App& app, StudyOptions& o);

/// exit code: 0 done (unstable combinations are results, not failures), 2 bad input
int study_command(const StudyOptions& opt);

}  // namespace gs
