# every public function and method of the module given random types and values (Hypothesis):
# each call returns or raises a Python error a caller can handle — InputError (naming the
# function and the argument) for a bad value, TypeError for a wrong type — and never crashes the
# interpreter or lets a C++ exception through as a bare RuntimeError. A fixed number of examples
# per function, derandomised, so that the test is repeatable and takes tens of seconds.
import math
import os
import tempfile

import numpy as np
import pytest

# Hypothesis keeps a cache (its Unicode tables) in ./.hypothesis unless told otherwise: the
# temporary directory, not the source tree
os.environ.setdefault("HYPOTHESIS_STORAGE_DIRECTORY",
                      os.path.join(tempfile.gettempdir(), "gransim-hypothesis"))
hypothesis = pytest.importorskip("hypothesis")
from hypothesis import HealthCheck, given, settings, strategies as st  # noqa: E402

import conftest  # noqa: E402

EXAMPLES = int(os.environ.get("GS_FUZZ_EXAMPLES", "40"))
fuzz = settings(max_examples=EXAMPLES, deadline=None, derandomize=True, database=None,
                suppress_health_check=list(HealthCheck))

# ---- values --------------------------------------------------------------------------------

edge_ints = st.sampled_from([-2**70, -2**63, -2**31 - 1, -5, -1, 0, 1, 2, 3, 7, 2**31, 2**63, 2**70])
ints = st.one_of(edge_ints, st.integers(-300, 300))
edge_floats = st.sampled_from([0.0, -0.0, -5.0, -1.0, 1e-300, -1e-300, 1e300, -1e300, 5e-324,
                               math.inf, -math.inf, math.nan, 0.5, 1.0, 1.5, 2.0, 0.01])
floats = st.one_of(edge_floats, st.floats(allow_nan=True, allow_infinity=True),
                   st.floats(-10, 10))
numbers = st.one_of(ints, floats)
texts = st.one_of(st.sampled_from(["", "histogram", "kde", "exact", "rounded", "x", "-1"]),
                  st.text(max_size=6))
float_lists = st.lists(numbers, max_size=40)
arrays = st.one_of(
    st.builds(lambda n, m, v: np.full((n, m), v), st.integers(0, 30), st.integers(1, 3), floats),
    st.builds(lambda n, v: np.full(n, v), st.integers(0, 30), floats),
    st.builds(lambda n, s: np.random.default_rng(s).normal(size=(n, 2)), st.integers(0, 60),
              st.integers(0, 9)),
    st.builds(lambda h, w, c, v: np.full((h, w, c), v, dtype=np.uint8), st.integers(0, 12),
              st.integers(0, 12), st.integers(1, 5), st.integers(0, 255)),
    st.just(np.zeros((2, 2, 2))), st.just(np.array([], dtype=object)),
    st.just(np.array(["a", "b"])))
# anything at all, of any type
anything = st.one_of(st.none(), st.booleans(), numbers, texts, float_lists, arrays,
                     st.dictionaries(texts, numbers, max_size=3))


def phi_series(min_size=0, max_size=120):
    """volume fractions near a pile's, sometimes with a bad value among them"""
    good = st.floats(0.78, 0.86)
    return st.one_of(st.lists(good, min_size=min_size, max_size=max_size),
                     st.lists(st.one_of(good, floats), min_size=min_size, max_size=max_size))


def arg(plausible):
    """a plausible value most of the time, anything at all otherwise"""
    return st.one_of(plausible, plausible, anything)


def outcome(call):
    """the call's result, or the Python error it raised; an error outside the handled ones
    (an unknown C++ exception surfaces as a bare RuntimeError) fails the test"""
    import gransim
    try:
        return call()
    except (gransim.InputError, TypeError) as e:
        return e
    except gransim.OutputError as e:  # a file that cannot be written
        return e
    except (gransim.HealthError, gransim.RenderError) as e:
        return e
    except MemoryError as e:
        return e
    except Exception as e:  # noqa: BLE001
        pytest.fail(f"{type(e).__name__} (not an InputError or TypeError): {e}")


