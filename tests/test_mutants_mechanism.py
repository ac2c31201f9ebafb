"""The slider-crank's joint effects and command-free helpers (mechanism/): bugs planted one
at a time that the mechanism tests did not notice (docs/mutation.md)."""
import math

import numpy as np
import pytest

from mechanism.effects import CoulombFriction, HertzContact, JointKinematics

C = 20e-6
R = 0.01


def _contacts(n=200, seed=3):
    """Random kinematics in contact (e > c), every direction and sliding sense."""
    rng = np.random.default_rng(seed)
    for _ in range(n):
        e = C * (1.0 + rng.uniform(1e-4, 5e-3))
        a = rng.uniform(0, 2 * np.pi)
        yield JointKinematics(e * math.cos(a), e * math.sin(a), *rng.normal(0, 0.05, 2),
                              omega=rng.normal(0, 20.0))


def test_coulomb_friction_dissipates_and_is_bounded():
    """Energy: the friction force on the pin does no positive work against the sliding
    velocity of the pin surface over the bush at the contact point, v = e' + omega R t_hat
    (computed here from the kinematics), and its magnitude never exceeds mu_f F_n; it is
    tangential. Fails with the friction acting along the sliding velocity (effects.py,
    CoulombFriction.force: the sign of ft)."""
    contact = HertzContact(C, 1e10, v_impact=1.0)   # mild damping: F_n > 0
    friction = CoulombFriction(contact, 0.1, R, v_reg=1e-4)
    powers = []
    for k in _contacts():
        fx, fy = friction.force(k)
        rx, ry = k.e_x / k.e, k.e_y / k.e
        vx, vy = k.de_x - k.omega * R * ry, k.de_y + k.omega * R * rx
        powers.append(fx * vx + fy * vy)
        fn = contact.normal_force(k)
        assert math.hypot(fx, fy) <= 0.1 * fn * (1 + 1e-12)
        assert abs(fx * rx + fy * ry) <= 1e-12 * (1 + fn)
    powers = np.array(powers)
    assert np.all(powers <= 0.0) and np.mean(powers < 0) > 0.9


def test_joint_omega_is_the_rods_rotation_from_the_geometry():
    """The journal's speed relative to the bearing is the rod's counter-clockwise rotation
    (the slider does not turn): here the rate of the angle of the line crank pin -> piston
    pin, by central differences along the motion. Fails with omega = +A' (joint.py)."""
    from mechanism.dynamics import pin_position, rod_from_eccentricity
    from mechanism.joint import joint_kinematics
    from mechanism.parameters import Mechanism
    m = Mechanism()
    rng = np.random.default_rng(5)
    for _ in range(20):
        y = np.array([rng.uniform(0, 2 * np.pi), 1e-5, rng.uniform(-1e-5, 1e-5),
                      rng.uniform(100, 400), 1e-3, rng.uniform(-0.01, 0.01)])

        def rod_angle(dt):
            q, ey = y[0] + y[3] * dt, y[2] + y[5] * dt
            A, _ = rod_from_eccentricity(m, q, y[3], ey, y[5])
            px, py = pin_position(m, q, A)
            r = m.crank_length
            return math.atan2(py - r * math.sin(q), px - r * math.cos(q))

        h = 1e-7
        rate = (rod_angle(h) - rod_angle(-h)) / (2 * h)
        assert joint_kinematics(m, y).omega == pytest.approx(rate, rel=1e-5)


def test_film_frames_take_the_nearest_sample_across_360_deg():
    """A frame asked at 359.9 deg is the sample at 0 deg (0.1 deg away across the turn),
    not the one at 359.5 deg (0.4 deg away). Fails with the distance not wrapped
    (film_history.py, _sample_indices)."""
    from types import SimpleNamespace

    from mechanism.film_history import _sample_indices
    result = SimpleNamespace(crank_angle=np.radians(np.arange(0.0, 360.0, 0.5)))
    assert _sample_indices(result, [359.9, 0.2, 180.1]) == [0, 0, 360]


def test_recorded_slider_and_rod_close_the_loop():
    """The run's recorded slider position and rod angle against the linkage's geometry by
    hand, from the run's own crank angle and pin eccentricity: the piston pin sits at
    crank pin + rod, (R cos q + L cos A, R sin q - L sin A), the slider at that pin less
    (e_x, e_y) and on its axis Y = 0, so sin A = (R sin q - e_y) / L and
    X = R cos q + L cos A - e_x. Round-off only (1e-12 of the stroke). No test read the
    slider position before: it survived X = pin + e_x (joint.py), a 2 e_x (~20 um) shift."""
    from dataclasses import replace

    from mechanism import load_scene, simulate
    scene = load_scene("paper-long-analytic")
    scene = replace(scene, run=replace(scene.run, turns=0.1, record_from_turn=0.0))
    res = simulate(scene, progress=False)
    m = scene.mechanism
    R, L = m.crank_length, m.rod_length
    q = res.crank_angle
    A = np.arcsin((R * np.sin(q) - res.e_y) / L)
    assert np.abs(res.e_x).max() > 1e-6           # the pin moves in its clearance
    assert res.rod_angle == pytest.approx(A, abs=1e-12)
    assert res.slider_position == pytest.approx(R * np.cos(q) + L * np.cos(A) - res.e_x,
                                                abs=1e-12 * 2 * R)


