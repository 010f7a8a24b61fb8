"""Regenerate the default ground-motion record(s) that ship as package data in vdw_frames/motion/data/.

    python ground_motions/make_records.py            # rewrites the shipped files
    python ground_motions/make_records.py --out DIR  # writes them to DIR instead

Deterministic: the records come from a fixed seed through vdw_frames.motion, so rerunning this
script reproduces the shipped files (tests/test_ground_motion.py checks that it does).
"""

from __future__ import annotations

import argparse
from pathlib import Path

from vdw_frames.motion import G, synthetic_ground_motion, write_at2
from vdw_frames.motion.synthetic import DEFAULT_RECORD, default_record_path

# file name -> (synthetic_ground_motion keyword arguments, two free-text header lines)
RECORDS = {
    DEFAULT_RECORD: (
        dict(duration=25.0, dt=0.01, pga=0.35 * G, seed=1940, name="synthetic_kt_035g"),
        ["SYNTHETIC GROUND MOTION (NOT A RECORDING), VDW_FRAMES GROUND_MOTIONS/MAKE_RECORDS.PY",
         "CLOUGH-PENZIEN FILTERED WHITE NOISE (KT 2.5 HZ, 0.6), JENNINGS ENVELOPE, SEED 1940, PGA 0.35 G"],
    ),
}


def write_records(directory) -> list[Path]:
    """Write every record of RECORDS into ``directory``; returns the paths written."""
    directory = Path(directory)
    directory.mkdir(parents=True, exist_ok=True)
    return [write_at2(synthetic_ground_motion(**arguments), directory / file_name, header)
            for file_name, (arguments, header) in RECORDS.items()]


def main(argv=None) -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--out", type=Path, default=default_record_path().parent,
                        help="folder to write the records to (default: the package's vdw_frames/motion/data/)")
    for path in write_records(parser.parse_args(argv).out):
        print(f"wrote {path}")


if __name__ == "__main__":
    main()
