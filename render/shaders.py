"""Shader programs loaded by name from shaders/NAME.glsl.

One file holds one program: `#version` on line 1 and the stages behind
`#if defined VERTEX_SHADER` / `#elif defined FRAGMENT_SHADER`. `#include "file.glsl"` pulls in a
shared snippet. The loader injects the stage define and `#line` directives so compile errors
point at the right line, and names the file when a program fails to build.
"""

from __future__ import annotations

import re
import weakref
from importlib import resources

import moderngl

_INCLUDE = re.compile(r'^\s*#include\s+"([^"]+)"\s*$')


class ShaderError(RuntimeError):
    """A shader file that is missing or does not compile."""


def shader_source(name: str) -> str:
    try:
        return resources.files("shaders").joinpath(name).read_text(encoding="utf-8")
    except FileNotFoundError as exc:
        raise ShaderError(f"shader file shaders/{name} not found") from exc


def _expand(name: str, seen: tuple[str, ...] = ()) -> list[str]:
    if name in seen:
        raise ShaderError(f"shaders/{name}: circular #include")
    out: list[str] = []
    for number, line in enumerate(shader_source(name).splitlines(), start=1):
        m = _INCLUDE.match(line)
        if m:
            out.extend(_expand(m.group(1), (*seen, name)))
            out.append(f"#line {number + 1}")
        else:
            out.append(line)
    return out


def snippet_source(name: str) -> str:
    """A shared snippet (shaders/_NAME.glsl) with its includes expanded, for test programs."""
    return "\n".join(_expand(name)) + "\n"


def stage_source(name: str, stage: str, defines: tuple[str, ...] = ()) -> str:
    lines = _expand(name)
    if not lines or not lines[0].startswith("#version"):
        raise ShaderError(f"shaders/{name}: line 1 must be the #version directive")
    flags = [f"#define {flag}" for flag in defines]
    return "\n".join([lines[0], f"#define {stage}", *flags, "#line 2", *lines[1:]]) + "\n"


def wind_defines(enabled: bool, trampled: bool = False) -> tuple[str, ...]:
    """The defines of a program's variant for still air or wind, and for upright or trampled
    grass (shaders/_wind.glsl WIND_ON). A CPU renderer runs both sides of a branch, so a
    uniform switch made still frames pay for the wind's lookups and bends; the variants draw
    the same picture as that switch did."""
    return (("WIND",) if enabled else ()) + (("TRAMPLE",) if trampled else ())


def program_names() -> list[str]:
    """Every program file in shaders/ (snippets for #include start with an underscore)."""
    files = resources.files("shaders").iterdir()
    return sorted(f.name for f in files if f.name.endswith(".glsl") and not f.name.startswith("_"))


# per context object (not its id: a new context at a reused address must not get dead
# programs), then per file and defines; a context that goes away takes its programs with it
_cache: weakref.WeakKeyDictionary[
    moderngl.Context, dict[tuple[str, tuple[str, ...]], moderngl.Program]
] = weakref.WeakKeyDictionary()


def load_program(
    ctx: moderngl.Context, name: str, defines: tuple[str, ...] = ()
) -> moderngl.Program:
    """The compiled program in shaders/NAME with `defines` set, cached per context."""
    programs = _cache.setdefault(ctx, {})
    key = (name, tuple(defines))
    if key in programs:
        return programs[key]
    try:
        program = ctx.program(
            vertex_shader=stage_source(name, "VERTEX_SHADER", key[1]),
            fragment_shader=stage_source(name, "FRAGMENT_SHADER", key[1]),
        )
    except ShaderError:
        raise
    except Exception as exc:
        raise ShaderError(f"shaders/{name} failed to build:\n{exc}") from exc
    programs[key] = program
    return program


def reads(program: moderngl.Program, name: str) -> bool:
    """Whether `program` has the uniform or attribute `name` (the compiler drops those it does
    not use). Program has no __contains__: `name in program` walks every member."""
    return program.get(name, None) is not None
