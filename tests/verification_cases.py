"""Small frames and short synthetic records shared by the verification tests (fixtures in conftest.py)."""

import numpy as np

from vdw_frames import FDMKDamper, ShearBuilding
from vdw_frames.motion import synthetic_ground_motion


def r1_wall(scale: float = 1.0) -> FDMKDamper:
    """A classical (r = 1) Kelvin + Maxwell wall: A / t = 2e4 mm."""
    return FDMKDamper(G1=0.5 * scale, G2=1.0 * scale, eta1=0.05 * scale, eta2=0.2 * scale, r=1.0, area=2.0e5,
                      thickness=10.0)


def three_story(walls: bool = True, heights: bool = True) -> ShearBuilding:
    return ShearBuilding(masses=(100.0, 100.0, 80.0), stiffnesses=(1.2e5, 1.0e5, 0.8e5), damping_ratio=0.03,
                         devices={1: r1_wall(), 2: r1_wall(), 3: r1_wall(0.8)} if walls else {},
                         story_heights=(3500.0, 3200.0, 3200.0) if heights else None)


def synthetic_records(count: int = 14, duration: float = 12.0):
    """``count`` short synthetic records of different seeds and ground frequencies (mm/s^2)."""
    frequencies = np.linspace(1.5, 4.0, count)
    return [synthetic_ground_motion(duration=duration, dt=0.01, pga=0.3 * 9806.65, seed=100 + i,
                                    ground_frequency=float(f), strong_motion_end=7.0, name=f"synthetic {i}")
            for i, f in enumerate(frequencies)]
