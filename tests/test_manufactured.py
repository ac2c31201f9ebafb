"""Manufactured solution on the periodic film with the variable H^3 coefficient.

P = (lam^2 - zeta^2)(1 + sin(theta)/2 + 3 cos(2 theta)/10), H = 1 + 0.7 cos(theta):
observed orders must be those of the theory - P1: 2 (L2), 1 (energy); P2: 3, 2;
finite volumes: 2 (max norm at cell centres).
"""
import numpy as np
import pytest
import scipy.sparse.linalg as spla
import sympy as sy
from skfem import Functional, LinearForm

from bearingfem.fe.assembly import film_operator
from bearingfem.fv.fvm import _assemble, fvm_grid

LAM, EPS = 0.5, 0.7
_t, _z = sy.symbols("theta zeta")
_P = (LAM ** 2 - _z ** 2) * (1 + sy.sin(_t) / 2 + sy.Rational(3, 10) * sy.cos(2 * _t))
_H3 = (1 + EPS * sy.cos(_t)) ** 3
_f = -(sy.diff(_H3 * sy.diff(_P, _t), _t) + sy.diff(_H3 * sy.diff(_P, _z), _z))
P_EX = sy.lambdify((_t, _z), _P, "numpy")
DP_EX = [sy.lambdify((_t, _z), sy.diff(_P, v), "numpy") for v in (_t, _z)]
F_EX = sy.lambdify((_t, _z), _f, "numpy")


@LinearForm
def _source(v, w):
    return F_EX(w.x[0], w.x[1]) * v


@Functional
def _err_l2(w):
    return (w["ph"] - P_EX(w.x[0], w.x[1])) ** 2


@Functional
def _err_h1(w):
    g = w["ph"].grad
    return (g[0] - DP_EX[0](w.x[0], w.x[1])) ** 2 + (g[1] - DP_EX[1](w.x[0], w.x[1])) ** 2


def _fe_errors(element, k):
    op = film_operator(24 * k, 4 * k, element, LAM, None, True)
    basis, free = op.mesh.basis, op.mesh.free
    P = np.zeros(basis.N)
    P[free] = spla.spsolve(op.free_stiffness(EPS).tocsc(), _source.assemble(basis)[free])
    ph = basis.interpolate(P)
    return np.sqrt(_err_l2.assemble(basis, ph=ph)), np.sqrt(_err_h1.assemble(basis, ph=ph))


def _orders(errs):
    e = np.asarray(errs)
    return np.log2(e[:-1] / e[1:])


@pytest.mark.parametrize("element,l2,h1", [("P1", 2.0, 1.0), ("P2", 3.0, 2.0)])
def test_fe_orders(element, l2, h1):
    errs = np.array([_fe_errors(element, k) for k in (1, 2, 4)])
    o_l2, o_h1 = _orders(errs[:, 0]), _orders(errs[:, 1])
    assert o_l2[-1] == pytest.approx(l2, abs=0.15), o_l2
    assert o_h1[-1] == pytest.approx(h1, abs=0.15), o_h1


def test_fvm_order():
    errs = []
    for k in (1, 2, 4):
        g = fvm_grid(24 * k, 8 * k, LAM, None)
        A, _ = _assemble(g, EPS, 0.0, 0.0)
        th, ze = np.meshgrid(g.theta_c, g.zeta_c, indexing="ij")
        rhs = F_EX(th, ze).ravel() * g.dtheta * g.dzeta
        P = spla.spsolve(A.tocsc(), rhs)
        errs.append(np.max(np.abs(P - P_EX(th, ze).ravel())))
    assert _orders(errs)[-1] == pytest.approx(2.0, abs=0.15), errs
