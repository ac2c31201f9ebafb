"""The journal speed and the oil as a designer types them: --rpm [1/min] and --oil GRADE
at --oil-temperature [degC]."""
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def run(*args):
    return subprocess.run([sys.executable, "-m", "bearingfem_app", *args], cwd=ROOT,
                          capture_output=True, text=True, timeout=300)


def test_rpm_is_the_speed_in_revolutions_per_minute():
    """--rpm 3000 is --omega 100 pi (the same film), and one of the two is given."""
    import math
    a = run("solve", "--rpm", "3000", "--model", "fvm", "--n-theta", "24", "--n-z", "4")
    b = run("solve", "--omega", repr(100 * math.pi), "--model", "fvm", "--n-theta", "24",
            "--n-z", "4")
    assert a.returncode == 0 and a.stdout == b.stdout
    c = run("equilibrium", "--load", "100", "--rpm", "3000", "--omega", "3")
    assert c.returncode == 2 and "not allowed with argument" in c.stderr


def test_oil_by_grade_is_its_viscosity_at_the_temperature():
    """--oil 'ISO VG 32' at 40 degC is 32 mm^2/s (the grade's midpoint, ISO 3448) times
    870 kg/m^3 = 0.02784 Pa s, by hand; a warmer oil is thinner; a grade that does not
    exist, both --oil and --viscosity, or a temperature without an oil are refused."""
    a = run("solve", "--oil", "ISO VG 32", "--oil-temperature", "40", "--model", "fvm",
            "--n-theta", "24", "--n-z", "4")
    b = run("solve", "--viscosity", repr(32e-6 * 870), "--model", "fvm", "--n-theta", "24",
            "--n-z", "4")
    assert a.returncode == 0 and a.stdout == b.stdout
    hot = run("solve", "--oil", "VG32", "--oil-temperature", "80", "--model", "fvm",
              "--n-theta", "24", "--n-z", "4")
    f = [float(r.stdout.split("|F| ")[1].split()[0]) for r in (a, hot)]
    assert f[1] < 0.5 * f[0]
    for argv, needle in ((("--oil", "ISO VG 33"), "--oil must be an ISO VG grade"),
                         (("--oil", "VG 32", "--viscosity", "0.03"), "not allowed with"),
                         (("--oil-temperature", "60"), "--oil-temperature is the --oil's")):
        r = run("equilibrium", "--load", "100", *argv)
        assert r.returncode == 2 and needle in r.stderr
