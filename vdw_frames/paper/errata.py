"""The paper's errata and the numbers of the reproduction report, computed (no rendering here).

Every number :mod:`vdw_frames.paper.report` prints comes from these functions, from the printed data in
:mod:`vdw_frames.paper.data`, the model (:class:`~vdw_frames.element.damper.FDMKDamper`), the
identification (:mod:`vdw_frames.paper.identification`) and the strain-dependent model
(:mod:`vdw_frames.paper.strain_dependence`); the tests check them here.

Units: moduli MPa, stiffness N/mm (the tables' kN/mm times :data:`N_PER_KN`), areas N*mm, frequency Hz.
"""

from __future__ import annotations

import dataclasses
from dataclasses import dataclass
from typing import Any

import numpy as np

from ..element.damper import FDMKDamper
from ..element.sine import sine_test
from ..element.strain_dependent import PARAMETERS, StrainDependentDamper
from . import data as paper
from . import strain_dependence
from .data import FREQUENCIES, STRAINS, TABLE4, TABLE5, TABLES, Table5Row
from .identification import IdentificationResult, identify

N_PER_KN = 1.0e3
"""N per kN: the tables print stiffness in kN/mm and areas in kN*mm."""


@dataclass(frozen=True)
class ParameterSet:
    """One parameter set compared with the tables: a damper per strain level (paper A and h)."""

    key: str
    label: str
    dampers: dict[int, FDMKDamper]  # strain (%) -> FDMKDamper
    results: dict[int, IdentificationResult]  # strain (%) -> IdentificationResult, or {} for Table 4


def _pooled() -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    frequency = np.concatenate([FREQUENCIES for _ in STRAINS])
    storage = np.concatenate([TABLES[s]["storage_modulus"] for s in STRAINS])
    loss = np.concatenate([TABLES[s]["loss_modulus"] for s in STRAINS])
    return frequency, storage, loss


def parameter_sets() -> list[ParameterSet]:
    """Table 4 and this package's fits: per strain (both objectives), r fixed at 0.60, all strains pooled."""
    sets = [ParameterSet("table4", "Table 4 (paper)", {s: FDMKDamper(**TABLE4) for s in STRAINS}, {})]
    for residual in ("relative", "absolute"):
        per_strain = {s: identify(*paper.table_moduli(s), residual=residual) for s in STRAINS}
        sets.append(ParameterSet(f"{residual}", f"fit per strain, {residual}",
                                 {s: res.damper() for s, res in per_strain.items()}, per_strain))
    for residual in ("relative", "absolute"):
        fixed = {s: identify(*paper.table_moduli(s), residual=residual, fixed={"r": 0.6}) for s in STRAINS}
        sets.append(ParameterSet(f"r060_{residual}", f"fit per strain, r = 0.60, {residual}",
                                 {s: res.damper() for s, res in fixed.items()}, fixed))
    for residual in ("relative", "absolute"):
        joint = identify(*_pooled(), residual=residual)
        sets.append(ParameterSet(f"joint_{residual}", f"joint fit (all strains), {residual}",
                                 {s: joint.damper() for s in STRAINS}, {s: joint for s in STRAINS}))
    return sets


def fit_measures(damper: FDMKDamper, strain: float) -> tuple[float, float, float, float]:
    """(absolute SSE, relative SSE, max |rel err| G', max |rel err| G'') of ``damper`` on one table."""
    _, storage, loss = paper.table_moduli(strain)
    modulus = damper.complex_modulus(FREQUENCIES)
    absolute = np.concatenate([modulus.real - storage, modulus.imag - loss])
    relative = np.concatenate([modulus.real / storage - 1.0, modulus.imag / loss - 1.0])
    n = FREQUENCIES.size
    return (float(absolute @ absolute), float(relative @ relative),
            float(np.abs(relative[:n]).max()), float(np.abs(relative[n:]).max()))


@dataclass(frozen=True)
class Table5Candidate:
    """A candidate definition of the "theoretical" loop areas of Table 5 (kN*mm, in TABLE5's row order)."""

    label: str
    areas: np.ndarray
    method: str
    frequency_domain: np.ndarray | None = None  # pi K'' U^2 of the same damper (kN*mm), time-domain candidates only

    def deviation(self) -> np.ndarray:
        """(candidate - printed theoretical) / printed theoretical, per row."""
        return self.areas / np.array([row.theoretical for row in TABLE5]) - 1.0

    def delta(self) -> np.ndarray:
        """Delta of eq. (13) against the printed experimental areas, per row (fraction)."""
        experimental = np.array([row.experimental for row in TABLE5])
        return np.abs(experimental - self.areas) / experimental


