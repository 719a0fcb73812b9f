"""The command line's vocabulary: one option name for one meaning, in every command.

:data:`VOCABULARY` is the list of every option name the commands take, with its one meaning;
``tests/test_cli_vocabulary.py`` checks every command against it (each option is in it, a name
takes the same kind of value everywhere, each study takes the shared study options) and the
documentation's reference of the options is generated from it. :data:`DEPRECATED` holds the
names an option had before, per command, and :data:`DEPRECATED_COMMANDS` the commands merged
into another, :data:`IGNORED` the options a command takes without effect:
:func:`rewrite_deprecated` still accepts them for one version and says what to use instead.
"""
from __future__ import annotations

__all__ = ["DEPRECATED", "DEPRECATED_COMMANDS", "IGNORED", "REMOVED_IN", "STUDY_SHARED",
           "VOCABULARY", "rewrite_deprecated"]

#: Option name -> its meaning, the same in every command that takes it.
VOCABULARY: dict[str, str] = {
    # the machine and its changes
    "--set": "change one config key for this run: PATH=VALUE with units, repeatable (-s)",
    "-s": "short for --set",
    "--profile": "the speed profile kind: std, tsr, motor, ... (the config's keys for it apply)",
    "--units": "units of the text output: si, or KIND=UNIT,... (default: as the config writes "
               "them); JSON is always SI",
    # what is asked
    "--grade": "target ISO 1940 grade G [mm/s] (default 16)",
    "--speed": "one speed to analyse at, with units (default the machine's nominal speed)",
    "--speeds": "speeds: a range LO:HI:N or a list 'a, b, c unit', a unit written once "
                "applying to all",
    "--angles": "ball angles, a list with units",
    "--starts": "start positions per ball of 004's equispaced grid (N per ball)",
    "--random": "uniform random start positions instead of the grid: this many",
    "--seed": "seed of the random start positions",
    "--budget": "most runs added where a decision is undecided at 95 % confidence",
    "--confidence": "share of start positions that must meet the target [-]",
    "--mu-r": "factors on the balls' rolling resistance, a list",
    "--c-r": "factors on the suspension damping, a list",
    "--g-ini": "initial unbalance as a grade [mm/s]",
    "--g-max": "largest initial grade of the grid [mm/s]",
    "--steps": "intervals of the initial-grade grid",
    "--ratios": "plateau speeds as multiples of the natural frequency, a list",
    "--grid": "a sweep axis PATH=V1,V2 or PATH=LO:HI:N, repeatable",
    "--vary": "one variant of the model: overrides joined by ';', repeatable",
    "--z": "the z-score of the sensitivity's significance",
    "--split": "shares of the residual unbalance per cause",
    "--method": "which method: the true bound or the paper's",
    "--residual-fraction": "000's one-ball method: required residual / M e [-]",
    "--check": "also check by simulation",
    "--threshold": "balancing threshold as a fraction of e = U/M_t [-]",
    "--law": "motor torque laws, a list",
    "--bare": "also run without the balls", "--no-bare": "do not run without the balls",
    "--ks-only": "only the kinetic-static verdict, not the full model's",
    "--full-model": "also the linearised full model",
    "--fills": "liquid fills, a range or list with units",
    "--dynamic": "also the coupled film in time", "--linear": "also the linear stability",
    "--duration": "simulated time [s], with units",
    "--cells": "cells of the liquid's film grid",
    # design
    "--balls": "ball counts to try, a list", "--capacity": "ball capacity N m R as "
                                                          "multiples of the largest unbalance",
    "--radii": "race radii to try, a list with units",
    "--profiles": "speed profiles to try: given, std, slow, tsr",
    "--unbalance": "an unbalance with units, or a range LO:HI",
    "--n-unbalance": "unbalances across the range",
    "--refine-plateau": "run the plateau study on the best TSR candidate",
    "--no-refine-plateau": "do not run the plateau study",
    # the liquid's own commands
    "--volume": "liquid volume, with units (-V)", "-V": "short for --volume",
    "--radius": "chamber radius, with units (-R)", "-R": "short for --radius",
    "--height": "chamber height, with units", "--gravity": "gravity, with units",
    "--gravity-fraction": "share of gravity in the speeds' criterion [-]",
    "--liquid": "one of 001's liquids (density and viscosity)",
    "--delta": "rotor phase angles, a range or list with units",
    "--k": "001's k = D0/D [-]", "--arc": "the liquid's arc, with units",
    "--settle": "settling time of each speed, with units",
    "--placement": "the lumped model's law", "--model": "which liquid model",
    "--run-up": "also integrate the run-up", "--no-run-up": "do not integrate the run-up",
    "--fill-sweep": "amplitude against fill (003 Fig. 5)",
    "--damping-plot": "figure of the damping sweep",
    "--f-r": "factor on the rolling resistance",
    # how and where it runs
    "--quick": "coarse grids: minutes on 2 cores",
    "--full": "the papers' own grids (hours, resumable)",
    "--store": "keep the simulations in resumable stores under DIR",
    "--resume": "continue the store's sweep",
    "--executor": "serial, local (processes) or dask",
    "--workers": "local worker processes",
    "--scheduler": "a Dask scheduler's address, tcp://host:port",
    # outputs
    "--out": "write the dataset to this file (NetCDF)",
    "--out-dir": "write the files into this directory",
    "--plot": "write the figure to this file (.png, .svg, .pdf)",
    "--json": "print one JSON object in SI on stdout",
    "--version": "print the version and exit (the program's own option)",
    "--list": "list the choices and exit",
}

