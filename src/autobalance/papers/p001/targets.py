"""Reproduction targets of seed 001 (Drach 2018: the fluid balancer, influence of the viscosity
of the liquid) for ``autobalance reproduce 001``: kinetostatic liquid angle (eq 2-4), laminar
friction (eq 5-7) and the trends of its experiments (Fig. 3-6; the Ukrainian text and most
figure numbers were lost in extraction, the English abstract survives).

This module wires the targets; the published statements are in :mod:`.published`, the
computations and rows in :mod:`.kinetostatics` and :mod:`.trends`. 001's bench is modelled by
003's bench preset (:mod:`autobalance.papers.p003.bench`).
"""
from __future__ import annotations

from ...validation.target import Target
from ..p003.bench import QUICK
from ..p003.fig5_6 import PHYSICAL_NOTE
from . import kinetostatics, trends
from .published import ITEMS_001, PUBLISHED

__all__ = ["ITEMS_001", "PUBLISHED", "TARGETS"]

TARGETS = [
    Target("001-fig1-2", "001", ("Fig. 1", "Fig. 2"), "Unbalance scheme and bench schematic",
           None, PUBLISHED["001-fig1-2"],
           notes="Schematics: nothing to compute. Fig. 1's vectors are the notation of 001 eq "
                 "1-4 (001-eq3-4); Fig. 2's bench is modelled by the leblanc_003 preset."),
    Target("001-eq3-4", "001", ("eq 3", "eq 4"), "Kinetostatic liquid angle and residual",
           kinetostatics.run_eq3_4, PUBLISHED["001-eq3-4"],
           notes="001 eq 3 as published (the root of eq 2 that 001 selects); where k < sin "
                 "delta the square root is clipped at 0 (our choice). Miss: 001's damping trend "
                 "contradicts its own eq 3.", quick=QUICK),
    Target("001-eq5-7", "001", ("eq 5", "eq 6", "eq 7"), "Laminar friction force and angle",
           kinetostatics.run_eq5_7, PUBLISHED["001-eq5-7"],
           notes="Checks of 001's derivation (Hagen-Poiseuille lambda = 64/Re) and of our "
                 "implementation; the wetted arc xi = 180 deg is our choice (001 gives none).",
           quick=QUICK),
    Target("001-fig3-6", "001", ("Fig. 3", "Fig. 4", "Fig. 5", "Fig. 6"),
           "Density and viscosity of the working liquid (experimental trends)",
           trends.run_fig3_6, PUBLISHED["001-fig3-6"],
           notes=PHYSICAL_NOTE + " 001's figure data did not survive extraction: the "
                 "abstract's statements are compared, each liquid at the fill rho V R = D "
                 "(001's sufficient volume) unless stated. Liquid properties lost in "
                 "extraction are our choices (liquids_001.toml). The misses are physics: "
                 "below resonance the liquid raises the whirl, and the steady whirl does not "
                 "depend on viscosity.", quick=QUICK),
]
