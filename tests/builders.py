"""Parameter sets, buildings, ground motions and files that several test modules build alike: one definition
each.  Units N-mm-s-tonne; moduli in MPa, viscosities in MPa*s^r."""

from __future__ import annotations

import numpy as np
from reference import tapered_sine
from shared_data import EXAMPLE_BUILDING

from vdw_frames import (
    Bilinear,
    FDMKDamper,
    FluidViscousDamper,
    FrictionDamper,
    GroundMotion,
    ShearBuilding,
    SupportedDamper,
    paper,
)
from vdw_frames.config import load_building

# ---------------------------------------------------------------------------------------------- parameter sets
# The paper's Table 4, as printed (the model of eqs. (3)-(5) is tested against it, not fitted with it).
TABLE4 = dict(G1=8.69, G2=3.58, eta1=0.75, eta2=0.98, r=0.60)
# The README's example wall (a fractional Maxwell branch and a small Kelvin dashpot, r = 1/2).
README_WALL = dict(G1=0.0, G2=3.0, eta1=0.3, eta2=2.0, r=0.5)
# The recommended 300 % set, rounded (paper.fitted(300) holds the unrounded one).
FITTED300 = dict(G1=0.0, G2=2.63, eta1=0.0355, eta2=1.955, r=0.589)
# A pure Abel dashpot: s^r alone, the hardest case for a discretisation.
ABEL = dict(G1=0.0, G2=0.0, eta1=1.0, eta2=0.0, r=1.0)
# Both branches active (a spring and a dashpot in the Kelvin branch), for any order r.
BOTH_BRANCHES = dict(G1=0.5, G2=3.0, eta1=0.3, eta2=2.0)
# A classical (r = 1) Kelvin + Maxwell wall, whose modes a state-space model gives exactly.
CLASSICAL_KELVIN_MAXWELL = dict(G1=0.5, G2=3.0, eta1=0.4, eta2=2.0, r=1.0)
# Ground accelerations in g that AT2 test files hold.
VALUES_G = [0.1, -0.25, 0.3125, 0.0, -0.5, 0.125, 0.0625]

# ---------------------------------------------------------------------------------------------- buildings
# The README's 10-story frame, also that of examples/ten_story.toml: 600 t floors (roof 450 t), story
# stiffness 300 -> 165 kN/mm, a 4 m first story.
TEN_STORY_MASSES = [600.0] * 9 + [450.0]
TEN_STORY_STIFFNESSES = [300e3 - 15e3 * k for k in range(10)]
TEN_STORY_HEIGHTS = [4000.0] + [3500.0] * 9
TEN_STORY_GRAVITY = np.cumsum((9.80665e3 * np.array(TEN_STORY_MASSES))[::-1])[::-1]  # N: the weight above


def readme_ten_story():
    """The README's linear 10-story frame with a half-size 300 % wall in each of the six lower stories."""
    wall = paper.fitted(300, area=0.5e6)
    return ShearBuilding(masses=TEN_STORY_MASSES, stiffnesses=TEN_STORY_STIFFNESSES,
                         devices={story: wall for story in range(1, 7)}, story_heights=TEN_STORY_HEIGHTS)


# The yielding frame's walls: the README wall at 0.3 m^2 as a classical (r = 1) and a fractional wall.
INELASTIC_R1_WALL = FDMKDamper(**dict(README_WALL, r=1.0), area=0.3e6, thickness=10.0)
INELASTIC_FRACTIONAL_WALL = FDMKDamper(**README_WALL, area=0.3e6, thickness=10.0)


def yielding_ten_story(model=Bilinear, strength=0.08, hardening=0.03, walls=INELASTIC_R1_WALL, gravity=True,
                       **options):
    """The README's 10-story frame with yielding stories: strengths ``strength`` x the weight above story 1,
    tapered with height; P-Delta from the weight above each story (``gravity``); ``walls`` in stories 1-6."""
    yield_forces = [strength * TEN_STORY_GRAVITY[0] * (1 - k / 12) for k in range(10)]
    return ShearBuilding(TEN_STORY_MASSES, TEN_STORY_STIFFNESSES, story_heights=TEN_STORY_HEIGHTS,
                         hysteresis=[model(f, hardening) for f in yield_forces],
                         gravity_loads=TEN_STORY_GRAVITY if gravity else None,
                         devices={story: walls for story in range(1, 7)} if walls else None, **options)


def example_ten_story():
    """examples/ten_story.toml: the README's frame, yielding, with P-Delta and one 300 % wall a story."""
    return load_building(EXAMPLE_BUILDING)