def table_scale() -> float:
    """A/h (mm) that the printed K'_d (kN/mm) implies: K'_d / G', converted to N/mm per MPa."""
    ratios = [TABLES[s]["storage_stiffness"] * N_PER_KN / TABLES[s]["storage_modulus"] for s in STRAINS]
    return float(np.median(np.concatenate(ratios)))


def loop_area_scale() -> np.ndarray:
    """A/h (mm) that Table 5's measured loop areas imply, per row: area [N*mm] / (pi G'' [MPa] U^2), U = strain x h
    with the paper's h (only the force's first harmonic dissipates over a sinusoidal cycle, so any loop has area
    pi K'' U^2)."""
    printed_g2 = np.array([TABLES[row.strain]["loss_modulus"][row.frequency == FREQUENCIES][0] for row in TABLE5])
    amplitude = np.array([row.strain / 100.0 * paper.THICKNESS for row in TABLE5])
    experimental = np.array([row.experimental for row in TABLE5])
    return experimental * N_PER_KN / (np.pi * printed_g2 * amplitude**2)


def table5_candidates(sets: list[ParameterSet] | None = None) -> list[Table5Candidate]:
    """Every candidate definition of Table 5's theoretical areas, computed (see the report)."""
    sets = parameter_sets() if sets is None else sets
    by_key = {s.key: s for s in sets}
    scale_of_tables = table_scale()
    geometries = (  # (label, thickness giving U = strain * thickness, area)
        (f"U = strain x h, h = {paper.THICKNESS:g} mm, A = {paper.AREA:g} mm^2", paper.THICKNESS, paper.AREA),
        (f"U = strain x h, A/h = {scale_of_tables:g} mm (the tables' K'/G')", paper.THICKNESS,
         scale_of_tables * paper.THICKNESS),
        (f"U = strain x 4h = strain x {4 * paper.THICKNESS:g} mm (as if the four layers were in series; "
         f"they are not: they work in parallel), A = {paper.AREA:g} mm^2",
         4 * paper.THICKNESS, paper.AREA),
    )
    candidates = []
    for key in ("table4", "relative", "absolute", "joint_relative"):
        for geometry, thickness, area in geometries:
            areas, steady = [], []
            for row in TABLE5:
                damper = dataclasses.replace(by_key[key].dampers[row.strain], area=area, thickness=thickness)
                amplitude = row.strain / 100.0 * thickness
                areas.append(sine_test(damper, amplitude, row.frequency).loop_area / N_PER_KN)
                steady.append(np.pi * damper.loss_stiffness(row.frequency) * amplitude**2 / N_PER_KN)
            candidates.append(Table5Candidate(f"{by_key[key].label}; {geometry}", np.array(areas),
                                              "time-domain sine test (5 cycles from rest, last loop)",
                                              np.array(steady)))
    for scale, scale_label in ((paper.AREA / paper.THICKNESS, "A/h = 1e5 mm"), (scale_of_tables, "A/h = 1000 mm")):
        areas = [np.pi * paper.printed_eq10_stiffness(2 * np.pi * row.frequency, **TABLE4, area=scale,
                                                      thickness=1.0)[1]
                 * (row.strain / 100.0 * paper.THICKNESS) ** 2 / N_PER_KN for row in TABLE5]
        candidates.append(Table5Candidate(f"Table 4 under printed (8)/(10), {scale_label}, U = strain x h",
                                          np.array(areas), "pi K''_d U^2 with K''_d from the printed eq. (10)"))
    for thickness in (paper.THICKNESS, 4 * paper.THICKNESS):
        areas = [np.pi * table_row(row, "loss_stiffness") * (row.strain / 100.0 * thickness) ** 2
                 for row in TABLE5]
        candidates.append(Table5Candidate(f"printed K''_d (kN/mm) of Tables 1-3, U = strain x {thickness:g} mm",
                                          np.array(areas), "pi K''_d U^2 from the tables"))
    return candidates


def table_row(row: Table5Row, column: str) -> float:
    return float(TABLES[row.strain][column][list(FREQUENCIES).index(row.frequency)])


