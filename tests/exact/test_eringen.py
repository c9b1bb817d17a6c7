"""exact-eringen: Eringen's differential nonlocal Euler–Bernoulli beam against its closed forms (Reddy 2007), the
local beam at mu = 0, and the paradox cases where the differential model has no nonlocal effect (Peddieson et al.
2003; Challamel & Wang 2008)."""

import numpy as np
import pytest
from helpers import PAIRS

from pdverify.core.errors import InputError
from pdverify.core.scene_file import parse_scene
from pdverify.exact.eringen import eringen_fields
from pdverify.exact.straight import solve_straight
from pdverify.registry import run

L, P, q, e0a = 2.0, -350.0, -900.0, 0.15
mu = e0a**2
x = np.linspace(0.0, L, 81)
TOL = 1e-12  # closed forms evaluated in double precision: a few round-offs of the largest value


def udl(v=q, shape="uniform"):
    return {"type": "distributed", "value": v, "shape": shape}


def pf(a, v=P):
    return {"type": "point_force", "position": a, "value": v}


def rel(a, b):
    return np.max(np.abs(a - b)) / np.max(np.abs(b))


def test_simply_supported_uniform(make_scene):
    """w = q(x^4 - 2Lx^3 + L^3x)/24EI + mu q(Lx - x^2)/2EI; M the local moment."""
    sc = make_scene("pinned", "pinned", [udl()])
    EI = sc.EI
    f = eringen_fields(sc, mu)(x)
    want = q * (x**4 - 2 * L * x**3 + L**3 * x) / (24 * EI) + mu * q * (L * x - x**2) / (2 * EI)
    assert rel(f["w"], want) < TOL
    assert rel(f["M"], solve_straight(sc, False).fields(x)["M"]) < TOL


def test_simply_supported_sine(make_scene):
    """EI w'''' = q - mu q'' on q0 sin(kx): w = q0 (1 + mu k^2) sin(kx) / EI k^4."""
    sc = make_scene("pinned", "pinned", [udl(shape="sine")])
    k = np.pi / L
    want = q * (1 + mu * k**2) * np.sin(k * x) / (sc.EI * k**4)
    assert rel(eringen_fields(sc, mu)(x)["w"], want) < TOL


def test_centre_force_kinks(make_scene):
    """A force P at a on a simply supported beam: u = mu P (x (L - a)/L - (x - a)+) / EI, a kink of -mu P/EI."""
    a = 0.7
    sc = make_scene("pinned", "pinned", [pf(a)])
    f = eringen_fields(sc, mu)(x)
    local = solve_straight(sc, False).fields(x)["w"]
    u = mu * P * (x * (L - a) / L - np.maximum(x - a, 0.0)) / sc.EI
    assert rel(f["w"], local + u) < TOL


@pytest.mark.parametrize(
    "left,right,loads",
    [("clamped", "clamped", [udl()]), ("clamped", "free", [pf(L)]), ("free", "clamped", [pf(0.0)])],
    ids=["clamped-clamped uniform", "cantilever tip force", "mirrored cantilever tip force"],
)
def test_paradox_no_nonlocal_effect(left, right, loads, make_scene):
    """The differential model's paradox: the deflection and rotation are the local ones at any mu."""
    sc = make_scene(left, right, loads)
    f, local = eringen_fields(sc, mu)(x), solve_straight(sc, False).fields(x)
    assert rel(f["w"], local["w"]) < TOL
    assert rel(f["rotation"], local["rotation"]) < TOL


def test_clamped_clamped_moment_shifts(make_scene):
    """Clamped-clamped under a uniform load: w is the local one, the moment is shifted by mu q."""
    sc = make_scene("clamped", "clamped", [udl()])
    f, local = eringen_fields(sc, mu)(x), solve_straight(sc, False).fields(x)
    assert rel(f["M"], local["M"] + mu * q) < TOL


def test_cantilever_uniform_has_an_effect(make_scene):
    """A cantilever under a uniform load: u = -mu q x^2 / 2EI (u'' = -mu q/EI, u(0) = u'(0) = 0, M kept)."""
    sc = make_scene("clamped", "free", [udl()])
    f, local = eringen_fields(sc, mu)(x), solve_straight(sc, False).fields(x)
    assert rel(f["w"], local["w"] - mu * q * x**2 / (2 * sc.EI)) < TOL


@pytest.mark.parametrize("left,right", PAIRS)
def test_local_limit_and_statics(left, right, make_scene):
    """mu = 0 is exact-eb; at any mu the moment satisfies the same statics (M'' = q, no moment at a free or pinned
    end, no shear at a free or guided end)."""
    sc = make_scene(left, right, [udl(), pf(0.6), udl(300.0, "sine")])
    local = solve_straight(sc, False).fields(x)
    assert rel(eringen_fields(sc, 0.0)(x)["w"], local["w"]) < TOL
    f = eringen_fields(sc, mu)(x)
    scale = np.abs(local["M"]).max()
    for end, sup in ((0, left), (-1, right)):
        if sup in ("free", "pinned"):
            assert abs(f["M"][end]) < TOL * scale
        if sup in ("free", "guided"):
            assert abs(f["V"][end] - local["V"][end]) < TOL * np.abs(local["V"]).max() + 1e-9 * abs(P)


def test_mirror(make_scene):
    """A mirror-image scene gives the mirror-image deflection."""
    a = make_scene("clamped", "pinned", [udl(), pf(0.5)])
    b = make_scene("pinned", "clamped", [udl(), pf(L - 0.5)])
    assert rel(eringen_fields(a, mu)(x)["w"], eringen_fields(b, mu)(L - x)["w"]) < TOL


def test_registered_and_refuses_inner_couple(make_scene):
    sc = make_scene("pinned", "pinned", [udl()])
    r = run(sc, "exact-eringen", points=21, e0a=e0a)
    assert r.info["mu"] == pytest.approx(mu)
    assert rel(r.w, eringen_fields(sc, mu)(np.linspace(0, L, 21))["w"]) < TOL
    bad = make_scene("pinned", "pinned", [{"type": "point_moment", "position": 0.8, "value": 10.0}])
    with pytest.raises(InputError, match="exact-eringen takes couples at the ends only"):
        run(bad, "exact-eringen", e0a=e0a)


@pytest.mark.parametrize("factor", [1e-6, 1e6])
def test_a_scaled_scene_gives_the_same_relative_result(factor, make_scene):
    """Every length (and e0a) times ``factor``, line loads divided by it: the deflection scales as a whole."""
    loads = [udl(), pf(0.6)]
    a = make_scene("clamped", "pinned", loads)
    big = [dict(udl(q / factor)), dict(pf(0.6 * factor))]
    d = a.to_dict()
    d.update(loads=big, beam={"length": L * factor}, section={"width": 0.05 * factor, "height": 0.1 * factor})
    b = parse_scene(d)
    wa = eringen_fields(a, mu)(x)["w"]
    wb = eringen_fields(b, mu * factor**2)(x * factor)["w"]
    assert rel(wb / np.abs(wb).max(), wa / np.abs(wa).max()) < 1e-12
