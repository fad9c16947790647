"""Paper figures that are not error tables or convergence plots: each module's
write(profile_name) computes or renders what it needs and returns the files it wrote.
`make plots` (and so `make run` and `make reproduce`) writes them after the harness's plots."""
from pathlib import Path

from . import pmc_fig04_buddha, ris_fig01_resampling, ris_fig03_m_over_n, twostage_fig12_time

FIGURES = [pmc_fig04_buddha, ris_fig01_resampling, ris_fig03_m_over_n, twostage_fig12_time]


def write_all(profile_name: str) -> list[Path]:
    written: list[Path] = []
    for figure in FIGURES:
        written += figure.write(profile_name)
    return written