def errata() -> dict[str, Any]:
    """Every number of the report's errata section (keys documented inline)."""
    omega = 2 * np.pi * FREQUENCIES
    table4 = FDMKDamper(**TABLE4)
    out: dict[str, Any] = {"frequency": FREQUENCIES, "omega": omega}
    out["model_table4"] = table4.complex_modulus(FREQUENCIES)  # correct model, MPa
    out["eq7_table4"] = paper.printed_eq7_modulus(omega, **TABLE4)  # printed (7), "MPa"
    out["eq8_table4"] = np.array(paper.printed_eq8_moduli(omega, **TABLE4))  # printed (8): rows G', G''
    out["eq10_table4"] = np.array(paper.printed_eq10_stiffness(omega, **TABLE4))  # N/mm
    out["eq11_table4"] = paper.printed_eq11_damping_coefficient(omega, **TABLE4)  # N*s/mm
    out["eq9_table4"] = paper.printed_eq9_loss_factor(omega, **TABLE4)  # printed (9), "loss factor"
    out["cos_r_pi"] = float(np.cos(TABLE4["r"] * np.pi))
    # Table 4 against each table under the model, printed (7) and printed (8): abs SSE, rel SSE, max rel errs.
    versions = {"model": out["model_table4"], "eq7": out["eq7_table4"],
                "eq8": out["eq8_table4"][0] + 1j * out["eq8_table4"][1]}
    out["table4_fit"] = {}
    for name, modulus in versions.items():
        for strain in STRAINS:
            _, storage, loss = paper.table_moduli(strain)
            rel = np.concatenate([modulus.real / storage - 1.0, modulus.imag / loss - 1.0])
            ab = np.concatenate([modulus.real - storage, modulus.imag - loss])
            out["table4_fit"][name, strain] = (float(ab @ ab), float(rel @ rel), float(np.abs(rel[:6]).max()),
                                               float(np.abs(rel[6:]).max()))
    # Internal consistency of Tables 1-3.
    consistency = {}
    for strain in STRAINS:
        t = TABLES[strain]
        consistency[strain] = {
            "loss_factor_minus_ratio": t["loss_factor"] - t["loss_modulus"] / t["storage_modulus"],
            "storage_scale": t["storage_stiffness"] * N_PER_KN / t["storage_modulus"],  # N/mm per MPa = mm
            "loss_scale": t["loss_stiffness"] * N_PER_KN / t["loss_modulus"],
            "cd_times_omega_over_k": t["damping_coefficient"] * omega / t["loss_stiffness"],
            "cd_times_f_over_k": t["damping_coefficient"] * FREQUENCIES / t["loss_stiffness"],
            # Is C_d = K''_d / f within the rounding of the printed two decimals?
            "cd_is_k_over_f": np.abs(t["damping_coefficient"] - t["loss_stiffness"] / FREQUENCIES)
            <= 0.005 + 0.005 / FREQUENCIES + 1e-12,
            "cd_is_k_over_1p5": (FREQUENCIES == 1.0)
            & (np.abs(t["damping_coefficient"] - t["loss_stiffness"] / 1.5) <= 0.005 + 0.005 / 1.5 + 1e-12),
            "storage_change": t["storage_modulus"][-1] / t["storage_modulus"][0] - 1.0,
            "storage_steps": np.diff(t["storage_modulus"]),
            # Local Kramers-Kronig (Booij & Thoone): dG'/dln(omega) ~ (2/pi) G''; trapezoid over the data.
            "kk_predicted_rise": float(2.0 / np.pi * np.sum(0.5 * (t["loss_modulus"][1:] + t["loss_modulus"][:-1])
                                                             * np.diff(np.log(omega)))),
            "observed_rise": float(t["storage_modulus"][-1] - t["storage_modulus"][0]),
        }
    out["consistency"] = consistency
    out["implied_area_over_thickness"] = table_scale()  # mm
    out["implied_thickness"] = paper.AREA / out["implied_area_over_thickness"]  # mm, for A = 1e6 mm^2
    out["implied_area"] = out["implied_area_over_thickness"] * paper.THICKNESS  # mm^2, for h = 10 mm
    # Table 5: Delta recomputed by eq. (13) from the printed areas, and the 0.5/1.5 Hz and strain ratios.
    theoretical = np.array([row.theoretical for row in TABLE5])
    experimental = np.array([row.experimental for row in TABLE5])
    out["table5_delta_recomputed"] = 100.0 * np.abs(experimental - theoretical) / experimental
    out["table5_delta_over_theoretical"] = 100.0 * np.abs(experimental - theoretical) / theoretical
    # Measured areas against pi K''_d U^2 of the printed loss stiffness (U = strain x h, h = 10 mm): only the
    # first harmonic of the force dissipates over a sinusoidal cycle, so any loop, nonlinear or not, has
    # area pi K'' U^2 with K'' its first-harmonic loss stiffness.
    printed_loss = np.array([TABLES[row.strain]["loss_stiffness"][row.frequency == FREQUENCIES][0] for row in TABLE5])
    amplitude = np.array([row.strain / 100.0 * paper.THICKNESS for row in TABLE5])
    out["table5_experimental_over_pi_k_u2"] = experimental / (np.pi * printed_loss * amplitude**2)
    out["table5_implied_area_over_thickness"] = loop_area_scale()
    out["table5_delta_printed"] = np.array([row.delta for row in TABLE5])
    out["table5_theory_over_experiment"] = theoretical / experimental
    out["table5_ratio_05_over_15"] = theoretical[0::2] / theoretical[1::2]  # per strain
    out["table5_ratio_strain"] = theoretical[0::2] / theoretical[0]  # 0.5 Hz areas / the 225 % one
    out["table5_ratio_strain_squared"] = (np.array(STRAINS) / STRAINS[0]) ** 2
    # How well r is determined: the relative-objective sum with r pinned, over the best free-r sum.
    out["r_profile_orders"] = np.array([0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.8, 1.0])
    out["r_profile"] = {}
    for strain in STRAINS:
        data = paper.table_moduli(strain)
        best = identify(*data, residual="relative").sse
        out["r_profile"][strain] = np.array([identify(*data, residual="relative", fixed={"r": r}).sse / best
                                             for r in out["r_profile_orders"]])
    # Any FDMK parameters: G' never falls with frequency.  A deterministic sample of 2000 sets.
    out["monotone_min_step"] = _min_storage_step(2000)
    return out