#: The options every ``autobalance study`` command takes (docs/commands.md lists the others).
STUDY_SHARED = ("--set", "--profile", "--units", "--json")

#: The version that drops the names of :data:`DEPRECATED`.
REMOVED_IN = "0.4.0"

_STARTS = {"--n": "--starts"}
_LIQUID_SPEEDS = {"--omega": "--speeds"}
#: Command -> {former option name: the name to use}, accepted until :data:`REMOVED_IN`.
DEPRECATED: dict[tuple[str, ...], dict[str, str]] = {
    ("study", "start-positions"): _STARTS, ("study", "unbalance-range"): _STARTS,
    ("study", "plateau"): _STARTS, ("study", "sensitivity"): _STARTS,
    ("study", "immobility"): {"--n-conf": "--starts"},
    ("study", "speed-map"): {"--damping": "--c-r"},
    ("study", "runup"): {"--fraction": "--threshold"},
    ("design",): {"--starts": "--random"},
    # the 000 method of `study tolerances` (`analyze tolerance` gave it beside the bound)
    ("analyze", "tolerance"): {"--fraction": "--method 000 --residual-fraction",
                               "--residual-fraction": "--method 000 --residual-fraction"},
    ("analyze", "equilibria"): {"--full": "--full-model"},
    ("reproduce",): {"--out": "--out-dir"}, ("demo",): {"--out": "--out-dir"},
    ("liquid", "surface"): {**_LIQUID_SPEEDS, "--g": "--gravity"},
    ("liquid", "modes"): {**_LIQUID_SPEEDS, "--g": "--gravity"},
    ("liquid", "speeds"): {"--g": "--gravity"},
    ("liquid", "simulate"): _LIQUID_SPEEDS, ("liquid", "stability"): _LIQUID_SPEEDS,
    ("liquid", "kinetostatic-check"): _LIQUID_SPEEDS,
    ("liquid", "kinetostatic"): {"--omega": "--speed"},
}

#: Command -> {an option that has no effect there, taking one value: why}, accepted (and
#: ignored, with a warning) until :data:`REMOVED_IN`.
IGNORED: dict[tuple[str, ...], dict[str, str]] = {
    ("study", "speed-map"): {"--grade": "its verdict is whether the balanced state exists and "
                                        "is stable, which no target grade changes"},
}

#: Former command -> (the command it is now, or None where it still runs itself; what to use,
#: for the warning), accepted until :data:`REMOVED_IN`.
DEPRECATED_COMMANDS: dict[tuple[str, ...], tuple[tuple[str, ...] | None, str]] = {
    ("analyze", "response"): (("response",), "response --speed S [--angles A]"),
    ("analyze", "tolerance"): (("study", "tolerances"), "study tolerances"),
    ("liquid", "simulate"): (None, "response (the steady response against speed), simulate "
                                   "(the run-up through the profile) or study fill-map (the "
                                   "response against fill)"),
}

#: The command groups (their subcommand is part of the command's name).
GROUPS = ("study", "analyze", "liquid")


def rewrite_deprecated(argv: list[str]) -> tuple[list[str], list[str]]:
    """The arguments with a former command (:data:`DEPRECATED_COMMANDS`) replaced by the one it
    is now and every former option name of their command replaced by its name now
    (:data:`DEPRECATED`), and one warning per name replaced.

    Parameters
    ----------
    argv : list of str
        The arguments after the program name.

    Returns
    -------
    (argv, warnings) : tuple of list of str
        The arguments to parse; the lines to print on stderr.
    """
    n = 2 if argv and argv[0] in GROUPS else 1
    command = tuple(argv[:n])
    table = DEPRECATED.get(command, {})
    ignored = IGNORED.get(command, {})
    said: dict[str, str] = {}
    dropped: list[str] = []
    head = list(command)
    if command in DEPRECATED_COMMANDS:
        now, use = DEPRECATED_COMMANDS[command]
        said[" ".join(command)] = use
        head = list(now) if now is not None else head
    if not table and not said and not ignored:
        return list(argv), []
    out = head
    skip = False
    for k, tok in enumerate(argv[n:], n):
        if skip:                              # the value of an ignored option
            skip = False
            continue
        if tok == "--":                       # the rest are values
            out += argv[k:]
            break
        name, eq, value = tok.partition("=")
        if name in ignored:
            dropped.append(f"warning: {' '.join(command)} {name} has no effect ("
                           f"{ignored[name]}); it goes in {REMOVED_IN}")
            skip = not eq
            continue
        if name in table:
            said[f"{' '.join(command)} {name}"] = table[name]
            *extra, name = table[name].split()
            out += extra
            tok = name + eq + value
        out.append(tok)
    return out, [f"warning: {old} is deprecated: use {new} (the old name goes in {REMOVED_IN})"
                 for old, new in said.items()] + list(dict.fromkeys(dropped))