# The OpenSees cross-checks' frame: 500 t floors, story stiffness 800 -> 400 kN/mm (T1 = 1.15 s bare), 5 %
# Rayleigh in modes 1 and 2.  Classical (r = 1) walls, the paper's size (A = 1e6 mm^2, h = 10 mm) and a
# smaller, thinner one: k1 = 1e5 N/mm, c1 = 1e4 N*s/mm, k2 = 1e5 N/mm, c2 = 2e4 N*s/mm (tau = 0.2 s) and
# k1 = 5e4 N/mm, c1 = 5e3 N*s/mm, k2 = 2e5 N/mm, c2 = 5e4 N*s/mm (tau = 0.25 s).
CLASSICAL_WALL_A = FDMKDamper(G1=1.0, G2=1.0, eta1=0.1, eta2=0.2, r=1.0, area=1.0e6, thickness=10.0)
CLASSICAL_WALL_B = FDMKDamper(G1=0.4, G2=1.6, eta1=0.04, eta2=0.4, r=1.0, area=1.0e6, thickness=8.0)
# Fractional walls: the recommended 300 % and 450 % sets (r = 0.59, 0.46) at a tenth and a twentieth of the
# paper's area, and the 300 % wall on a support of 200 kN/mm in series.
FRACTIONAL_WALL_A = paper.fitted(300, area=0.5e6)
FRACTIONAL_WALL_B = paper.fitted(450, area=0.3e6)
SUPPORTED_WALL = SupportedDamper(paper.fitted(300, area=0.4e6), 2.0e5)


def uniform_ten_story(walls=None, hysteresis=None):
    """500 t floors, 800 -> 400 kN/mm, 5 % Rayleigh in modes 1 and 2."""
    return ShearBuilding([500.0] * 10, np.linspace(800e3, 400e3, 10), devices=walls, hysteresis=hysteresis)


def classical_ten_story(walls=True):
    """The uniform frame with classical walls A + B on stories 1-5 and A on stories 6-10 (``walls``)."""
    return uniform_ten_story({story: [CLASSICAL_WALL_A, CLASSICAL_WALL_B] if story <= 5 else [CLASSICAL_WALL_A]
                              for story in range(1, 11)} if walls else None)


def fractional_ten_story(hysteresis=None):
    """The uniform frame with fractional walls A + B on stories 1-5 and A + supported on stories 6-10."""
    return uniform_ten_story({story: [FRACTIONAL_WALL_A, FRACTIONAL_WALL_B] if story <= 5
                              else [FRACTIONAL_WALL_A, SUPPORTED_WALL] for story in range(1, 11)}, hysteresis)


# The README wall at a fifth of its area (0.2 m^2, 10 mm layers).
SMALL_README_WALL = FDMKDamper(**README_WALL, area=2.0e5, thickness=10.0)


def light_ten_story(walls=True):
    """300 t floors, 3.5 m stories, story stiffness 300 kN/mm falling 5 % a story, two ``SMALL_README_WALL``
    in every story (``walls``)."""
    stiffness = [300e3 * (1 - 0.05 * i) for i in range(10)]
    walls = {story: [SMALL_README_WALL, SMALL_README_WALL] for story in range(1, 11)} if walls else None
    return ShearBuilding([300.0] * 10, stiffness, devices=walls, story_heights=[3500.0] * 10)


def three_story(walls=None, story_heights=(3500.0,) * 3):
    """300, 300 and 250 t floors on 200, 180 and 150 kN/mm stories (``story_heights=None``: none given)."""
    return ShearBuilding([300.0, 300.0, 250.0], [2e5, 1.8e5, 1.5e5], devices=walls,
                         story_heights=list(story_heights) if story_heights is not None else None)


def three_story_spec():
    """A valid building file's content (JSON-like) for the three-story frame: README walls, two a story in
    stories 1-2, and fitted-300 walls of 0.5 m^2 in every story."""
    return {"masses": [300.0, 300.0, 250.0], "stiffnesses": [2e5, 1.8e5, 1.5e5], "story_heights": [3500.0] * 3,
            "walls": [{"stories": [1, 2], "per_story": 2, "parameters": dict(README_WALL)},
                      {"stories": "all", "parameters": "fitted-300", "area": 5e5}]}


# ---------------------------------------------------------------------------------------------- ground motions
def tapered_pulse(name="pulse"):
    """A 1.5 Hz sine of 2000 mm/s^2 over 6 s (601 samples at 0.01 s), switched on and off over 1 s."""
    t = np.arange(601) * 0.01
    return GroundMotion(tapered_sine(t, 1.5, 2000.0, 1.0, 6.0), 0.01, name)


