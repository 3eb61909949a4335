"""The tapping paper's time-step check (section IV): runs repeated with a smaller Δt keep the
mean, the variance and the shape of the distribution of φ. The study's plan (standard and
full budgets) runs Δt halved at two pulse strengths as long as its own runs (sweep timestep,
analysed apart in analysis/timestep); the claim compares each with the study's run at the same
g_p."""
import math
import os

import numpy as np

from .report import Claim, test_of
from .tapping_data import _fig, _finish, read_csv, read_json
from .verdicts import UNRESOLVED, decide, tau_int

Z80 = 1.96 + 0.8416


def _normal_sf2(z):
    """two-sided p of a standard normal z"""
    return math.erfc(abs(z) / math.sqrt(2))


def ks_p(d, n1, n2):
    """asymptotic p of the two-sample Kolmogorov–Smirnov distance d for sizes n1, n2"""
    ne = n1 * n2 / (n1 + n2)
    lam = (math.sqrt(ne) + 0.12 + 0.11 / math.sqrt(ne)) * d
    if lam < 0.2:
        return 1.0
    return max(0.0, min(1.0, 2 * sum((-1) ** (k - 1) * math.exp(-2 * k * k * lam * lam)
                                     for k in range(1, 101))))


def compare(a, b):
    """mean, variance and shape of two series of φ with serial correlation (n_eff = n/2τ_int):
    p of each test and the smallest mean shift and σ ratio found at 80 % (5 % test)"""
    a, b = np.asarray(a, float), np.asarray(b, float)
    na, nb = len(a) / (2 * tau_int(a)), len(b) / (2 * tau_int(b))
    sa, sb = a.std(ddof=1), b.std(ddof=1)
    se = math.sqrt(sa ** 2 / na + sb ** 2 / nb)
    p_mean = _normal_sf2((a.mean() - b.mean()) / se)
    s_ln = math.sqrt(2 / max(na - 1, 1) + 2 / max(nb - 1, 1))  # of ln(s_a²/s_b²)
    p_var = _normal_sf2(math.log(sa ** 2 / sb ** 2) / s_ln)
    za, zb = np.sort((a - a.mean()) / sa), np.sort((b - b.mean()) / sb)
    grid = np.concatenate([za, zb])
    d = float(np.max(np.abs(np.searchsorted(za, grid, "right") / len(za)
                            - np.searchsorted(zb, grid, "right") / len(zb))))
    return {"dmean": float(a.mean() - b.mean()), "se": se, "ratio": sa / sb, "ks": d,
            "p": {"mean": p_mean, "variance": p_var, "shape": ks_p(d, na, nb)},
            "mde_mean": Z80 * se, "mde_ratio": math.exp(Z80 * s_ln / 2)}


NULL = "Δt/2 leaves the mean, the variance and the shape of P(φ) unchanged"
ALT = "none sized by the source"


def timestep_verdict(comparisons):
    """mean, variance and shape unchanged by Δt/2, over the pairs of compare(): the family's
    smallest p, Bonferroni over its 3·pairs tests. The source sizes no change that would count
    (nor does Tejada et al.'s width and shape effect it cites), so the claim has no alternative
    and no power: it disagrees at the family's 1 % level and otherwise stays not resolved"""
    k = 3 * len(comparisons)
    pmin = min(p for c in comparisons for p in c["p"].values())
    return decide(min(1.0, pmin * k), float("nan"), NULL, ALT,
                  f"smallest p {pmin:.3g} of {k} tests (mean: Welch; variance: log-ratio; shape: "
                  "Kolmogorov–Smirnov of the standardised taps; effective sizes n/2τ_int), "
                  "Bonferroni-corrected", float("nan"))


class _Runs:
    """a sub-analysis (analysis/timestep): its summary and each run's steady taps"""

    def __init__(self, folder, sub):
        a = os.path.join(folder, "analysis", sub)
        self.summary = read_csv(os.path.join(a, "summary.csv"))
        self.discard = int(read_json(os.path.join(a, "analysis.json")).get("discard", 10))
        runs = read_csv(os.path.join(a, "runs.csv"))
        self.run_dir = {r["label"]: str(r.get("dir", "")) for r in runs}

    def used(self, label):
        cut = next((int(r["discard"]) for r in self.summary if r["label"] == label
                    and isinstance(r.get("discard"), float)), self.discard)
        d = self.run_dir.get(label, "")
        rows = read_csv(os.path.join(d, "taps.csv")) if d else []
        return np.array([r["phi"] for r in rows if r.get("tap", 0) > cut], float)


def timestep(st, budget):
    """section IV: Δt halved changes neither the mean, the variance nor the shape"""
    half = _Runs(st.folder, "timestep")
    quote = ("we repeated some of the simulations with a time step of Δt = 10⁻⁵ s. We found that "
             "the mean volume fraction, the volume fraction variance and also the shape of the "
             "volume fraction distribution did not change on reduction of the time step")
    pairs = []
    for r in half.summary:
        main = next((m for m in st.runs(r["protocol"]) if m["control"] == r["control"]), None)
        if main is None:
            continue
        x, y = half.used(r["label"]), st.used(main["label"], "phi")
        if len(x) >= 8 and len(y) >= 8:
            pairs.append((r["control"], compare(x, y), x, y))
    if not pairs:
        why = ("no run with Δt halved at this budget: the standard and full budgets' plan runs "
               "them (sweep timestep, g_p = 6 and 20, as many taps as the study's runs)"
               if not half.summary else "no Δt-halved run matches a study run with ≥ 8 taps")
        return Claim("timestep", "Time step", quote, "section IV", "not run", UNRESOLVED,
                     why + "; the source sizes no change that would count, so once run the "
                     "claim can disagree but not agree", "the standard budget" if budget in
                     ("smoke", "quick") else "the sweep timestep of this budget, run to its end",
                     null=NULL, alternative=ALT)
    v = timestep_verdict([c for _, c, _, _ in pairs])
    meas = "; ".join(
        f"g_p={g:g}: Δφ̄ {c['dmean']:+.5f} ± {1.96 * c['se']:.5f} (p {c['p']['mean']:.2g}), "
        f"σ ratio {c['ratio']:.3f} (p {c['p']['variance']:.2g}), KS {c['ks']:.3f} "
        f"(p {c['p']['shape']:.2g})" for g, c, _, _ in pairs)
    smallest = "; ".join(f"g_p={g:g}: a mean shift ≥ {c['mde_mean']:.5f} or σ ratio ≥ "
                         f"{c['mde_ratio']:.2f}" for g, c, _, _ in pairs)
    v.reason += f". The smallest changes these runs find at 80 % (5 % test): {smallest}"
    fig, ax = _fig()
    for g, _, x, y in pairs:
        line = ax.hist(y, bins=15, density=True, histtype="step", label=f"g_p={g:g}, Δt")[2][0]
        ax.hist(x, bins=15, density=True, histtype="step", ls="--", color=line.get_edgecolor(),
                label=f"g_p={g:g}, Δt/2")
    chart = _finish(st, fig, ax, "φ", "density", "timestep", 7)
    return Claim("timestep", "Time step", quote, "section IV", meas, v.verdict, v.reason,
                 "" if v.verdict != UNRESOLVED else "a size of change that the source would call "
                 "a failure (it states none), or a change beyond the 1 % level", chart,
                 {"p_min": min(p for _, c, _, _ in pairs for p in c["p"].values())}, **test_of(v))