def test_recorded_film_and_slider_are_the_geometry_and_the_sliders_free_body():
    """A rigid aligned journal's least film is c - |e| (from the run's own e_x, e_y); the
    slider, pushed by the pin's reaction -F_x and pulled down by gravity, accelerates at
    -(F_x + M_PT g) / M_PT (the scene has gravity and no slider force). Round-off. Both
    survived: the least film halved and the slider's recorded acceleration without gravity
    (sampling.py; the ideal joint's has its own test)."""
    from dataclasses import replace

    from mechanism import load_scene, simulate
    scene = load_scene("paper-long-analytic")
    assert scene.gravity and scene.slider_force == 0.0
    scene = replace(scene, run=replace(scene.run, turns=0.05, record_from_turn=0.0))
    res = simulate(scene, progress=False)
    c, M = scene.bearing.clearance, scene.mechanism.slider_mass
    assert res.film_min == pytest.approx(c - np.hypot(res.e_x, res.e_y), abs=1e-12 * c)
    assert res.slider_acceleration == pytest.approx(-(res.force_x + M * 9.81) / M, rel=1e-12)


def test_ideal_joints_reaction_across_the_slider_keeps_the_linkages_angular_momentum():
    """The ideal joint's reaction on the pin against Newton-Euler, not Lagrange: about the
    crank pivot O the linkage's angular momentum H = I_MO q' + I_B theta' + M_B (G x v_G)
    (theta = -A the rod's counter-clockwise angle, G its centre of mass; the crank's sits on
    the pivot in this scene; the slider moves along the line through O and has none) changes by the moments of gravity and of the
    guide's force on the slider, N = F_y at (X, 0): dH/dt = X F_y + g M_B G_y. Positions by
    hand from the geometry, dH/dt by differences along the run (measured 2e-7 of the largest
    term at 20000 samples a turn; the bound 1e-5). The joint's F_y was read by no test: it
    survived the rod's m22 written I_B, the term F_x L sin A with its sign flipped and the
    rod's weight left out (ideal.py)."""
    from mechanism import parse_scene, simulate
    s = parse_scene({"name": "ideal", "joint": "ideal",
                     "run": {"turns": 1.0, "samples_per_turn": 20000, "rtol": 1e-10}})
    r = simulate(s, progress=False)
    m = s.mechanism
    R, L, (U, V), g = m.crank_length, m.rod_length, m.rod_cm, 9.81

    def centre(q):
        A = np.arcsin(R * np.sin(q) / L)
        return (R * np.cos(q) + U * np.cos(A) + V * np.sin(A),
                R * np.sin(q) - U * np.sin(A) + V * np.cos(A), -A)

    q, qd, h = r.crank_angle, r.crank_speed, 1e-5
    gx, gy, th = centre(q)
    d = [(a - b) / (2 * h) * qd for a, b in zip(centre(q + h), centre(q - h))]
    H = m.crank_inertia * qd + m.rod_inertia * d[2] + m.rod_mass * (gx * d[1] - gy * d[0])
    dH = np.gradient(H, r.t)
    moment = r.slider_position * r.force_y + g * m.rod_mass * gy
    inner = slice(5, -5)
    scale = np.abs(r.slider_position * r.force_y).max()
    assert scale > 10.0                     # the guide's moment is not negligible
    assert np.abs(dH - moment)[inner].max() < 1e-5 * scale


def test_friction_slides_at_the_pins_radius():
    """A pin turning at omega in contact, without moving its centre, slides over the bush at
    omega D / 2 (D the scene's pin diameter): the regularised friction is then
    mu F_n tanh(omega D / (2 v_reg)), against the sliding. Here omega D / 2 = v_reg / 2, on
    the tanh's steep part. Survived the scene's friction built with the diameter for the
    radius (simulate.py)."""
    from mechanism import parse_scene
    from mechanism.simulate import build_effects
    s = parse_scene({"name": "t", "bearing": {"diameter": 0.02, "length_ratio": 0.5,
                                              "clearance": 20e-6, "viscosity": 0.01},
                     "effects": {"contact": {}, "friction": {"coefficient": 0.1,
                                                             "v_reg": 1e-3}}})
    effects, _, contact = build_effects(s)
    friction = effects[-1]
    assert isinstance(friction, CoulombFriction)
    omega = 0.5e-3 / 0.01                   # omega D / 2 = v_reg / 2
    e = 20e-6 * 1.001
    for a in np.linspace(0.0, 2 * np.pi, 7):
        k = JointKinematics(e * math.cos(a), e * math.sin(a), 0.0, 0.0, omega=omega)
        fn = contact.normal_force(k)
        fx, fy = friction.force(k)
        t_hat = (-math.sin(a), math.cos(a))
        assert fx * t_hat[0] + fy * t_hat[1] == pytest.approx(-0.1 * fn * math.tanh(0.5),
                                                              rel=1e-12)


