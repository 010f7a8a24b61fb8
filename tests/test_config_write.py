"""Writing building files (vdw_frames.config.save_building / building_to_dict): every device kind, story model,
thermal description and limit written and read back (load_building) gives the building the constructor made,
every array bit for bit; [site] and [verification] come back as given; a building that a building file cannot
say is refused with a ValueError naming why, and leaves an existing file as it was."""

from __future__ import annotations

import dataclasses
import math

import numpy as np
import pytest
from builders import mixed_devices_building

from vdw_frames import BoucWen, FluidViscousDamper, FrictionDamper, ShearBuilding, paper
from vdw_frames.config import building_to_dict, load_building, load_verification, save_building
from vdw_frames.element.catalogue import strain_dependent
from vdw_frames.element.damper import FDMKDamper
from vdw_frames.element.limits import WallLimits
from vdw_frames.element.supported import SupportedDamper
from vdw_frames.element.thermal import ISD110_LOSS_PEAK, WLF, Arrhenius, ThermalProperties
from vdw_frames.frame.hysteresis import Bilinear
from vdw_frames.verification import PropertyBounds, Site


def bits(values):
    """The bytes of a float64 array: equal bytes are equal bits (NaN, -0.0 and all)."""
    return np.asarray(values, dtype=np.float64).tobytes()


def assert_same_building(read, built):
    """Field by field (a ShearBuilding compares by identity); the per-story arrays bit for bit."""
    for name in ("masses", "stiffnesses", "story_heights", "gravity_loads"):
        one, other = getattr(read, name), getattr(built, name)
        assert (one is None) == (other is None), name
        if one is not None:
            assert bits(one) == bits(other), name
    for item in dataclasses.fields(built):
        assert getattr(read, item.name) == getattr(built, item.name), item.name
    assert [type(d) for _, d in read.device_list] == [type(d) for _, d in built.device_list]
    assert bits(read.stiffness_matrix) == bits(built.stiffness_matrix)


# Values with long binary expansions (1/3, 0.1 + 0.2, pi): a writer that rounds would change their bits.
THIRD, ODD = 1.0 / 3.0, 0.1 + 0.2


def every_device_building():
    """Four stories with every kind the package has: fitted and explicit FDMK walls (with thermal
    descriptions of a named and two written-out shift laws, limits and a magnification), the paper's
    strain-dependent walls, linear and nonlinear FVDs (with and without a brace), friction dampers, several
    devices of a kind in one story and a story without any; Bouc-Wen stories, P-Delta, modal damping."""
    wlf = WLF(C1=8.0 + THIRD, C2=120.0, reference=21.2, valid=(0.0, 60.0), source='a "quoted" source\twith a tab')
    arrhenius = Arrhenius(activation_energy=2.0e5 + ODD, reference=20.0, valid=(-10.0, 50.0))
    explicit = FDMKDamper(G1=0.1 + ODD, G2=3.0, eta1=THIRD, eta2=2.0, r=0.5 + THIRD / 10, area=2.0e5 + THIRD,
                          thickness=7.0, thermal=ThermalProperties(wlf, 1.8, temperature=25.0, cooling_time=600.0),
                          limits=WallLimits(strain=8.5, stress=2.0, temperature=80.0, residual=0.1, source="test"),
                          magnification=0.9)
    fitted = paper.fitted(225, area=3.0e5, thickness=20.0)
    heated = dataclasses.replace(paper.fitted(450, area=1.5e5, thickness=9.0),
                                 thermal=ThermalProperties(ISD110_LOSS_PEAK, 1.7))
    following = strain_dependent(area=4.0e5 + THIRD, thickness=6.0,
                                 thermal=ThermalProperties(arrhenius, 2.0, cooling_time=math.pi),
                                 limits=WallLimits(strain=6.0))
    devices = {
        1: (fitted, fitted, FluidViscousDamper(C=150.0 + THIRD, alpha=1.0), explicit),
        2: (following, FrictionDamper(slip_force=2.0e4 + ODD, stiffness=6.0e4, magnification=0.8),
            FrictionDamper(slip_force=2.0e4 + ODD, stiffness=6.0e4, magnification=0.8)),
        3: (heated, FluidViscousDamper(C=1500.0, alpha=0.35 + ODD, stiffness=8.0e4 + THIRD, magnification=0.7)),
    }
    models = [BoucWen(2.0e6 + THIRD, hardening=0.02, exponent=2.0, beta=0.6, gamma=0.4 + ODD / 10)
              for _ in range(3)] + [BoucWen(1.0e6, hardening=0.02, exponent=2.0, beta=0.6, gamma=0.4 + ODD / 10)]
    return ShearBuilding([300.0 + THIRD, 300.0, 300.0, 250.0], [2.0e5, 1.8e5 + ODD, 1.6e5, 1.4e5],
                         damping_ratio=0.03 + ODD / 100, damping_modes=(1, 3), devices=devices,
                         story_heights=[3500.0 + THIRD, 3500.0, 3500.0, 3500.0], hysteresis=models,
                         gravity_loads=[9.0e6 + THIRD, 6.0e6, 3.0e6, 1.0e6], damping_model="modal")


