"""stickslip's Sobol' estimators (uncertainty/sobol.hpp) against OpenTURNS,
the field's reference library, on the same input/output sample: OpenTURNS's
own SobolIndicesExperiment, the Ishigami function and the g-function.
stickslip's first and total indices of a deterministic model (y_A2 = y_A)
must equal SaltelliSensitivityAlgorithm.getFirstOrderIndices() and
JansenSensitivityAlgorithm.getTotalOrderIndices() to 1e-10.

OpenTURNS's sample is the blocks A, B, E_1..E_d of N rows each, E_i being A
with column i taken from B; stickslip's row j is (y_A, y_A2, y_B, y_E[0..d-1])
of row j of each block (sobol.hpp)."""
import numpy as np
import pytest

ot = pytest.importorskip("openturns")
from stickslip import _stickslip  # noqa: E402


def ishigami(x, a=7.0, b=0.1):
    return np.sin(x[:, 0]) + a * np.sin(x[:, 1]) ** 2 + b * x[:, 2] ** 4 * np.sin(x[:, 0])


G_A = np.array([0.0, 1.0, 4.5, 9.0, 99.0, 99.0])


def g_function(x):
    return np.prod((np.abs(4 * x - 2) + G_A) / (1 + G_A), axis=1)


CASES = {
    "ishigami": (ishigami, [ot.Uniform(-np.pi, np.pi)] * 3),
    "g-function": (g_function, [ot.Uniform(0.0, 1.0)] * len(G_A)),
}


def openturns_design(law, n, seed):
    ot.RandomGenerator.SetSeed(seed)
    return np.array(ot.SobolIndicesExperiment(ot.ComposedDistribution(law), n).generate())


def blocks(values, n, d):
    """The A, B and E_i blocks of OpenTURNS's row order."""
    return values[:n], values[n:2 * n], [values[(2 + i) * n:(3 + i) * n] for i in range(d)]


@pytest.mark.parametrize("name", sorted(CASES))
def test_design_layout_is_the_documented_one(name):
    _, law = CASES[name]
    d, n = len(law), 50
    a, b, e = blocks(openturns_design(law, n, 1), n, d)
    for i in range(d):
        for k in range(d):
            np.testing.assert_array_equal(e[i][:, k], b[:, k] if k == i else a[:, k])


@pytest.mark.parametrize("name", sorted(CASES))
@pytest.mark.parametrize("n,seed", [(100, 1), (1000, 2), (20000, 3)])
def test_agrees_with_openturns_saltelli_and_jansen(name, n, seed):
    f, law = CASES[name]
    d = len(law)
    x = openturns_design(law, n, seed)
    y = f(x)
    y_a, y_b, y_e = blocks(y, n, d)
    ours = _stickslip.sobol_indices(y_a, y_a, y_b, np.column_stack(y_e))
    xs, ys = ot.Sample(x), ot.Sample(y[:, None])
    saltelli = ot.SaltelliSensitivityAlgorithm(xs, ys, n)
    jansen = ot.JansenSensitivityAlgorithm(xs, ys, n)
    np.testing.assert_allclose(ours["first_order"], np.array(saltelli.getFirstOrderIndices()),
                               rtol=0, atol=1e-10)
    np.testing.assert_allclose(ours["total_order"], np.array(jansen.getTotalOrderIndices()),
                               rtol=0, atol=1e-10)
    # A deterministic model: no intrinsic variance, all of it the parameters'.
    assert ours["intrinsic_variance"] == 0
    assert ours["parameter_share"] == 1
    assert ours["response_first_order"] == ours["first_order"]
    assert ours["rows"] == n
    np.testing.assert_allclose(ours["variance"], np.var(y_a, ddof=1), rtol=1e-12)


def test_intervals_are_centred_and_never_clip():
    f, law = CASES["g-function"]
    d, n = len(law), 200
    x = openturns_design(law, n, 1)
    y_a, y_b, y_e = blocks(f(x), n, d)
    ours = _stickslip.sobol_indices(y_a, y_a, y_b, np.column_stack(y_e))
    for key in ("first_order", "total_order"):
        for value, (lo, hi) in zip(ours[key], ours[key + "_ci95"]):
            assert lo <= value <= hi
            assert value - lo == pytest.approx(hi - value, rel=1e-12, abs=1e-15)
    # The inputs with a_i = 99 have first-order indices ~7e-5: at N = 200
    # some estimates are negative (here 4 of 6), and they are reported as such.
    assert min(ours["first_order"]) < 0