def test_contact_stiffness_is_hertzs_ball_in_its_socket():
    """The pin-in-bush stiffness K [N/m^1.5] against Hertz's sphere as the EHL module writes
    it (Johnson 1985, Eqs. 4.22-4.23: a = (3 P R / (2 E'))^(1/3), approach a^2 / R), with
    the conforming radius 1/R = 1/R_pin - 1/R_bush and E' = E / (1 - nu^2) for two equal
    solids, set by hand: P = K approach^1.5 to round-off. The stiffness was pinned only by
    one run's peak penetration: a one-solid modulus (K 2x) and the radii's sum for their
    difference were each caught there alone (effects.py), and a scene's contact built on
    the pin's diameter for its radius (simulate.py)."""
    from bearingfem.ehl.pointcontact import hertz_point
    from mechanism.effects import hertz_stiffness
    for radius, clearance, E, nu in ((0.01, 20e-6, 207e9, 0.3), (0.03, 50e-6, 110e9, 0.34)):
        K = hertz_stiffness(radius, clearance, E, nu)
        R = 1.0 / (1.0 / radius - 1.0 / (radius + clearance))
        for P in (10.0, 1e3, 1e5):
            approach = hertz_point(R, E / (1.0 - nu ** 2), P).approach
            assert K * approach ** 1.5 == pytest.approx(P, rel=1e-12)
    # a scene's contact: its pin of diameter 0.02 m, 20 um clearance, steel by default
    from mechanism import parse_scene
    from mechanism.simulate import build_effects
    s = parse_scene({"name": "t", "bearing": {"diameter": 0.02, "length_ratio": 0.5,
                                              "clearance": 20e-6, "viscosity": 0.01},
                     "effects": {"contact": {}}})
    contact = build_effects(s)[2]
    R = 1.0 / (1.0 / 0.01 - 1.0 / (0.01 + 20e-6))
    approach = hertz_point(R, 207e9 / (1.0 - 0.3 ** 2), 1e3).approach
    assert contact.stiffness * approach ** 1.5 == pytest.approx(1e3, rel=1e-12)


def test_lankarani_nikravesh_rebound_tends_to_the_restitution():
    """A mass meeting the bush at v0 leaves at e_eff v0. Lankarani and Nikravesh (1990)
    chose the hysteresis factor 3 (1 - c_e^2) / 4 so that the energy lost is
    (1 - c_e^2) m v0^2 / 2 to first order in 1 - c_e: (1 - e_eff) / (1 - c_e) -> 1 as
    c_e -> 1 (measured 0.985 at c_e 0.99, 0.992 at 0.995; 0.93 at 0.95, so the limit is
    O(1 - c_e)), and e_eff is the same at every impact speed (the damping scales with
    d'/v0). Integrated here to 1e-11. The damping was pinned only by one run's peak
    penetration: 1 - c_e for 1 - c_e^2 (ratio 0.5) and the approach speed's sign (energy
    gained) were each caught there alone (effects.py)."""
    from scipy.integrate import solve_ivp
    from mechanism.effects import hertz_stiffness

    def rebound(ce, v0):
        hc = HertzContact(C, hertz_stiffness(R, C, 207e9, 0.3), restitution=ce, v_impact=v0)

        def f(t, y):
            return [y[1], -hc.normal_force(JointKinematics(C + y[0], 0.0, y[1], 0.0, 0.0)) / 0.91]
        out = lambda t, y: y[0] + 1e-30          # noqa: E731
        out.terminal, out.direction = True, -1
        s = solve_ivp(f, (0.0, 1.0), [1e-30, v0], events=out, rtol=1e-11, atol=1e-18,
                      method="DOP853", max_step=1e-6)
        assert s.status == 1
        return -s.y[1, -1] / v0

    for ce in (0.99, 0.995):
        e = [rebound(ce, v0) for v0 in (0.01, 1.0)]
        assert e[0] == pytest.approx(e[1], rel=1e-8)
        assert (1.0 - e[0]) / (1.0 - ce) == pytest.approx(1.0, abs=0.03)
