# the analyses on in-memory series with known answers: overlapping histograms of Gaussian
# samples, the tapping analysis of a synthetic quadron gas, and the RFM statistics
import numpy as np
import pytest


def test_beta_of_gaussian_series(gransim):
    # x = 1/φ normal with equal σ: Q = ln(P₁/P₀) = (μ₁ − μ₀)/σ² · x − (μ₁² − μ₀²)/(2σ²), so
    # β − β_ref = −slope/V_g and ln Z − ln Z_ref = −intercept
    rng = np.random.default_rng(5)
    mu0, mu1, sigma, v_g, n = 1.20, 1.21, 0.01, 0.1, 40000
    phi0 = 1.0 / rng.normal(mu0, sigma, n)
    phi1 = 1.0 / rng.normal(mu1, sigma, n)
    b = gransim.beta_from_phi(phi0, phi1, v_g)
    assert b["valid"]
    slope = (mu1 - mu0) / sigma**2
    intercept = -(mu1**2 - mu0**2) / (2 * sigma**2)
    assert b["dbeta"] == pytest.approx(-slope / v_g, abs=4 * b["dbeta_err"])
    assert b["dbeta"] == pytest.approx(-slope / v_g, rel=0.05)
    assert b["dlnz"] == pytest.approx(-intercept, abs=4 * b["dlnz_err"])
    fit = b["fit"]
    assert len(fit["x"]) == len(fit["q"]) >= 5
    # the fitted points lie on the exact line
    exact = slope * fit["x"] + intercept
    assert np.all(np.abs(fit["q"] - exact) < 5 * fit["q_err"] + 0.05)


def test_tap_analysis_of_quadron_gas(gransim):
    a, v_g = 556.5, 0.13
    betas = [300.0, 600.0]
    runs = [{"label": f"b{b:g}", "protocol": "negative_g", "control": k + 1,
             "phi": gransim.quadron_gas_phi(b, 3000, a=a, v_g=v_g, refresh=0.5, seed=11, stream=k)}
            for k, b in enumerate(betas)]
    r = gransim.tap_analysis(runs, discard=0, reference="b300", test_area=v_g / 0.83,
                             bootstrap=0)
    assert [s["label"] for s in r["runs"]] == ["b300", "b600"]
    for s, b in zip(r["runs"], betas):
        assert s["n_used"] == 3000
        assert s["phi_mean"] == pytest.approx(float(gransim.quadron_phi(b, a)), abs=4 * s["phi_err"])
        # refresh p = 0.5: ρ(t) = (1 − p)^t, τ_int = (2 − p)/(2p)
        assert s["tau_int"] == pytest.approx(1.5, abs=3 * s["tau_err"] + 0.1)
    assert r["ref"] == 0
    d = r["beta"][1]
    assert d["valid"]
    # β is relative to the reference; V_g of the analysis is test_area·φ̄_ref, not quite v_g
    scale = r["v_g"] / v_g
    assert d["dbeta"] * scale == pytest.approx(betas[1] - betas[0], abs=3 * d["dbeta_err"] * scale)
    assert d["dbeta_err"] * scale < 0.3 * (betas[1] - betas[0])


def test_quadron_functions_are_vectorised(gransim):
    beta = np.array([100.0, 1000.0, 1e4])
    phi = gransim.quadron_phi(beta, 556.5)
    assert phi.shape == (3,) and np.all(np.diff(phi) > 0)
    assert 0.81 < phi[0] < phi[-1] < 0.855


def test_autocorr_and_normality(gransim):
    rng = np.random.default_rng(1)
    white = rng.normal(size=5000)
    t = gransim.autocorr_time(white)
    assert t["tau_int"] == pytest.approx(0.5, abs=0.1)
    assert gransim.normality_chi2(white)["normal"]
    assert not gransim.normality_chi2(rng.exponential(size=5000))["normal"]


def test_mser_truncation_and_discard_auto(gransim):
    # a 5σ step over the first 40 taps is cut where it ends (the C++ tests give the statistics)
    rng = np.random.default_rng(3)
    x = rng.normal(size=250)
    x[:40] += 5.0
    t = gransim.mser_truncation(x)
    assert 40 <= t["drop"] <= 60 and t["steady"]
    runs = [{"phi": 0.83 + 0.002 * x, "control": 2.0},
            {"phi": 0.82 + 0.002 * rng.normal(size=250), "control": 6.0}]
    fixed = gransim.tap_analysis(runs, bootstrap=0)["runs"]
    auto = gransim.tap_analysis(runs, discard_auto=True, bootstrap=0)["runs"]
    assert fixed[0]["discard"] == 10 and auto[0]["discard"] == t["drop"]
    assert auto[0]["phi_mean"] == pytest.approx(0.83, abs=0.001)
    assert fixed[0]["phi_mean"] > auto[0]["phi_mean"] + 0.001  # the step left in