def tapered_sine_pair():
    """Two 8 s tapered sines (1.1 and 2.7 Hz, 1500 mm/s^2, 2 s ramps) at 0.01 s, named by their frequency."""
    t = np.arange(801) * 0.01
    return [GroundMotion(tapered_sine(t, f, 1500.0, 2.0, 8.0), 0.01, name=f"sine {f} Hz") for f in (1.1, 2.7)]


def two_tone_motion(dt, duration, first, second, ramp):
    """The sum of two tapered sines ``first`` and ``second`` ((frequency Hz, amplitude mm/s^2)), switched on
    and off over ``ramp`` s, sampled every ``dt`` s over ``duration`` s; named "smooth"."""
    t = np.arange(round(duration / dt) + 1) * dt
    a = tapered_sine(t, *first, ramp, duration) + tapered_sine(t, *second, ramp, duration)
    return GroundMotion(a, dt, name="smooth")


# ---------------------------------------------------------------------------------------------- files
def write_file(tmp_path, name: str, data):
    """``data`` (str: written as ASCII; bytes: as they are) in ``tmp_path / name``; returns the path."""
    path = tmp_path / name
    path.write_bytes(data.encode("ascii") if isinstance(data, str) else data)
    return path


EL_CENTRO_HEADER = ("PEER STRONG MOTION DATABASE RECORD.", "IMPERIAL VALLEY 10/15/79 2316, EL CENTRO ARRAY #6, 230",
                    "ACCELEROGRAM IN G.  FILTER POINTS:  HP=0.1 Hz LP=40.0 Hz")


def replace_somewhere(spec, path: list[int], value):
    """``spec`` with the item at ``path`` (keys/indices, followed as far as they go) replaced by ``value``."""
    node = spec
    for step in path[:-1]:
        items = list(node) if isinstance(node, dict) else range(len(node)) if isinstance(node, list) else []
        if not items or not isinstance(node[items[step % len(items)]], (dict, list)):
            break
        node = node[items[step % len(items)]]
    items = list(node) if isinstance(node, dict) else list(range(len(node)))
    if items:
        node[items[path[-1] % len(items)]] = value
    return spec


def peer_at2(count_line: str, rows: list[str], header=EL_CENTRO_HEADER) -> str:
    """The text of a PEER-style AT2 file: ``header`` lines, the count line, the rows of values."""
    return "\n".join([*header, count_line, *rows]) + "\n"


# ---------------------------------------------------------------------------------------------- every device kind
# A four-story frame with one device kind a story: a fitted-300 wall, 20 mm thick (story 1), a linear FVD (story 2), a
# nonlinear FVD with a brace on a diagonal (story 3) and two friction dampers (story 4).  Sizes give each
# story's device some 5-20 % of the story's force at the tapered pulse's drifts.
MIXED_FVD_LINEAR = dict(C=150.0, alpha=1.0)
MIXED_FVD_NONLINEAR = dict(C=1500.0, alpha=0.5, stiffness=8e4, magnification=0.8)
MIXED_FRICTION = dict(slip_force=2.0e4, stiffness=6e4)
MIXED_DEVICES_TOML = """\
masses = [300.0, 300.0, 300.0, 250.0]
stiffnesses = [2.0e5, 1.8e5, 1.6e5, 1.4e5]
story_heights = [3500.0, 3500.0, 3500.0, 3500.0]

[[walls]]
stories = [1]
parameters = "fitted-300"
area = 3.0e5
thickness = 20.0

[[devices]]
type = "fluid_viscous"
stories = [2]
C = 150.0
alpha = 1.0

[[devices]]
type = "fluid_viscous"
stories = [3]
C = 1500.0
alpha = 0.5
stiffness = 8.0e4
magnification = 0.8

[[devices]]
type = "friction"
stories = [4]
per_story = 2
slip_force = 2.0e4
stiffness = 6.0e4
"""


def mixed_devices_building():
    """The frame of :data:`MIXED_DEVICES_TOML`, made by the constructor."""
    friction = FrictionDamper(**MIXED_FRICTION)
    return ShearBuilding([300.0, 300.0, 300.0, 250.0], [2.0e5, 1.8e5, 1.6e5, 1.4e5], story_heights=[3500.0] * 4,
                         devices={1: paper.fitted(300, area=3.0e5, thickness=20.0),
                                  2: FluidViscousDamper(**MIXED_FVD_LINEAR),
                                  3: FluidViscousDamper(**MIXED_FVD_NONLINEAR), 4: [friction, friction]})