def check_names_argument(e, function):
    """a value error names the function it came from"""
    import gransim
    if isinstance(e, gransim.InputError) and function:
        assert function in str(e) or e.key, str(e)


# ---- the tapping analysis --------------------------------------------------------------------

runs = st.lists(st.one_of(
    st.fixed_dictionaries({"phi": phi_series(0, 80)},
                          optional={"label": arg(texts), "protocol": arg(texts),
                                    "control": arg(numbers), "tap": arg(float_lists),
                                    "phi_left": arg(phi_series()), "phi_right": arg(phi_series())}),
    anything), max_size=3)


@fuzz
@given(runs=arg(runs), discard=arg(st.integers(-10, 30)), level=arg(st.floats(0, 1)),
       alpha=arg(st.floats(0, 1)), test_area=arg(st.floats(0, 1)), method=arg(texts),
       bins=arg(st.integers(-2, 50)), phi_rlp=arg(st.floats(0.7, 0.9)),
       phi_rcp=arg(st.floats(0.8, 1.0)), bootstrap=arg(st.integers(-2, 5)),
       discard_auto=arg(st.booleans()))
def test_tap_analysis(gransim, runs, discard, level, alpha, test_area, method, bins, phi_rlp,
                      phi_rcp, bootstrap, discard_auto):
    e = outcome(lambda: gransim.tap_analysis(
        runs, discard=discard, level=level, alpha=alpha, test_area=test_area, method=method,
        bins=bins, phi_rlp=phi_rlp, phi_rcp=phi_rcp, bootstrap=bootstrap,
        discard_auto=discard_auto))
    check_names_argument(e, "tap_analysis")


def test_tap_analysis_negative_discard_is_an_input_error(gransim):
    phi = list(np.random.default_rng(1).uniform(0.80, 0.84, 50))
    for d in (-5, -1):
        with pytest.raises(gransim.InputError, match="discard") as e:
            gransim.tap_analysis([{"phi": phi}], discard=d, test_area=0.01)
        assert e.value.key == "discard"


@fuzz
@given(ref=arg(phi_series(0, 200)), phi=arg(phi_series(0, 200)), v_g=arg(st.floats(0, 1)),
       method=arg(texts), bins=arg(st.integers(-2, 40)), min_fraction=arg(st.floats(0, 1)),
       volume=st.booleans())
def test_beta_from_phi_and_volume(gransim, ref, phi, v_g, method, bins, min_fraction, volume):
    if volume:
        outcome(lambda: gransim.beta_from_volume(ref, phi, method, bins, min_fraction))
    else:
        outcome(lambda: gransim.beta_from_phi(ref, phi, v_g, method, bins, min_fraction))


@fuzz
@given(beta=arg(float_lists), phi=arg(phi_series(0, 10)), phi_err=arg(float_lists),
       beta_err=arg(float_lists), rlp=arg(st.floats(0.7, 0.9)), rcp=arg(st.floats(0.8, 1.0)),
       a=arg(st.floats(1, 1000)), v_g=arg(st.floats(0, 1)))
def test_quadron(gransim, beta, phi, phi_err, beta_err, rlp, rcp, a, v_g):
    outcome(lambda: gransim.fit_quadron(beta, phi, phi_err, beta_err, rlp, rcp))
    outcome(lambda: gransim.quadron_phi(beta, a, rlp, rcp))
    outcome(lambda: gransim.quadron_lnz(beta, a, v_g, rlp, rcp))


@fuzz
@given(beta=arg(st.floats(0, 2000)), taps=arg(st.integers(-3, 300)), a=arg(st.floats(1, 1000)),
       v_g=arg(st.floats(0, 1)), refresh=arg(st.floats(0, 1)), seed=arg(ints), stream=arg(ints),
       x=arg(float_lists), c=arg(st.floats(0, 10)), batch=arg(st.integers(-2, 10)),
       alpha=arg(st.floats(0, 1)), bins=arg(st.integers(-2, 30)))
