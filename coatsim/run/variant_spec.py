"""Scenario keys of the program variants a job compares: a built-in variant by name, one in
another language than the scenario's (``{variant: polysegment, language: abb-rapid}``), a
user's own program run beside them, and the scenario's own language (``program: {language:
kuka-krl}``)."""

from __future__ import annotations

from typing import Annotated, Any, Literal, Optional, Union

from pydantic import AfterValidator, Discriminator, Field, Tag, field_validator, model_validator

from coatsim.core import defaults
from coatsim.core.errors import InputError
from coatsim.languages.registry import DEFAULT_LANGUAGE, language
from coatsim.path.build import VARIANTS
from coatsim.run.spec_fields import Strict


def _language_name(name: str) -> str:
    """The registered language's full name (a part of it only it has is accepted too)."""
    try:
        return language(name).name
    except InputError as exc:
        raise ValueError(str(exc)) from None


VariantName = Literal[VARIANTS]  # type: ignore[valid-type]
VariantLabel = Annotated[str, Field(pattern=r"^[A-Za-z][A-Za-z0-9_.-]*$", max_length=40)]
LanguageName = Annotated[str, AfterValidator(_language_name),
                         Field(description="a robot language: kawasaki-as, abb-rapid, kuka-krl, ... (or a part of the "
                                           "name only it has: rapid)")]


class ProgramSpec(Strict):
    """How the scenario's built-in variants are written: the robot ``language``."""

    language: LanguageName = DEFAULT_LANGUAGE


class BuiltinVariantSpec(Strict):
    """A built-in variant written in its own ``language`` (the scenario's ``program.language``
    when not given), named ``name`` (default ``<variant>-<language>``, e.g.
    ``polysegment-abb-rapid``; the name names its files and its gates), programmed at its own
    ``speed_mm_s`` when given."""

    variant: VariantName
    language: Optional[LanguageName] = None
    name: Optional[VariantLabel] = None  # filled in on loading: always a name after validation
    speed_mm_s: Optional[Annotated[float, Field(gt=0)]] = Field(
        None, description="this variant's programmed speed instead of motion.speed_mm_s (a variant the arm "
                          "cannot run at the scenario's speed, run at one it can)")

    @model_validator(mode="before")
    @classmethod
    def _default_name(cls, value: Any) -> Any:
        if isinstance(value, dict) and "name" not in value and isinstance(value.get("variant"), str):
            tail = _language_name(value["language"]) if isinstance(value.get("language"), str) else "own"
            return {**value, "name": f"{value['variant']}-{tail}" if "language" in value else value["variant"]}
        return value


def variant_label(entry: Any) -> str:
    """The name of a scenario's variant entry as written (a built-in name, or a mapping's name,
    or the default name of a built-in variant in a language)."""
    if isinstance(entry, str):
        return entry
    if "name" in entry:
        return entry["name"]
    spec = BuiltinVariantSpec.model_validate(entry)
    return spec.name


class ProgramVariantSpec(Strict):
    """A program of the user's own run as a variant beside coatsim's: its file(s) relative
    to the scenario (in ``language``, default by their suffix or opening) (data files such as poses after the program), the main program (default:
    the first), the input signals the cell sets (``[1001, -1002]``: 1001 on, 1002 off), and
    the variables no file gives (the controller keeps them): ``{direction: 8, $mode: auto,
    pick: "TRANS(600,0,300,0,180,0)"}`` (a number, a string's text, or an AS expression)."""

    name: VariantLabel
    program: Annotated[list[str], Field(min_length=1, description="AS file, or files loaded together")]
    main: Optional[str] = None
    inputs: list[Annotated[int, Field(ge=-defaults.MAX_SIGNAL, le=defaults.MAX_SIGNAL)]] = Field(
        default_factory=list, description="input signals the cell sets: n on, -n off")
    variables: dict[str, Union[float, str]] = Field(
        default_factory=dict, description="variables the files do not give: NAME: number, text or AS expression")
    language: Optional[LanguageName] = Field(None, description="the language of the files [default: by their "
                                             "suffix, else by their opening]")

    @field_validator("program", mode="before")
    @classmethod
    def _one_file(cls, value: Any) -> Any:
        return [value] if isinstance(value, str) else value

    @field_validator("name")
    @classmethod
    def _own_name(cls, name: str) -> str:
        if name in VARIANTS:
            raise ValueError(f"{name!r} is the name of a built-in variant; give the program another name")
        return name

    @field_validator("inputs")
    @classmethod
    def _signals(cls, inputs: list[int]) -> list[int]:
        if 0 in inputs:
            raise ValueError("signal 0 does not exist; give n (on) or -n (off)")
        return inputs

    @property
    def files(self) -> list[str]:
        return list(self.program)

    @property
    def input_states(self) -> dict[int, bool]:
        return {abs(n): n > 0 for n in self.inputs}


def _variant_kind(value: Any) -> str:
    """The kind of a variant entry, as read (a string, a mapping) or as a model being written out."""
    if isinstance(value, str):
        return "builtin"
    built_in = isinstance(value, BuiltinVariantSpec) or (isinstance(value, dict) and "variant" in value)
    return "language" if built_in else "program"


# A built-in variant by name, one in its own language, or a user's program (a mapping): errors
# speak of the one meant.
VariantEntry = Annotated[Union[Annotated[VariantName, Tag("builtin")], Annotated[ProgramVariantSpec, Tag("program")],
                               Annotated[BuiltinVariantSpec, Tag("language")]], Discriminator(_variant_kind)]