def _min_storage_step(count: int) -> float:
    """Smallest G'(f_{k+1}) - G'(f_k) (MPa) over ``count`` log-uniform FDMK parameter sets on 0.01-100 Hz."""
    rng = np.random.default_rng(20160529)
    f = np.geomspace(0.01, 100.0, 400)
    low = np.inf
    for _ in range(count):
        g1, g2, e1, e2 = 10.0 ** rng.uniform(-3, 2, 4)
        damper = FDMKDamper(G1=g1, G2=g2, eta1=e1, eta2=e2, r=rng.uniform(0.01, 1.0))
        low = min(low, float(np.diff(damper.storage_modulus(f)).min()))
    return low


def interpolated_optima() -> StrainDependentDamper:
    """The per-strain optima (``FITTED``) interpolated linearly in log strain: the naive family (paper A, h)."""
    return StrainDependentDamper.from_nodes(
        {"strains": tuple(s / 100.0 for s in STRAINS),
         **{name: tuple(paper.FITTED[s][name] for s in STRAINS) for name in PARAMETERS}},
        area=paper.AREA, thickness=paper.THICKNESS)


def strain_dependence_numbers() -> dict[str, np.ndarray]:
    """The numbers of the report's strain-dependence section.

    ``strains`` (%): the joint fit's strains; ``best``: the best FDMK relative objective at each (on the
    table or the interpolated tables); ``model`` and ``naive``: the objective of the strain-dependent
    model and of the interpolated per-strain optima there.
    """
    model, naive = strain_dependence.strain_dependent(common_order=False), interpolated_optima()
    strains = strain_dependence.identification_strains()

    def objective(wall: StrainDependentDamper, strain: float) -> float:
        errors = strain_dependence.relative_errors(wall.complex_modulus(FREQUENCIES, strain / 100.0), strain)
        return float(errors @ errors)

    return {
        "strains": strains,
        "best": np.array([identify(*strain_dependence.interpolated_moduli(s), residual=paper.RECOMMENDED_RESIDUAL).sse
                          for s in strains]),
        "model": np.array([objective(model, s) for s in strains]),
        "naive": np.array([objective(naive, s) for s in strains]),
    }


def fixed_sets(strain: float) -> list[int]:
    """The per-strain set(s) whose FIT_RANGE holds ``strain`` (%): one, or two at a boundary."""
    return [key for key, (low, high) in paper.FIT_RANGE.items() if low <= strain <= high]
