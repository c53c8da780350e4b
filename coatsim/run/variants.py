"""What every run does with its variants, whatever its input (a curve or a 3-D part): their
names and the reference among them, the files of their programs, the region of interest they
share, and their thickness files on one colour scale."""

from __future__ import annotations

from dataclasses import replace
from pathlib import Path

import numpy as np

from coatsim.core.errors import InputError
from coatsim.path.language import Language
from coatsim.path.program_files import program_paths, program_suffixes
from coatsim.report.metrics import coating_group
from coatsim.report.results import VariantRun
from coatsim.run.scenario import Scenario
from coatsim.spray.coat import remeasured
from coatsim.spray.outputs import write_thickness_glb, write_thickness_ply


def program_files(name: str, writer: Language) -> tuple[str, ...]:
    """The files of variant ``name``'s program in ``writer``'s language, the main first: named
    after the variant, or (a language whose controller loads a program by its file's name) after
    the program, which is then named after the variant."""
    stem = writer.program_name(name) if writer.capabilities.named_by_file else name
    return tuple(p.name for p in program_paths(writer, Path(stem + program_suffixes(writer)[0])))


def on_common_roi(runs: list[VariantRun], target_um: float) -> list[VariantRun]:
    """Every variant's coating measured over the same region of interest: the vertices inside
    every variant's band. Each band follows its own sprayed track, and the tracks differ within
    the tolerance and the corner blends, so a vertex near a band's edge may fall in one and not
    in another; the variants are compared on the same area instead."""
    common = np.logical_and.reduce([r.coating.roi for r in runs])
    if not common.any():
        raise InputError("the variants' regions of interest share no vertex; check coating.band_halfwidth_mm")
    measured = []
    for r in runs:
        coating = remeasured(r.coating, common, target_um)
        measured.append(replace(r, coating=coating, groups={**r.groups, "coating": coating_group(coating.metrics)}))
    return measured


def variant_names(spec: Scenario) -> list[str]:
    """The names of the scenario's variants (built-in variants and program variants)."""
    return [entry if isinstance(entry, str) else entry.name for entry in spec.variants]


def reference_variant(spec: Scenario) -> str:
    """The variant the report compares the others with (and ``--video`` shows): the
    polysegment, else the first."""
    names = variant_names(spec)
    return "polysegment" if "polysegment" in names else names[0]


def write_thickness_files(runs: list[VariantRun], out: Path, standoff_mm: float) -> list[Path]:
    """Every variant's ``V.thickness.ply`` (the properties ``coatsim coat`` writes) and
    ``V.thickness.glb`` (vertex colours, the sprayed tool path), all on the report's one
    colour scale."""
    from coatsim.report.data import aim_paths, thickness_scale

    vmin, vmax = thickness_scale([r.coating.thickness_um for r in runs])
    files = []
    for r in runs:
        ply, glb = out / f"{r.name}.thickness.ply", out / f"{r.name}.thickness.glb"
        write_thickness_ply(ply, r.coating.surface, r.coating.thickness_um, vmin, vmax, r.coating.deposit.exposure_s)
        write_thickness_glb(glb, r.coating.surface, r.coating.thickness_um, vmin, vmax, r.coating.deposit.exposure_s,
                            aim_paths(r.execution.log, standoff_mm))
        files += [ply, glb]
    return files
