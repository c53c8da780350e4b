"""Scenario keys of the languages programs are written in: a built-in variant in another
language than the scenario's (``{variant: polysegment, language: abb-rapid}``), and the
scenario's own language (``program: {language: kuka-krl}``)."""

from __future__ import annotations

from typing import Annotated, Any, Literal, Optional

from pydantic import AfterValidator, BaseModel, ConfigDict, Field, model_validator

from coatsim.core.errors import InputError
from coatsim.languages.registry import DEFAULT_LANGUAGE, language
from coatsim.path.build import VARIANTS


class Strict(BaseModel):
    """A scenario mapping: unknown keys, wrong types and infinities refused; immutable."""

    model_config = ConfigDict(extra="forbid", strict=True, frozen=True, allow_inf_nan=False)


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
