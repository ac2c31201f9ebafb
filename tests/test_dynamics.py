"""Equations of motion against an independent symbolic Lagrange derivation, and the
ideal mechanism against energy conservation and the crank-speed swing (seed-corrections §11)."""
import numpy as np
import pytest
import sympy as sy

from mechanism.dynamics import accelerations, energy, pin_position
from mechanism.parameters import Mechanism
from mechanism.rigid import rigid_kinematics, simulate_rigid


def _symbolic_accelerations():
    """Lagrange from positions only: crank, rod and slider bodies, forces by virtual work."""
    t = sy.symbols("t")
    q, A, X = (sy.Function(n)(t) for n in ("q", "A", "X"))
    R, L, IM, IB, MM, MB, MP, Um, Vm, U, V, g, Fx, Fy, tau, Fe = sy.symbols(
        "R L IM IB MM MB MP Um Vm U V g Fx Fy tau Fe")
    crank_cm = sy.Matrix([Um * sy.cos(q) - Vm * sy.sin(q), Um * sy.sin(q) + Vm * sy.cos(q)])
    pin_c = sy.Matrix([R * sy.cos(q), R * sy.sin(q)])
    along, across = sy.Matrix([sy.cos(A), -sy.sin(A)]), sy.Matrix([sy.sin(A), sy.cos(A)])
    rod_cm = pin_c + U * along + V * across
    pin = pin_c + L * along
    v = lambda r: r.diff(t)
    # I_MO is about the pivot: crank kinetic energy is 1/2 I_MO q'^2
    T = (IM * q.diff(t) ** 2 / 2 + MB * v(rod_cm).dot(v(rod_cm)) / 2
         + IB * A.diff(t) ** 2 / 2 + MP * X.diff(t) ** 2 / 2)
    Vg = g * (MM * crank_cm[0] + MB * rod_cm[0] + MP * X)
    Lag = T - Vg
    F = sy.Matrix([Fx, Fy])
    Q = [F.dot(pin.diff(c)) + (tau if c is q else 0) for c in (q, A)] + [-Fx - Fe]
    eqs = [sy.diff(Lag.diff(c.diff(t)), t) - Lag.diff(c) - Qc for c, Qc in zip((q, A, X), Q)]
    acc = [c.diff(t, 2) for c in (q, A, X)]
    qs, As, qds, Ads, a1, a2, a3 = sy.symbols("qs As qds Ads a1 a2 a3")
    subs = {acc[0]: a1, acc[1]: a2, acc[2]: a3}
    eqs = [e.subs(subs).subs({q.diff(t): qds, A.diff(t): Ads}).subs({q: qs, A: As})
           for e in eqs]
    M, b = sy.linear_eq_to_matrix(eqs, [a1, a2, a3])
    args = (qs, As, qds, Ads, R, L, IM, IB, MM, MB, MP, Um, Vm, U, V, g, Fx, Fy, tau, Fe)
    fM, fb = sy.lambdify(args, M, "numpy"), sy.lambdify(args, b, "numpy")
    solve = lambda *a: np.linalg.solve(np.array(fM(*a), float), np.array(fb(*a), float).ravel())
    return [lambda *a, i=i: solve(*a)[i] for i in range(3)]


@pytest.fixture(scope="module")
def symbolic():
    return _symbolic_accelerations()


@pytest.mark.parametrize("seed", range(5))
def test_equations_match_symbolic_lagrange(symbolic, seed):
    rng = np.random.default_rng(seed)
    m = Mechanism(crank_cm=tuple(rng.normal(0, 0.01, 2)), rod_cm=(0.05, rng.normal(0, 0.01)))
    q, A, qd, Ad = rng.uniform(-3, 3), rng.uniform(-0.3, 0.3), rng.normal(0, 200), rng.normal(0, 60)
    Fx, Fy, g, tau, Fe = rng.normal(0, 500, 2).tolist() + [9.81, 3.0, 40.0]
    ours = accelerations(m, q, A, qd, Ad, Fx, Fy, g=g, torque=tau, slider_force=Fe)
    args = (q, A, qd, Ad, m.crank_length, m.rod_length, m.crank_inertia, m.rod_inertia,
            m.crank_mass, m.rod_mass, m.slider_mass, *m.crank_cm, *m.rod_cm, g, Fx, Fy, tau, Fe)
    ref = [f(*args) for f in symbolic]
    assert np.allclose(ours, ref, rtol=1e-10, atol=1e-8)


def test_printed_velocity_term_sign_is_wrong(symbolic):
    """Seed Eq. 1 prints +M_B R (V cos(A+q) - U sin(A+q)) [A'^2, q'^2]; the derivation
    gives the opposite sign. The accelerations are linear in that term, so the printed
    equations give a_printed = 2 a(velocities 0) - a: evaluated here, they miss the
    Lagrange accelerations, which ours match."""
    m = Mechanism()
    q, A, qd, Ad, Fx, Fy, g = 0.7, 0.1, 250.0, 60.0, 300.0, -200.0, 9.81
    ours = np.array(accelerations(m, q, A, qd, Ad, Fx, Fy, g=g))
    still = np.array(accelerations(m, q, A, 0.0, 0.0, Fx, Fy, g=g))
    printed = 2.0 * still - ours
    args = (q, A, qd, Ad, m.crank_length, m.rod_length, m.crank_inertia, m.rod_inertia,
            m.crank_mass, m.rod_mass, m.slider_mass, *m.crank_cm, *m.rod_cm, g, Fx, Fy, 0, 0)
    ref = np.array([f(*args) for f in symbolic])
    assert np.allclose(ours, ref, rtol=1e-10)
    assert np.abs(printed - ref)[:2].max() > 1e3 * np.abs(ours - ref)[:2].max() + 1.0


@pytest.mark.parametrize("g", [0.0, 9.81])
def test_ideal_mechanism_conserves_energy(g):
    m = Mechanism()
    t, q, qd = simulate_rigid(m, 250.0, 2.0, g)
    A, A1, _, X, X1, _ = rigid_kinematics(m, q)
    E = energy(m, q, A, qd, A1 * qd, X1 * qd, X, g)
    assert np.ptp(E) / E[0] < 1e-8


def test_ideal_crank_speed_swing():
    """seed-corrections §11: from TDC at 250 rad/s the crank speed swings 211-251 rad/s."""
    _, _, qd = simulate_rigid(Mechanism(), 250.0, 2.0, 9.81)
    assert qd.min() == pytest.approx(211.5, abs=0.5)
    assert qd.max() == pytest.approx(251.0, abs=0.5)


def test_pin_on_axis_for_ideal_mechanism():
    m = Mechanism()
    q = np.linspace(0, 2 * np.pi, 50)
    A = rigid_kinematics(m, q)[0]
    np.testing.assert_allclose(pin_position(m, q, A)[1], 0.0, atol=1e-15)