@pytest.mark.parametrize("suffix", [".toml", ".json"])
def test_every_device_kind_comes_back_bit_for_bit(tmp_path, suffix):
    built = every_device_building()
    path = save_building(built, tmp_path / f"building{suffix}")
    read = load_building(path)
    assert_same_building(read, built)
    # Device by device, in their order in each story, every number the same bits
    for (story, one), (story_read, other) in zip(built.device_list, read.device_list, strict=True):
        assert story == story_read and one == other
        for item in dataclasses.fields(one):
            value = getattr(one, item.name)
            if isinstance(value, float):
                assert bits(getattr(other, item.name)) == bits(value), (story, item.name)


def test_the_shared_test_building_and_bilinear_stories(tmp_path):
    built = dataclasses.replace(mixed_devices_building(), gravity_loads=[4e6, 3e6, 2e6, 1e6],
                                hysteresis=[Bilinear(1.0e6 * (4 - s), 0.03) for s in range(4)])
    assert_same_building(load_building(save_building(built, tmp_path / "mixed.toml")), built)


def test_a_bare_linear_frame_needs_no_tables(tmp_path):
    built = ShearBuilding([10.0, 10.0], [1.0e4, 1.0e4])
    data = building_to_dict(built)
    assert set(data) == {"masses", "stiffnesses", "damping_ratio", "damping_modes", "damping_model"}
    assert_same_building(load_building(save_building(built, tmp_path / "bare.toml")), built)


def test_devices_of_a_kind_in_every_story_are_one_group_with_per_story_lists():
    walls = {story: (paper.fitted(300, area=1.0e5 * story, thickness=10.0),) for story in (1, 2, 3)}
    data = building_to_dict(ShearBuilding([1.0] * 3, [1e3] * 3, devices=walls))
    assert data["devices"] == [{"type": "wall", "stories": "all", "parameters": "fitted-300",
                                "area": [1.0e5, 2.0e5, 3.0e5], "thickness": 10.0}]


@pytest.mark.parametrize("site", [Site(1.5, 0.9, 8.0, "III"), Site.from_mapped(1.5, 0.5, "C", 6.0),
                                  # S_1 >= 0.6: mapped values refused for a damped building (Sec. 11.4.8), so
                                  # the file gives S_MS and S_M1 instead
                                  Site.from_mapped(1.5, 0.6, "C", 6.0, damping_system=False)])
def test_site_and_bounds_come_back(tmp_path, site):
    bounds = PropertyBounds(0.8, 1.2 + ODD, "a stated source", ambient=(0.0, 40.0))
    path = save_building(every_device_building(), tmp_path / "verify.toml", site=site, bounds=bounds)
    _, read_site, read_bounds = load_verification(path)
    assert read_bounds == bounds
    for name in ("sms", "sm1", "tl", "risk_category"):
        assert getattr(read_site, name) == getattr(site, name)
    assert (read_site.ss is not None) == (site.ss is not None and site.s1 < 0.6)


def test_a_comment_heads_a_toml_file(tmp_path):
    text = save_building(ShearBuilding([1.0], [1.0]), tmp_path / "a.toml", comment="line one\n\nline three").read_text()
    assert text.startswith("# line one\n#\n# line three\n")


@pytest.mark.parametrize(("building", "message"), [
    (ShearBuilding([1.0, 1.0], [1e3, 1e3], hysteresis=[Bilinear(10.0, 0.01), Bilinear(10.0, 0.02)]),
     "hardening differ"),
    (ShearBuilding([1.0, 1.0], [1e3, 1e3], hysteresis=[Bilinear(10.0), BoucWen(10.0)]), "mix Bilinear and BoucWen"),
    (ShearBuilding([1.0, 1.0], [1e3, 1e3], hysteresis=[Bilinear(10.0), None]), r"stories \[2\] are linear"),
    (ShearBuilding([1.0], [1e3], devices={1: SupportedDamper(paper.fitted(300), 1.0e5)}),
     "SupportedDamper cannot be written"),
    (ShearBuilding([1.0], [1e3], devices={1: strain_dependent(common_order=False)}),
     "strain-dependent wall of other tables"),
])
def test_a_building_a_file_cannot_say_is_refused_and_the_old_file_kept(tmp_path, building, message):
    path = tmp_path / "kept.toml"
    path.write_text("old contents\n")
    with pytest.raises(ValueError, match=message):
        save_building(building, path)
    assert path.read_text() == "old contents\n"


def test_a_path_of_another_kind_is_refused(tmp_path):
    with pytest.raises(ValueError, match=r"must end in \.toml or \.json"):
        save_building(ShearBuilding([1.0], [1.0]), tmp_path / "building.yaml")