def test_series_statistics(gransim, beta, taps, a, v_g, refresh, seed, stream, x, c, batch, alpha,
                           bins):
    outcome(lambda: gransim.quadron_gas_phi(beta, taps, a, v_g, refresh, seed, stream))
    outcome(lambda: gransim.autocorr_time(x, c))
    outcome(lambda: gransim.mser_truncation(x, batch))
    outcome(lambda: gransim.normality_chi2(x, alpha, bins))


# ---- the Random Force Model analyses ---------------------------------------------------------

points = st.one_of(arrays, st.builds(lambda n, s, box: np.random.default_rng(s).uniform(
    -box, 2 * box, size=(n, 2)), st.integers(0, 80), st.integers(0, 9), st.floats(0.1, 10)))


@fuzz
@given(box=arg(st.floats(0, 10)), n_max=arg(st.integers(-2, 40)), grouping=arg(texts),
       pts=arg(points), k_lo=arg(st.floats(0, 50)), k_hi=arg(st.floats(0, 100)),
       n=arg(st.integers(-2, 1000)), d=arg(st.floats(0, 0.1)), eps=arg(st.floats(0, 1)))
def test_structure_factor(gransim, box, n_max, grouping, pts, k_lo, k_hi, n, d, eps):
    s = outcome(lambda: gransim.rfm.StructureFactor2D(box, n_max, grouping))
    if isinstance(s, Exception):
        return
    outcome(lambda: s.add_snapshot(pts))
    outcome(lambda: s.shells())
    outcome(lambda: s.fit_df(k_lo, k_hi))
    outcome(lambda: s.fit_df_rfm(box, n, d, eps, eps))


@fuzz
@given(box=arg(st.floats(0, 10)), r_max=arg(st.floats(0, 5)), bins=arg(st.integers(-2, 100)),
       pts=arg(points))
def test_pair_correlation(gransim, box, r_max, bins, pts):
    g = outcome(lambda: gransim.rfm.PairCorrelation2D(box, r_max, bins))
    if isinstance(g, Exception):
        return
    outcome(lambda: g.add_snapshot(pts))
    outcome(lambda: g.bins())


@fuzz
@given(v_max=arg(st.floats(0, 5)), l_min=arg(st.floats(0, 1)), l_max=arg(st.floats(0, 10)),
       bins=arg(st.integers(-2, 100)), values=arg(points), lo=arg(st.floats(0, 100)),
       hi=arg(st.floats(0, 1e4)), v_abs=arg(st.floats(0, 2)), scale=arg(st.floats(0, 3)),
       alpha=arg(st.floats(0, 3)), fit_alpha=arg(st.booleans()), min_count=arg(st.floats(0, 20)))
def test_histograms_and_fits(gransim, v_max, l_min, l_max, bins, values, lo, hi, v_abs, scale,
                             alpha, fit_alpha, min_count):
    r = gransim.rfm
    for h in (outcome(lambda: r.velocity_histogram(v_max, bins)),
              outcome(lambda: r.free_path_histogram(l_min, l_max, bins))):
        if isinstance(h, Exception):
            continue
        outcome(lambda: h.add(values))
        outcome(lambda: h.add(np.abs(np.asarray(values, dtype=float)).ravel()
                              if isinstance(values, np.ndarray) and values.dtype != object
                              and values.dtype.kind in "fiu" else values))
        outcome(lambda: h.bins())
        outcome(lambda: r.fit_tail(h, lo, hi, v_abs, scale))
        outcome(lambda: r.fit_crossover(h, alpha, fit_alpha, min_count))
        outcome(lambda: r.fit_free_paths(h, l_min, min_count))


