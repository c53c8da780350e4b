"""Footprints: normalisation, stated moments and cut-off, spec parsing, tabulated files."""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

from coatsim.core.errors import InputError
from coatsim.spray.footprints import (
    Beta, DoubleBeta, EllipticGaussian, Gaussian, load_footprint_table, parse_footprint_spec,
)

FOOTPRINTS = [Gaussian(5), EllipticGaussian(6, 4), Beta(15, 2), Beta(10, 1), Beta(10, 3.5),
              DoubleBeta(12, 8, 2, 1.5), DoubleBeta(9, 14, 3, 2)]


def grid(extent: float, n: int = 2001):
    x = np.linspace(-extent, extent, n)
    u, v = np.meshgrid(x, x)
    return u, v, (x[1] - x[0]) ** 2


@pytest.mark.parametrize("fp", FOOTPRINTS, ids=lambda f: f.spec)
def test_density_integrates_to_one_with_the_stated_sigma_and_cutoff(fp):
    u, v, cell = grid(fp.cutoff_mm * 1.05)
    g = fp.density(u, v)
    assert np.all(g >= 0)
    mass = g.sum() * cell
    rim_tolerance = 2e-3 if isinstance(fp, Beta) and fp.beta == 1 else 2e-4  # flat disk: hard edge
    assert mass == pytest.approx(1.0, abs=rim_tolerance)
    sigma_u = math.sqrt(np.sum(g * u * u) * cell / mass)
    sigma_v = math.sqrt(np.sum(g * v * v) * cell / mass)
    assert max(sigma_u, sigma_v) == pytest.approx(fp.sigma_mm, rel=2e-3)
    assert np.all(g[np.hypot(u, v) > fp.cutoff_mm * (1 + 1e-9)] == 0)
    assert fp.substep_mm <= fp.sigma_mm and fp.spacing_mm <= fp.sigma_mm


def test_circular_double_beta_equals_beta():
    u, v, _ = grid(12, 301)
    np.testing.assert_allclose(DoubleBeta(10, 10, 2.5, 2.5).density(u, v), Beta(10, 2.5).density(u, v),
                               rtol=1e-12, atol=1e-15)


def test_gaussian_peak_is_renormalised_for_the_cutoff():
    assert Gaussian(5).density(np.zeros(1), np.zeros(1))[0] == pytest.approx(1 / (2 * math.pi * 25), rel=2e-8)


positive = st.floats(0.5, 50, allow_nan=False).map(lambda x: round(x, 3))
exponent = st.floats(1, 6, allow_nan=False).map(lambda x: round(x, 3))


@given(st.one_of(
    st.builds(Gaussian, positive), st.builds(EllipticGaussian, positive, positive),
    st.builds(Beta, positive, exponent), st.builds(DoubleBeta, positive, positive, exponent, exponent),
))
@settings(max_examples=60, deadline=None)
def test_spec_round_trip(fp):
    assert parse_footprint_spec(fp.spec) == fp


@pytest.mark.parametrize("spec, words", [
    ("cone:radius=3", "unknown kind"),
    ("gaussian", "missing sigma"),
    ("gaussian:sigma=0", "must be positive"),
    ("gaussian:sigma=-2", "must be positive"),
    ("gaussian:sigma=abc", "must be a number"),
    ("gaussian:sigma=nan", "must be positive"),
    ("gaussian:width=3", "unexpected"),
    ("beta:radius=10,beta=0.5", "at least 1"),
    ("double-beta:a=1,b=2,beta1=2", "missing beta2"),
    ("table:", "table file"),
    ("table:/nonexistent/spot.csv", "no such file"),
])
def test_bad_specs_name_the_problem(spec, words):
    with pytest.raises(InputError, match=words):
        parse_footprint_spec(spec)


def write_table(path, u, v, values, header="u_mm,v_mm,rate"):
    rows = [header] + [f"{a:g},{b:g},{c:.12g}" for a, b, c in zip(u, v, values)]
    path.write_text("\n".join(rows) + "\n")


def test_tabulated_gaussian_matches_the_analytic_one(tmp_path):
    x = np.arange(-30, 30.001, 0.5)
    u, v = (a.ravel() for a in np.meshgrid(x, x))
    order = np.random.default_rng(1).permutation(len(u))  # any row order
    path = tmp_path / "spot.csv"
    write_table(path, u[order], v[order], 7.0 * np.exp(-(u[order] ** 2 + v[order] ** 2) / 50))
    fp = parse_footprint_spec(f"table:{path}")
    assert fp.spec == f"table:{path}"
    q = np.linspace(-20, 20, 81)
    qu, qv = np.meshgrid(q, q)
    np.testing.assert_allclose(fp.density(qu, qv), Gaussian(5).density(qu, qv), atol=2e-5)
    assert fp.sigma_mm == pytest.approx(5, rel=1e-3)
    assert fp.density(np.array([31.0]), np.array([0.0]))[0] == 0.0
    uu, vv, cell = grid(31, 1241)
    assert fp.density(uu, vv).sum() * cell == pytest.approx(1.0, abs=1e-4)


@pytest.mark.parametrize("content, words", [
    ("x,y,z\n0,0,1\n", "header"),
    ("u_mm,v_mm,rate\n0,0,1\n1,0,1\n0,1,1\n", "regular u x v grid"),
    ("u_mm,v_mm,rate\n0,0,1\n1,0,1\n0,1,1\n1,1,-1\n", r"bad.csv:5: rate must be >= 0"),
    ("u_mm,v_mm,rate\n0,0,1\n1,0,x\n", r"bad.csv:3: .*must be numbers"),
    ("u_mm,v_mm,rate\n0,0,0\n1,0,0\n0,1,0\n1,1,0\n", "no positive rate"),
    ("u_mm,v_mm,rate\n0,0,1\n1,0,1\n3,0,1\n0,1,1\n1,1,1\n3,1,1\n", "not evenly spaced"),
])
def test_bad_tables_name_file_and_line(tmp_path, content, words):
    path = tmp_path / "bad.csv"
    path.write_text(content)
    with pytest.raises(InputError, match=words) as info:
        load_footprint_table(path)
    assert str(path) in str(info.value) and "\n" not in str(info.value)