def test_bad_shapes_are_refused():
    with pytest.raises(_stickslip.Error, match="same number of rows"):
        _stickslip.sobol_indices(np.zeros(3), np.zeros(3), np.zeros(4), np.zeros((3, 2)))
    with pytest.raises(_stickslip.Error, match="openturns_saltelli or saltelli_2010"):
        _stickslip.sobol_indices(np.zeros(3), np.zeros(3), np.zeros(3), np.zeros((3, 2)),
                                 form="jansen")


@pytest.mark.parametrize("name", sorted(CASES))
def test_intervals_match_openturns_asymptotic_ones(name):
    """OpenTURNS's asymptotic intervals are the delta method on (y_B y_E,
    y_A^2) and ((y_A - y_E)^2, y_A^2) of its centred outputs; ours also
    differentiate through the sample means, terms that vanish as N grows:
    the half-widths agree to 4e-3 or better at N = 4000 (tested to 1e-2)."""
    f, law = CASES[name]
    d, n = len(law), 4000
    x = openturns_design(law, n, 5)
    y = f(x)
    y_a, y_b, y_e = blocks(y, n, d)
    ours = _stickslip.sobol_indices(y_a, y_a, y_b, np.column_stack(y_e))
    xs, ys = ot.Sample(x), ot.Sample(y[:, None])
    for algorithm, key, interval in (
            (ot.SaltelliSensitivityAlgorithm, "first_order", "getFirstOrderIndicesInterval"),
            (ot.JansenSensitivityAlgorithm, "total_order", "getTotalOrderIndicesInterval")):
        a = algorithm(xs, ys, n)
        a.setUseAsymptoticDistribution(True)
        assert a.getConfidenceLevel() == pytest.approx(0.95)
        ci = getattr(a, interval)()
        theirs = (np.array(ci.getUpperBound()) - np.array(ci.getLowerBound())) / 2
        half = np.array([(hi - lo) / 2 for lo, hi in ours[key + "_ci95"]])
        np.testing.assert_allclose(half, theirs, rtol=1e-2)


@pytest.mark.parametrize("form", ["openturns_saltelli", "saltelli_2010"])
def test_stochastic_estimates_equal_the_header_formulas(form):
    """With a replicate y_A2 != y_A (a noisy output), every estimate equals
    sobol.hpp's formula computed here in two passes with numpy, for both
    first-order forms: the streaming accumulator adds nothing but rounding."""
    f, law = CASES["ishigami"]
    d, n = len(law), 5000
    x = openturns_design(law, n, 7)
    rng = np.random.default_rng(7)
    y_a, y_b, y_e = blocks(f(x) + 2.0 * rng.standard_normal(len(x)), n, d)
    y_a2 = f(x[:n]) + 2.0 * rng.standard_normal(n)
    ours = _stickslip.sobol_indices(y_a, y_a2, y_b, np.column_stack(y_e), form=form)
    c = np.mean(np.concatenate([y_a, y_b] + y_e))
    v = np.var(y_a, ddof=1)
    s2 = np.sum((y_a - y_a2) ** 2) / (2 * n)
    if form == "openturns_saltelli":
        vi = [np.sum((y_b - c) * (e - c)) / (n - 1) - np.mean(y_a - c) * np.mean(y_b - c)
              for e in y_e]
    else:
        vi = [np.mean(y_b * (e - y_a)) for e in y_e]
    vti = [(np.sum((y_a - e) ** 2) - np.sum((y_a - y_a2) ** 2)) / (2 * n - 1) for e in y_e]
    assert ours["intrinsic_variance"] > 0
    np.testing.assert_allclose(ours["mean"], c, rtol=1e-12)
    np.testing.assert_allclose(ours["variance"], v, rtol=1e-12)
    np.testing.assert_allclose(ours["intrinsic_variance"], s2, rtol=1e-12)
    np.testing.assert_allclose(ours["first_order"], np.array(vi) / (v - s2), rtol=0, atol=1e-12)
    np.testing.assert_allclose(ours["total_order"], np.array(vti) / (v - s2), rtol=0, atol=1e-12)
    np.testing.assert_allclose(ours["response_first_order"], np.array(vi) / v, rtol=0, atol=1e-12)
    np.testing.assert_allclose(ours["parameter_share"], (v - s2) / v, rtol=1e-12)
    np.testing.assert_allclose(ours["intrinsic_share"], s2 / v, rtol=1e-12)