@fuzz
@given(x=arg(arrays), y=arg(arrays), e=arg(arrays), m_max=arg(st.integers(-2, 20)),
       block=arg(st.integers(-2, 20)), box=arg(st.floats(0, 10)), n=arg(st.integers(-2, 100)),
       d=arg(st.floats(0, 0.5)), h=arg(st.integers(-2, 5)), lr=arg(st.floats(0, 10)))
def test_moments_gaps_and_lines(gransim, x, y, e, m_max, block, box, n, d, h, lr):
    r = gransim.rfm
    outcome(lambda: r.abs_moments(x, m_max))
    outcome(lambda: r.fit_scaling_exponent(x, y, e))
    outcome(lambda: r.granular_temperature(x))
    outcome(lambda: r.block_average(x, block))
    outcome(lambda: r.reduced_length(box, n, d))
    outcome(lambda: r.reduced_coordinates(x, box, d))
    outcome(lambda: r.neighbour_gaps(x, lr, h))
    outcome(lambda: r.fit_line(x, y, e))
    outcome(lambda: r.fit_power_law(x, y, e))
    outcome(lambda: r.mean_free_path(box, d, n))


# ---- the simulation, pictures and movies -----------------------------------------------------

@pytest.fixture(scope="module")
def sim(gransim):
    return gransim.Simulation(conftest.one_disk())


# (step counts and times stay small or invalid: a valid long run is no finding, only slow)
not_a_number = st.one_of(st.none(), texts, float_lists, arrays)


@fuzz
@given(n=st.one_of(st.integers(-3, 50), st.sampled_from([-2**63, -2**70, 2**64]), floats,
                   not_a_number),
       t=st.one_of(st.sampled_from([-1.0, 0.0, 1e-5, 1e-4, 1e300, 1e20, -0.0, 5e-324, math.nan,
                                    math.inf, -math.inf]), not_a_number),
       k=arg(st.integers(-3, 2)), rect=arg(st.lists(st.floats(-1, 2), min_size=4, max_size=4)),
       channels=arg(st.integers(2, 5)), options=st.dictionaries(
           st.sampled_from(["width", "height", "color_by", "renderer", "zoom", "nonsense"]),
           anything, max_size=2))
def test_simulation_methods(gransim, sim, n, t, k, rect, channels, options):
    outcome(lambda: sim.step(n))
    outcome(lambda: sim.run(t))
    outcome(lambda: sim.run_to_tap(k))
    outcome(lambda: sim.measure_tap(rect))
    outcome(lambda: sim.phi(rect))
    outcome(lambda: sim.contacts())
    outcome(lambda: sim.render(channels, **options))
    for name in ("x", "y", "vx", "vy", "theta", "omega", "species", "radius", "mass", "ids",
                 "positions", "velocities", "t", "step_count", "tap", "box", "gravity"):
        getattr(sim, name)


@pytest.mark.filterwarnings("ignore::RuntimeWarning")  # NumPy's cast of NaN to uint8
@fuzz
@given(image=arg(arrays), channels=arg(st.integers(2, 5)), name=arg(texts),
       size=arg(st.integers(-2, 40)), fps=arg(st.integers(-1, 60)), crf=arg(st.integers(-1, 60)),
       index=arg(st.integers(-2, 3)))
def test_pictures_and_movies(gransim, tmp_path_factory, image, channels, name, size, fps, crf,
                             index):
    d = tmp_path_factory.mktemp("fuzz")
    path = str(d / (name if isinstance(name, str) and name and "/" not in name and "\0" not in
                    name else "x.png"))
    outcome(lambda: gransim.write_png(path, image))
    outcome(lambda: gransim.read_png(path, channels))
    if gransim.have_movie:
        movie = str(d / "m.mp4")
        enc = outcome(lambda: gransim.MovieEncoder(movie, size, size, fps, crf, "ultrafast"))
        if not isinstance(enc, Exception):
            outcome(lambda: enc.add_frame(image))
            outcome(lambda: enc.close())
        outcome(lambda: gransim.probe_movie(movie))
        outcome(lambda: gransim.movie_frame(movie, index, channels))