def test_rfm_moments_temperature_and_fits(gransim):
    rfm = gransim.rfm
    rng = np.random.default_rng(2)
    sigma = 0.3
    v = rng.normal(0.0, sigma, size=(100000, 2))
    m = rfm.abs_moments(v[:, 0], 4)
    assert m[0] == pytest.approx(sigma * np.sqrt(2 / np.pi), rel=0.01)
    assert m[1] == pytest.approx(sigma**2, rel=0.01)
    # T = ⟨|v − ⟨v⟩|²⟩ over both components
    assert rfm.granular_temperature(v) == pytest.approx(2 * sigma**2, rel=0.01)
    x = np.linspace(1, 10, 20)
    p = rfm.fit_power_law(x, 3.0 * x**-1.7)
    assert p["exponent"] == pytest.approx(-1.7, abs=1e-9)
    assert p["amplitude"] == pytest.approx(3.0, rel=1e-9)
    line = rfm.fit_line(x, 2.0 + 0.5 * x)
    assert (line["a"], line["b"]) == (pytest.approx(2.0), pytest.approx(0.5))
    blocks = rfm.block_average(np.arange(100.0), 10)
    assert blocks["mean"] == pytest.approx(49.5) and len(blocks["block_means"]) == 10


def test_rfm_exponential_tail(gransim):
    rfm = gransim.rfm
    rng = np.random.default_rng(3)
    h = rfm.velocity_histogram(12.0, 240)
    h.add(rng.laplace(0.0, 1.0, size=400000))
    assert h.total == 400000
    fit = rfm.fit_tail(h, count_lo=50, count_hi=20000)
    assert fit["alpha"] == pytest.approx(1.0, abs=0.1)
    bins = h.bins()
    assert np.sum(bins["p"] * (bins["hi"] - bins["lo"])) == pytest.approx(1.0, abs=1e-3)


def test_rfm_structure_of_random_points(gransim):
    rfm = gransim.rfm
    rng = np.random.default_rng(4)
    box, n = 1.0, 2000
    sk = rfm.StructureFactor2D(box, 12)
    gr = rfm.PairCorrelation2D(box, 0.3, 30)
    for _ in range(5):
        pts = rng.uniform(0, box, size=(n, 2))
        sk.add_snapshot(pts)
        gr.add_snapshot(pts)
    assert sk.snapshots == 5
    s = sk.shells()
    # an ideal gas: S(k) = 1 and g(R) = 1 everywhere
    assert np.mean(s["s"]) == pytest.approx(1.0, abs=0.05)
    assert s["k"][0] == pytest.approx(2 * np.pi / box)
    g = gr.bins()
    assert np.mean(g["g"][3:]) == pytest.approx(1.0, abs=0.02)


def test_bad_method_is_input_error(gransim):
    with pytest.raises(gransim.InputError) as err:
        gransim.beta_from_phi([0.8] * 10, [0.81] * 10, 0.1, method="spline")
    assert err.value.key == "method"


def test_tap_analysis_without_test_area_is_phi_statistics(gransim):
    # the rule of `gransim analyze`: no test area, no β̂ and no quadron fit, and a note; series
    # without protocol and control are of unknown origin and compared with each other
    rng = np.random.default_rng(8)
    runs = [{"label": "dry", "phi": 0.83 + 0.002 * rng.normal(size=300)},
            {"label": "wet", "phi": 0.82 + 0.002 * rng.normal(size=300)}]
    r = gransim.tap_analysis(runs, bootstrap=0)
    assert [s["label"] for s in r["runs"]] == ["dry", "wet"]
    assert r["beta"] == [] and r["quadron"] == {} and r["v_g"] is None
    assert any("no test area" in n for n in r["notes"])
    assert len(r["pairs"]) == 1 and r["pairs"][0]["p_mean"] < 1e-6  # 0.01 apart, σ 0.002
    assert r["runs"][0]["phi_mean"] == pytest.approx(0.83, abs=0.001)
    r = gransim.tap_analysis(runs, bootstrap=0, test_area=0.16)
    assert len(r["beta"]) == 2 and r["v_g"] == pytest.approx(0.16 * r["runs"][r["ref"]]["phi_mean"])
    with pytest.raises(gransim.InputError, match="test_area"):
        gransim.tap_analysis(runs, test_area=-1.0)
