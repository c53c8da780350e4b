"""Hostile inputs for scripts/hostile.py: what a careless or hostile user can hand each command.

Each case is a command line (``{d}`` is the case's own folder), an optional setup that writes the
files it needs there, an optional check (a result that is silently wrong, a file of the user's
that was changed) and whether it is a *bomb* (a small input asking for huge work).
"""

from __future__ import annotations

import json
import math
import os
import socket
import stat
import subprocess
from dataclasses import dataclass
from pathlib import Path
from typing import Callable, Optional

import numpy as np


@dataclass
class Outcome:
    code: Optional[int]
    stdout: str
    stderr: str
    seconds: float
    timed_out: bool


Setup = Callable[[Path], None]
Check = Callable[[Path, Outcome], Optional[str]]


@dataclass
class Case:
    category: str
    name: str
    argv: list[str]
    setup: Optional[Setup] = None
    check: Optional[Check] = None
    bomb: bool = False
    stdout: Optional[str] = None
    timeout: Optional[float] = None


# --- setups ---------------------------------------------------------------------------------------

def files(**contents: str | bytes | Callable[[Path], None]) -> Setup:
    """Write each file (name -> text, bytes, or a function writing it given its path)."""
    def setup(d: Path) -> None:
        for name, content in contents.items():
            path = d / name.replace("__", ".")
            path.parent.mkdir(parents=True, exist_ok=True)
            if callable(content):
                content(path)
            elif isinstance(content, bytes):
                path.write_bytes(content)
            else:
                path.write_text(content, encoding="utf-8")
    return setup


def both(*setups: Optional[Setup]) -> Setup:
    def setup(d: Path) -> None:
        for s in setups:
            if s is not None:
                s(d)
    return setup


def link(name: str, target: str) -> Setup:
    def setup(d: Path) -> None:
        (d / name).parent.mkdir(parents=True, exist_ok=True)
        os.symlink(target.replace("{d}", str(d)), d / name)
    return setup


def fifo(name: str) -> Setup:
    def setup(d: Path) -> None:
        (d / name).parent.mkdir(parents=True, exist_ok=True)
        os.mkfifo(d / name)
    return setup


def null_device(name: str) -> Setup:
    """A character device like /dev/null, made in the case folder (needs root)."""
    def setup(d: Path) -> None:
        (d / name).parent.mkdir(parents=True, exist_ok=True)
        os.mknod(d / name, 0o666 | stat.S_IFCHR, os.makedev(1, 3))
    return setup


def unix_socket(name: str) -> Setup:
    def setup(d: Path) -> None:
        (d / name).parent.mkdir(parents=True, exist_ok=True)
        s = socket.socket(socket.AF_UNIX)
        s.bind(str(d / name))
        s.close()
    return setup


def folder(name: str) -> Setup:
    return lambda d: (d / name).mkdir(parents=True, exist_ok=True)


def frozen(name: str) -> Setup:
    """A folder nobody can write into, root included (the immutable attribute)."""
    def setup(d: Path) -> None:
        (d / name).mkdir(parents=True, exist_ok=True)
        subprocess.run(["chattr", "+i", str(d / name)], check=True, capture_output=True)
    return setup


VICTIM = "precious user data\n"


def victim(name: str = "victim.txt") -> Setup:
    return files(**{name: VICTIM})


# --- checks ---------------------------------------------------------------------------------------

def victim_intact(name: str = "victim.txt") -> Check:
    def check(d: Path, o: Outcome) -> Optional[str]:
        path = d / name
        if not path.is_file() or path.is_symlink() and not path.resolve().is_file():
            return f"data loss: {name} is gone"
        if path.read_text(errors="replace") != VICTIM:
            return f"data loss: {name} was overwritten"
        return None
    return check


def still(name: str, kind: str) -> Check:
    tests = {"fifo": stat.S_ISFIFO, "chr": stat.S_ISCHR, "sock": stat.S_ISSOCK, "dir": stat.S_ISDIR,
             "link": stat.S_ISLNK}

    def check(d: Path, o: Outcome) -> Optional[str]:
        try:
            mode = os.lstat(d / name).st_mode
        except FileNotFoundError:
            return f"data loss: the {kind} {name} is gone"
        return None if tests[kind](mode) else f"data loss: the {kind} {name} was replaced by another file"
    return check


def checks(*cs: Check) -> Check:
    def check(d: Path, o: Outcome) -> Optional[str]:
        for c in cs:
            problem = c(d, o)
            if problem:
                return problem
        return None
    return check


def refused(d: Path, o: Outcome) -> Optional[str]:
    """Must not be accepted (exit 0 or 1 with outputs would be a silent misreading)."""
    return f"wrong: accepted (exit {o.code}); expected a refusal" if o.code in (0, 1) else None


def _seg_length(seg: dict) -> float:
    if seg["kind"] == "line":
        return float(np.linalg.norm(np.subtract(seg["end"], seg["start"])))
    return abs(float(seg["sweep"])) * float(seg["radius"])


def length_is(expected: float, closed: Optional[bool] = None, name: str = "out.json", rtol: float = 0.01) -> Check:
    """Accepted: the polysegment written to ``name`` has this length (and closure); refused: fine."""
    def check(d: Path, o: Outcome) -> Optional[str]:
        if o.code != 0:
            return None
        doc = json.loads((d / name).read_text())
        docs = doc.get("contours", [doc])
        length = sum(_seg_length(s) for c in docs for s in c["segments"])
        if abs(length - expected) > rtol * expected:
            return f"wrong: read as a curve {length:.6g} mm long, expected {expected:g} mm"
        if closed is not None and docs[0]["closed"] != closed:
            return f"wrong: read as {'closed' if docs[0]['closed'] else 'open'}, the curve is {'closed' if closed else 'open'}"
        return None
    return check


def format_is(fmt: str, name: str = "out.json") -> Check:
    def check(d: Path, o: Outcome) -> Optional[str]:
        if o.code != 0:
            return None
        got = json.loads((d / name).read_text()).get("format")
        return None if got == fmt else f"wrong: wrote {got}, expected {fmt}"
    return check


# --- inputs ---------------------------------------------------------------------------------------

def rect_points(w: float = 100.0, h: float = 50.0, per_side: int = 50) -> np.ndarray:
    corners = np.array([[0, 0], [w, 0], [w, h], [0, h], [0, 0]], float)
    pts = [c0 + (c1 - c0) * t for c0, c1 in zip(corners[:-1], corners[1:])
           for t in np.linspace(0, 1, per_side, endpoint=False)]
    return np.vstack([pts, corners[:1]])


RECT = rect_points()
RECT_LENGTH = 300.0


def csv_text(points: np.ndarray, sep: str = ",", fmt: str = "{:.6f}", header: str = "") -> str:
    rows = [sep.join(fmt.format(v) for v in p) for p in points]
    return header + "\n".join(rows) + "\n"


def helix(n: int = 400, turns: float = 2.0) -> np.ndarray:
    t = np.linspace(0, 2 * math.pi * turns, n)
    return np.column_stack([50 * np.cos(t), 50 * np.sin(t), 10 * t])


def npy(array: np.ndarray) -> Callable[[Path], None]:
    return lambda path: np.save(path, array, allow_pickle=True)


def npy_header(shape: tuple, descr: str = "<f8", body: bytes = b"") -> bytes:
    header = repr({"descr": descr, "fortran_order": False, "shape": shape}).encode()
    header += b" " * (63 - (len(header) + 10) % 64) + b"\n"
    return b"\x93NUMPY\x01\x00" + len(header).to_bytes(2, "little") + header + body


def random_points(n: int, dims: int = 2, seed: int = 1) -> np.ndarray:
    return np.random.default_rng(seed).uniform(0, 100, (n, dims))


AS_OK = """.PROGRAM t()
  SPEED 200 MM/S ALWAYS
  LMOVE TRANS(600,0,300,0,180,0)
  SIGNAL 1
  LMOVE TRANS(650,0,300,0,180,0)
  SIGNAL -1
.END
"""


def as_program(body: str, name: str = "t") -> str:
    return f".PROGRAM {name}()\n{body}\n.END\n"


def svg(body: str, extra: str = "") -> str:
    size = "" if extra else ' width="200mm" height="200mm" viewBox="0 0 200 200"'
    return ('<svg xmlns="http://www.w3.org/2000/svg" xmlns:xlink="http://www.w3.org/1999/xlink"'
            f'{size}{extra}>{body}</svg>\n')


SVG_RECT = '<rect x="10" y="10" width="100" height="50" fill="none" stroke="black"/>'


def use_bomb(levels: int = 10, fan: int = 10) -> str:
    defs = ['<path id="a0" d="M0 0 L1 0"/>']
    for k in range(1, levels):
        defs.append(f'<g id="a{k}">' + f'<use xlink:href="#a{k - 1}"/>' * fan + "</g>")
    return svg("<defs>" + "".join(defs) + f'</defs><use xlink:href="#a{levels - 1}"/>')


# DXF: written by ezdxf with placeholder numbers, then the placeholders replaced by hostile text
PLACEHOLDER = "777.125"
RATIO_PLACEHOLDER = 0.625125


def dxf(build: Callable, replace: Optional[dict[str, str]] = None) -> Callable[[Path], None]:
    def write(path: Path) -> None:
        import ezdxf

        doc = ezdxf.new("R2010")
        doc.header["$INSUNITS"] = 4
        build(doc, doc.modelspace())
        doc.saveas(path)
        if replace:
            text = path.read_text()
            for old, new in replace.items():
                text = text.replace(old, new)
            path.write_text(text)
    return write


def dxf_line(x: float | str = PLACEHOLDER) -> Callable[[Path], None]:
    return dxf(lambda doc, msp: (msp.add_line((0, 0), (float(PLACEHOLDER), 50)), msp.add_line((0, 0), (100, 0))),
               {PLACEHOLDER: str(x)})


def dxf_rect(doc, msp) -> None:
    msp.add_lwpolyline([(0, 0), (100, 0), (100, 50), (0, 50)], close=True)


def dxf_nested_blocks(levels: int, fan: int, mcount: tuple[int, int] = (1, 1)) -> Callable[[Path], None]:
    def build(doc, msp) -> None:
        b0 = doc.blocks.new("B0")
        b0.add_line((0, 0), (1, 0))
        for k in range(1, levels):
            b = doc.blocks.new(f"B{k}")
            for j in range(fan):
                ins = b.add_blockref(f"B{k - 1}", (2.0 * j, 0))
                if mcount != (1, 1):
                    ins.grid(size=mcount, spacing=(1, 1))
        ins = msp.add_blockref(f"B{levels - 1}", (0, 0))
        if mcount != (1, 1):
            ins.grid(size=mcount, spacing=(1, 1))
    return dxf(build)


def million_lines_dxf(n: int = 1_000_000) -> Callable[[Path], None]:
    def write(path: Path) -> None:
        head = "0\nSECTION\n2\nHEADER\n9\n$INSUNITS\n70\n4\n0\nENDSEC\n0\nSECTION\n2\nENTITIES\n"
        body = "".join(f"0\nLINE\n8\n0\n10\n{i * 0.001:.3f}\n20\n0.0\n30\n0.0\n11\n{i * 0.001 + 0.001:.3f}\n21\n0.0\n31\n0.0\n"
                       for i in range(n))
        path.write_text(head + body + "0\nENDSEC\n0\nEOF\n")
    return write


def lwpolyline_dxf(n: int = 1_000_000) -> Callable[[Path], None]:
    def write(path: Path) -> None:
        head = "0\nSECTION\n2\nENTITIES\n0\nLWPOLYLINE\n8\n0\n90\n%d\n70\n0\n" % n
        body = "".join(f"10\n{i * 0.001:.3f}\n20\n{(i % 2) * 0.001:.3f}\n" for i in range(n))
        path.write_text(head + body + "0\nENDSEC\n0\nEOF\n")
    return write


def trajectory_csv(rows: int = 50, bad: Optional[dict[int, str]] = None) -> str:
    cols = "t_s,x_mm,y_mm,z_mm,ax,ay,az,speed_mm_s,spray,progress_mm,path_error_mm,q1,q2,q3,q4,q5,q6"
    lines = [cols]
    for i in range(rows):
        x = i * 2.0
        lines.append(f"{i * 0.01:.4f},{x:.4f},0,100,0,0,-1,200,1,{x:.4f},0,0,0,0,0,0,0")
    for i, text in (bad or {}).items():
        lines[i] = text
    return "\n".join(lines) + "\n"


SCENARIO = """name: hostile
curve: {curve}
segmentation: {{tolerance_mm: 0.1}}
workpiece: {workpiece}
gun: {{footprint: "{footprint}", target_thickness_um: 16.0}}
motion: {{speed_mm_s: {speed}, accuracy_mm: 0.5, lead_in_mm: 10.0, lead_out_mm: 10.0}}
coating: {{spacing_mm: 2.5}}
variants: [polysegment]
"""


def scenario(curve: str = "{builtin: ellipse, params: {a: 40, b: 20}}", workpiece: str = "{kind: plate, size_mm: [130.0, 90.0]}",
             footprint: str = "gaussian:sigma=5", speed: str = "200.0", extra: str = "") -> str:
    return SCENARIO.format(curve=curve, workpiece=workpiece, footprint=footprint, speed=speed) + extra


def sweep_file(grid: str, base: str = "base.yaml", extra: str = "") -> str:
    return f"base: {base}\nfast: true\ngrid:\n{grid}\n{extra}"


BINARY_STL_HUGE = b"\0" * 80 + (2**31).to_bytes(4, "little") + b"\0" * 100


# --- the cases ------------------------------------------------------------------------------------

def curve_cases() -> list[Case]:
    c: list[Case] = []
    seg = lambda name, *args, **kw: Case("curve", name, ["segment", *args], **kw)  # noqa: E731
    rect_csv = csv_text(RECT)
    texts = {
        "empty": "", "header-only": "x,y\n", "one-point": "1,2\n", "equal-points": "1,2\n1,2\n1,2\n",
        "nan": "0,0\n1,nan\n2,0\n", "inf": "0,0\n1,inf\n2,0\n", "1e308": "0,0\n1e308,1\n2,0\n",
        "neg-1e308": "0,0\n-1e308,1\n2,0\n", "1e400": "0,0\n1e400,1\n2,0\n", "tiny": "0,0\n1e-300,1e-300\n2e-300,0\n",
        "two-points": "0,0\n10,0\n", "four-columns": "0,0,0,0\n1,1,1,1\n2,0,0,0\n",
        "five-columns": "0,0,0,0,0\n1,1,1,1,1\n2,0,0,0,0\n3,1,0,0,0\n", "mixed-columns": "0,0\n1,1,1\n2,0\n",
        "typo-field": "0,0\n1e5x,1\n2,0\n", "hex": "0,0\n0x10,1\n2,0\n", "dotted": "0,0\n1.2.3,1\n2,0\n",
        "nan-word": "0,0\nNaN,1\n2,0\n", "infinity-word": "0,0\nInfinity,1\n2,0\n",
        "trailing-comma": "0,0,\n10,0,\n10,10,\n", "leading-comma": ",0,0\n,10,0\n,10,10\n",
        "quoted": '"x","y"\n"0","0"\n"10","0"\n"10","10"\n', "cr-only": "0,0\r10,0\r10,10\r",
        "crlf": "0,0\r\n10,0\r\n10,10\r\n", "bom-header": "\ufeffx,y\n0,0\n10,0\n10,10\n",
        "only-comments": "# a\n# b\n", "blank-lines": "\n\n\n", "x-header-negative": "x,\u22125\n0,0\n10,0\n",
        "ansi-escape": "0,0\n\x1b[31m1\x1b[0m,1\n2,0\n", "long-field": "0,0\n" + "9" * 100000 + ",1\n2,0\n",
        "many-fields": ",".join(["1"] * 200000) + "\n", "underscore": "0,0\n1_000,0\n1_000,1_000\n",
        "nul-bytes": "0,0\n1\x00,1\n2,0\n", "semicolon-decimal": csv_text(RECT, ";", "{:.3f}").replace(".", ","),
        "plus-signs": "+0,+0\n+10,+0\n+10,+10\n",
    }
    for name, text in texts.items():
        c.append(seg(name, "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json", setup=files(c__csv=text)))
    comma = lambda sep: "\n".join(sep.join(f"{v:.3f}".replace(".", ",") for v in p) for p in RECT) + "\n"  # noqa: E731
    for name, sep in (("decimal-comma-tab", "\t"), ("decimal-comma-space", " "), ("decimal-comma-2spaces", "  ")):
        c.append(seg(name, "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json", setup=files(c__csv=comma(sep)),
                     check=length_is(RECT_LENGTH, True)))
    shifted = RECT - [50.0, 25.0]
    for name, minus in (("unicode-minus", "\u2212"), ("en-dash-minus", "\u2013"), ("fullwidth-minus", "\uff0d"),
                        ("small-minus", "\ufe63")):
        text = csv_text(shifted).replace("-", minus)
        c.append(seg(name, "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json", setup=files(c__csv=text),
                     check=length_is(RECT_LENGTH, True)))
        c.append(seg(name + "-tab", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json",
                     setup=files(c__csv=csv_text(shifted, "\t").replace("-", minus)), check=length_is(RECT_LENGTH, True)))
    big = RECT * 100
    thousands = "\n".join(f"{p[0]:,.1f};{p[1]:,.1f}".replace(",", "\u00a0").replace(".", ",") for p in big) + "\n"
    c.append(seg("nbsp-thousands", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json", setup=files(c__csv=thousands),
                 check=length_is(RECT_LENGTH * 100, True)))
    c.append(seg("fullwidth-digits", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json",
                 setup=files(c__csv=rect_csv.translate({ord(str(k)): 0xFF10 + k for k in range(10)})),
                 check=length_is(RECT_LENGTH, True)))
    c.append(seg("arabic-digits", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json",
                 setup=files(c__csv=rect_csv.translate({ord(str(k)): 0x0660 + k for k in range(10)})),
                 check=length_is(RECT_LENGTH, True)))
    c.append(seg("superscript", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json",
                 setup=files(c__csv="0,0\n10,0\n10,1\u00b2\n0,10\n")))
    c.append(seg("utf16", "{d}/c.csv", "--tol", "0.1", setup=files(c__csv=rect_csv.encode("utf-16"))))
    c.append(seg("latin1", "{d}/c.csv", "--tol", "0.1", setup=files(c__csv=("x\xb5,y\n" + rect_csv).encode("latin-1"))))
    c.append(seg("garbage", "{d}/c.csv", "--tol", "0.1", setup=files(c__csv=np.random.default_rng(0).bytes(4096))))
    c.append(seg("header-units", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json",
                 setup=files(c__csv="x (mm),y (mm)\n" + rect_csv), check=length_is(RECT_LENGTH, True)))
    c.append(seg("header-minus-row", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json",
                 setup=files(c__csv=csv_text(shifted).replace("-", "\u2212", 2)), check=length_is(RECT_LENGTH, True)))
    c.append(seg("tab-separated", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json",
                 setup=files(c__csv=csv_text(RECT, "\t")), check=length_is(RECT_LENGTH, True)))
    c.append(seg("xyz-helix", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json", setup=files(c__csv=csv_text(helix())),
                 check=format_is("coatsim.polysegment/2")))
    c.append(Case("curve", "xyz-program", ["program", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/p.as"],
                  setup=files(c__csv=csv_text(helix())), check=refused))
    c.append(Case("curve", "npy3-program", ["program", "{d}/c.npy", "--tol", "0.1", "-o", "{d}/p.as"],
                  setup=files(c__npy=npy(helix())), check=refused))
    c.append(seg("npy3-helix", "{d}/c.npy", "--tol", "0.1", "-o", "{d}/out.json", setup=files(c__npy=npy(helix())),
                 check=format_is("coatsim.polysegment/2")))
    arrays = {
        "npy-5col": np.zeros((10, 5)), "npy-1d": np.arange(10.0), "npy-3d": np.zeros((3, 3, 2)),
        "npy-0d": np.array(1.0), "npy-complex": RECT.astype(complex), "npy-object": np.array([[1, "a"], [2, "b"]], object),
        "npy-bool": RECT > 10, "npy-nan": np.array([[0, 0], [np.nan, 1], [2, 0]]),
        "npy-bigendian": RECT.astype(">f8"), "npy-fortran": np.asfortranarray(RECT), "npy-float16": RECT.astype(np.float16),
        "npy-int8": RECT.astype(np.int8), "npy-datetime": np.zeros((3, 2), "datetime64[s]"),
        "npy-structured": np.zeros(3, dtype=[("x", "f8"), ("y", "f8")]), "npy-empty": np.zeros((0, 2)),
        "npy-huge-values": np.array([[0, 0], [1e300, 0], [0, 1]]),
    }
    for name, array in arrays.items():
        c.append(seg(name, "{d}/c.npy", "--tol", "0.1", setup=files(c__npy=npy(array))))
    c.append(seg("npy-truncated", "{d}/c.npy", "--tol", "0.1", setup=files(c__npy=npy_header((1000, 2), body=b"\0" * 160))))
    c.append(seg("npy-shape-1e12", "{d}/c.npy", "--tol", "0.1", setup=files(c__npy=npy_header((10**12, 2))), bomb=True))
    c.append(seg("npy-bad-header", "{d}/c.npy", "--tol", "0.1", setup=files(c__npy=b"\x93NUMPY\x01\x00\xff\xffgarbage")))
    c.append(seg("npy-is-csv", "{d}/c.npy", "--tol", "0.1", setup=files(c__npy=rect_csv)))
    c.append(seg("csv-is-npy", "{d}/c.csv", "--tol", "0.1", setup=files(c__csv=npy(RECT))))
    # file system objects
    c.append(seg("folder", "{d}/c.csv", "--tol", "0.1", setup=folder("c.csv")))
    c.append(seg("fifo", "{d}/c.csv", "--tol", "0.1", setup=fifo("c.csv"), bomb=True))
    c.append(seg("fifo-npy", "{d}/c.npy", "--tol", "0.1", setup=fifo("c.npy"), bomb=True))
    c.append(seg("dev-zero", "{d}/c.csv", "--tol", "0.1", setup=link("c.csv", "/dev/zero"), bomb=True))
    c.append(seg("dev-urandom", "{d}/c.csv", "--tol", "0.1", setup=link("c.csv", "/dev/urandom"), bomb=True))
    c.append(seg("dev-zero-npy", "{d}/c.npy", "--tol", "0.1", setup=link("c.npy", "/dev/zero"), bomb=True))
    c.append(seg("dev-null", "{d}/c.csv", "--tol", "0.1", setup=link("c.csv", "/dev/null")))
    c.append(seg("proc-file", "{d}/c.csv", "--tol", "0.1", setup=link("c.csv", "/proc/self/maps")))
    c.append(seg("proc-kcore", "{d}/c.csv", "--tol", "0.1", setup=link("c.csv", "/proc/kcore"), bomb=True))
    c.append(seg("socket", "{d}/c.csv", "--tol", "0.1", setup=unix_socket("c.csv")))
    c.append(seg("symlink-loop", "{d}/c.csv", "--tol", "0.1", setup=both(link("c.csv", "{d}/b.csv"), link("b.csv", "{d}/c.csv"))))
    c.append(seg("dangling-link", "{d}/c.csv", "--tol", "0.1", setup=link("c.csv", "{d}/nowhere.csv")))
    c.append(seg("missing", "{d}/nothing.csv", "--tol", "0.1"))
    c.append(seg("newline-in-name", "{d}/a\nb.csv", "--tol", "0.1"))
    c.append(seg("escape-in-name", "{d}/a\x1b[2Jb.csv", "--tol", "0.1"))
    c.append(seg("long-name", "{d}/" + "a" * 5000 + ".csv", "--tol", "0.1"))
    c.append(seg("dash", "-", "--tol", "0.1"))
    c.append(seg("empty-arg", "", "--tol", "0.1"))
    c.append(seg("no-suffix-folder", "{d}", "--tol", "0.1"))
    # size and work
    c.append(seg("comments-60mb", "{d}/c.csv", "--tol", "0.1",
                 setup=files(c__csv=lambda p: p.write_bytes(b"#" * 63 + b"\n" + b"#\n" * 30_000_000)), bomb=True))
    c.append(seg("points-3m", "{d}/c.csv", "--tol", "0.1",
                 setup=files(c__csv=lambda p: p.write_text("\n".join(f"{i},{i % 7}" for i in range(3_000_000)))), bomb=True))
    c.append(seg("duplicates-3m", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json",
                 setup=files(c__csv=lambda p: p.write_text("0,0\n" * 3_000_000 + "10,0\n10,10\n")), bomb=True))
    c.append(seg("one-line-30mb", "{d}/c.csv", "--tol", "0.1",
                 setup=files(c__csv=lambda p: p.write_text("1," * 15_000_000 + "1\n")), bomb=True))
    for n in (3000, 10000):
        c.append(seg(f"random-{n}", "{d}/c.csv", "--tol", "0.1", setup=files(c__csv=csv_text(random_points(n))), bomb=True,
                     timeout=120))
    c.append(seg("random-3000-3d", "{d}/c.csv", "--tol", "0.1", setup=files(c__csv=csv_text(random_points(3000, 3))),
                 bomb=True, timeout=120))
    t = np.arange(3000.0)
    zigzag = np.column_stack([t * 0.1, 5 * (t % 2)])
    c.append(seg("zigzag-3000", "{d}/c.csv", "--tol", "0.1", setup=files(c__csv=csv_text(zigzag)), bomb=True, timeout=120))
    alias = np.column_stack([t * 0.1, 5 * np.sin(t * 2.9)])
    c.append(seg("aliased-sine", "{d}/c.csv", "--tol", "0.01", setup=files(c__csv=csv_text(alias)), bomb=True, timeout=120))
    return c


def builtin_cases() -> list[Case]:
    specs = {
        "paper-spiral-turns-1e6": "paper-spiral:turns=1e6", "sine-wavelength-1e-6": "sine:wavelength=1e-6",
        "points-1e9": "ellipse:points=1e9", "points-negative": "ellipse:points=-5", "points-nan": "ellipse:points=nan",
        "points-2.5": "ellipse:points=2.5", "a-1e308": "ellipse:a=1e308", "a-0": "ellipse:a=0", "a-nan": "ellipse:a=nan",
        "a-inf": "ellipse:a=inf", "a-tiny": "ellipse:a=1e-300", "a-negative": "ellipse:a=-5",
        "sides-1e9": "polygon:sides=1e9", "sides-2": "polygon:sides=2", "passes-1e9": "raster:passes=1e9",
        "pitch-1e-300": "raster:pitch=1e-300", "naca-code": "naca:code=99999", "naca-code-text": "naca:code=abcd",
        "unknown": "nosuch", "empty": "", "no-value": "ellipse:a", "duplicate-key": "ellipse:a=1,a=2",
        "sine-amplitude-1e9": "sine:amplitude=1e9", "spiral-turns-1e3": "paper-spiral:turns=1e3",
        "spiral-turns-0": "paper-spiral:turns=0", "spiral-width-nan": "paper-spiral:width=nan",
        "rounded-radius-0": "rounded-rectangle:radius=0", "rounded-radius-huge": "rounded-rectangle:radius=1e6",
        "epitrochoid-extreme": "epitrochoid:points=100000", "clothoid-huge": "clothoid:points=2000000",
        "unknown-key": "ellipse:zz=1", "unicode-key": "ellipse:\u00e4=1", "semicolon": "ellipse;a=1",
        "sine-cycles-1e6": "sine:cycles=1e6", "cam-lift-1e9": "cam:lift=1e9",
    }
    bombs = {"paper-spiral-turns-1e6", "sine-wavelength-1e-6", "points-1e9", "sides-1e9", "passes-1e9",
             "spiral-turns-1e3", "clothoid-huge", "sine-cycles-1e6", "pitch-1e-300"}
    return [Case("builtin", name, ["segment", f"builtin:{spec}", "--tol", "0.1"], bomb=name in bombs, timeout=120)
            for name, spec in specs.items()]


def option_cases() -> list[Case]:
    c: list[Case] = []
    curve = files(c__csv=csv_text(RECT))
    for value in ("0", "-1", "nan", "inf", "1e-300", "1e300", "1e-12", "abc", "1e400"):
        c.append(Case("options", f"segment-tol-{value}", ["segment", "builtin:ellipse", "--tol", value], bomb=value in ("1e-300", "1e-12")))
    for value in ("1e-200", "1e308", "0", "-1", "nan", "inf", "1e-300"):
        c.append(Case("options", f"segment-speed-{value}", ["segment", "builtin:ellipse", "--tol", "0.1", "--speed", value],
                      bomb=value in ("1e-200", "1e-300")))
        c.append(Case("options", f"program-speed-{value}", ["program", "builtin:ellipse", "--tol", "0.1", "--speed", value,
                                                           "-o", "{d}/p.as"], bomb=value in ("1e-200", "1e-300")))
        c.append(Case("options", f"segment-file-speed-{value}", ["segment", "{d}/c.csv", "--tol", "0.1", "--speed", value],
                      setup=curve))
    for flag, values in {"--corner-deg": ("0", "180", "nan", "-5", "1e308"), "--min-segment": ("nan", "1e308", "-1", "1e-300"),
                         "--tool-accel": ("1e-300", "1e308", "nan", "0")}.items():
        for value in values:
            extra = ["--speed", "500"] if flag == "--tool-accel" else []
            c.append(Case("options", f"segment{flag}-{value}", ["segment", "builtin:ellipse", "--tol", "0.1", flag, value, *extra]))
    for value in ("0", "nan", "-1", "1e-300", "1e300"):
        c.append(Case("options", f"theta-tol-{value}", ["segment", "builtin:ellipse", "--tol", "0.1", "--method", "paper",
                                                        "--theta-tol", value], bomb=value == "1e-300"))
    c.append(Case("options", "paper-tol-1e-9", ["segment", "builtin:ellipse", "--tol", "1e-9", "--method", "paper"], bomb=True))
    c.append(Case("options", "method-unknown", ["segment", "builtin:ellipse", "--tol", "0.1", "--method", "magic"]))
    c.append(Case("options", "closed-maybe", ["segment", "builtin:ellipse", "--tol", "0.1", "--closed", "maybe"]))
    program_opts = {"--accuracy": ("1e308", "-1", "nan", "0"), "--frame": ("nan,0,0,0,0,0", "1e308,0,0,0,0,0", "1,2", "a,b,c,d,e,f", ""),
                    "--standoff": ("1e308", "-1", "0", "nan", "1e-300"), "--lead-in": ("1e308", "nan", "-1"),
                    "--lead-out": ("1e308",), "--approach": ("1e308", "-1"), "--roll-deg": ("1e308", "nan"),
                    "--gun": ("-1", "0", "99999999", "1e3"), "--name": ("a b", "x" * 100, "\u00e4\u00f6", "..", "1abc", "-x"),
                    "--order": ("garbage",), "--variant": ("garbage",)}
    for flag, values in program_opts.items():
        for value in values:
            c.append(Case("options", f"program{flag}-{value[:12]}", ["program", "builtin:ellipse", "--tol", "0.1", flag, value,
                                                                    "-o", "{d}/p.as"]))
    c.append(Case("options", "unknown-command", ["frobnicate"]))
    c.append(Case("options", "unknown-option", ["segment", "builtin:ellipse", "--frobnicate"]))
    c.append(Case("options", "huge-argument", ["segment", "x" * 100_000 + ".csv", "--tol", "0.1"]))
    c.append(Case("options", "execute-step-1e-300", ["execute", "{d}/t.as", "--step-mm", "1e-300", "-o", "{d}/out"],
                  setup=files(t__as=AS_OK), bomb=True))
    c.append(Case("options", "execute-step-nan", ["execute", "{d}/t.as", "--step-mm", "nan", "-o", "{d}/out"], setup=files(t__as=AS_OK)))
    c.append(Case("options", "execute-gun-1e9", ["execute", "{d}/t.as", "--gun", "1000000000", "-o", "{d}/out"], setup=files(t__as=AS_OK)))
    c.append(Case("options", "execute-set-garbage", ["execute", "{d}/t.as", "--set", "=", "-o", "{d}/out"], setup=files(t__as=AS_OK)))
    c.append(Case("options", "execute-inputs-garbage", ["execute", "{d}/t.as", "--inputs", "1e9,x", "-o", "{d}/out"], setup=files(t__as=AS_OK)))
    c.append(Case("options", "convert-lines-huge", ["convert", "{d}/t.as", "--tol", "0.1", "--lines", "1-99999999999999999999"],
                  setup=files(t__as=AS_OK)))
    c.append(Case("options", "convert-tol-nan", ["convert", "{d}/t.as", "--tol", "nan"], setup=files(t__as=AS_OK)))
    c.append(Case("options", "convert-tol-1e-300", ["convert", "{d}/t.as", "--tol", "1e-300"], setup=files(t__as=AS_OK)))
    c.append(Case("options", "sweep-workers-0", ["sweep", "{d}/s.yaml", "--workers", "0", "-o", "{d}/out"]))
    c.append(Case("options", "sweep-workers-1e5", ["sweep", "{d}/s.yaml", "--workers", "100000", "-o", "{d}/out"],
                  setup=files(s__yaml=sweep_file("  motion.speed_mm_s: [100]"), base__yaml=scenario()), bomb=True))
    return c


def output_cases() -> list[Case]:
    c: list[Case] = []
    seg = ["segment", "builtin:ellipse", "--tol", "0.1"]
    prog = ["program", "builtin:ellipse", "--tol", "0.1"]
    for label, argv in (("segment", seg), ("program", prog)):
        c.append(Case("outputs", f"{label}-onto-device", [*argv, "-o", "{d}/dev"], setup=null_device("dev"), check=still("dev", "chr")))
        c.append(Case("outputs", f"{label}-onto-fifo", [*argv, "-o", "{d}/f"], setup=fifo("f"), check=still("f", "fifo")))
        c.append(Case("outputs", f"{label}-onto-socket", [*argv, "-o", "{d}/s"], setup=unix_socket("s"), check=still("s", "sock")))
        c.append(Case("outputs", f"{label}-onto-folder", [*argv, "-o", "{d}/dir"], setup=folder("dir"), check=still("dir", "dir")))
        c.append(Case("outputs", f"{label}-onto-symlink", [*argv, "-o", "{d}/l"], setup=both(victim(), link("l", "{d}/victim.txt")),
                      check=victim_intact()))
        c.append(Case("outputs", f"{label}-into-frozen", [*argv, "-o", "{d}/ro/out"], setup=frozen("ro")))
        c.append(Case("outputs", f"{label}-under-file", [*argv, "-o", "{d}/victim.txt/out"], setup=victim(), check=victim_intact()))
        c.append(Case("outputs", f"{label}-long-name", [*argv, "-o", "{d}/" + "o" * 300]))
        c.append(Case("outputs", f"{label}-dev-full", [*argv], stdout="/dev/full"))
        c.append(Case("outputs", f"{label}-onto-symlink-loop", [*argv, "-o", "{d}/l"], setup=both(link("l", "{d}/m"), link("m", "{d}/l"))))
    c.append(Case("outputs", "plot-onto-device", [*seg, "--plot", "{d}/dev"], setup=null_device("dev"), check=still("dev", "chr")))
    c.append(Case("outputs", "check-program-dev-full", ["check-program", "{d}/t.as"], setup=files(t__as=AS_OK), stdout="/dev/full"))
    c.append(Case("outputs", "convert-dev-full", ["convert", "{d}/t.as", "--tol", "0.1"], setup=files(t__as=AS_OK), stdout="/dev/full"))
    c.append(Case("outputs", "schema-dev-full", ["schema"], stdout="/dev/full"))
    c.append(Case("outputs", "help-dev-full", ["--help"], stdout="/dev/full"))
    c.append(Case("outputs", "version-dev-full", ["--version"], stdout="/dev/full"))
    c.append(Case("outputs", "convert-onto-device", ["convert", "{d}/t.as", "--tol", "0.1", "-o", "{d}/dev"],
                  setup=both(files(t__as=AS_OK), null_device("dev")), check=still("dev", "chr")))
    # output folders: coat is the quickest command that writes one
    traj = files(t__csv=trajectory_csv())
    coat = ["coat", "{d}/t.csv", "--surface", "plate:100x60@50,0,0", "-o", "{d}/out"]
    folders = {
        "lock-symlink": both(victim(), link("out/.coatsim.lock", "{d}/victim.txt")),
        "lock-folder": folder("out/.coatsim.lock"), "lock-fifo": fifo("out/.coatsim.lock"),
        "lock-device": null_device("out/.coatsim.lock"), "lock-dev-zero": link("out/.coatsim.lock", "/dev/zero"),
        "lock-socket": unix_socket("out/.coatsim.lock"), "lock-loop": link("out/.coatsim.lock", "{d}/out/.coatsim.lock"),
        "manifest-symlink": both(victim(), link("out/.coatsim-outputs.json", "{d}/victim.txt")),
        "manifest-dev-zero": link("out/.coatsim-outputs.json", "/dev/zero"), "manifest-fifo": fifo("out/.coatsim-outputs.json"),
        "manifest-device": null_device("out/.coatsim-outputs.json"), "manifest-folder": folder("out/.coatsim-outputs.json"),
        "manifest-garbage": files(**{"out/.coatsim-outputs__json": "{" * 100000}),
        "manifest-huge": files(**{"out/.coatsim-outputs__json": lambda p: p.write_text(" " * 200_000_000 + "{}")}),
        "output-symlink": both(victim(), link("out/coating.json", "{d}/victim.txt")),
        "output-device": null_device("out/coating.json"), "output-fifo": fifo("out/coating.json"),
        "output-folder": folder("out/coating.json"), "frozen-folder": frozen("out"),
        "outdir-device": null_device("out"), "outdir-fifo": fifo("out"), "outdir-file": victim("out"),
        "outdir-symlink-loop": link("out", "{d}/out"),
    }
    special = {"lock-symlink": checks(victim_intact(), still("out/.coatsim.lock", "link")),
               "manifest-symlink": checks(victim_intact(), still("out/.coatsim-outputs.json", "link")),
               "output-symlink": victim_intact(), "output-device": still("out/coating.json", "chr"),
               "output-fifo": still("out/coating.json", "fifo"), "outdir-device": still("out", "chr"),
               "outdir-fifo": still("out", "fifo"), "outdir-file": victim_intact("out"),
               "lock-device": still("out/.coatsim.lock", "chr"), "lock-fifo": still("out/.coatsim.lock", "fifo"),
               "manifest-device": still("out/.coatsim-outputs.json", "chr"), "manifest-fifo": still("out/.coatsim-outputs.json", "fifo")}
    for name, setup in folders.items():
        bomb = name in ("manifest-dev-zero", "manifest-fifo", "lock-dev-zero", "lock-fifo", "manifest-huge")
        c.append(Case("outputs", f"coat-{name}", coat, setup=both(traj, setup), check=special.get(name), bomb=bomb))
        c.append(Case("outputs", f"coat-{name}-force", [*coat, "--force"], setup=both(traj, setup), check=special.get(name), bomb=bomb))
    for name in ("lock-symlink", "lock-folder", "lock-fifo", "manifest-symlink", "manifest-dev-zero", "frozen-folder"):
        argv = ["execute", "{d}/t.as", "-o", "{d}/out"]
        c.append(Case("outputs", f"execute-{name}", argv, setup=both(files(t__as=AS_OK), folders[name]), check=special.get(name),
                      bomb=name in ("manifest-dev-zero", "lock-fifo")))
        argv = ["run", "{d}/s.yaml", "--fast", "-o", "{d}/out"]
        c.append(Case("outputs", f"run-{name}", argv, setup=both(files(s__yaml=scenario()), folders[name]), check=special.get(name),
                      bomb=name in ("manifest-dev-zero", "lock-fifo"), timeout=180))
    sweep_ok = files(s__yaml=sweep_file("  motion.speed_mm_s: [100]"), base__yaml=scenario())
    sweeps = {"lock-symlink": both(victim(), link("out/.coatsim-sweep.lock", "{d}/victim.txt")),
              "lock-folder": folder("out/.coatsim-sweep.lock"), "lock-fifo": fifo("out/.coatsim-sweep.lock"),
              "manifest-symlink": both(victim(), link("out/sweep.json", "{d}/victim.txt")),
              "manifest-dev-zero": link("out/sweep.json", "/dev/zero"), "outdir-file": victim("out"),
              "frozen-folder": frozen("out"), "outdir-device": null_device("out")}
    for name, setup in sweeps.items():
        check = {"lock-symlink": victim_intact(), "manifest-symlink": victim_intact(), "outdir-file": victim_intact("out"),
                 "outdir-device": still("out", "chr")}.get(name)
        c.append(Case("outputs", f"sweep-{name}", ["sweep", "{d}/s.yaml", "-o", "{d}/out", "--workers", "1"],
                      setup=both(sweep_ok, setup), check=check, timeout=240, bomb=name in ("lock-fifo", "manifest-dev-zero")))
    return c


def svg_cases() -> list[Case]:
    bodies = {
        "use-self": '<g id="a"><use xlink:href="#a"/></g>', "use-mutual": '<g id="a"><use xlink:href="#b"/></g><g id="b"><use xlink:href="#a"/></g>',
        "use-self-href": '<g id="a"><use href="#a"/></g>', "use-missing": '<use xlink:href="#nothing"/>',
        "use-external": '<use xlink:href="other.svg#a"/>', "use-file-url": '<use xlink:href="file:///etc/passwd#a"/>',
        "nested-g-5000": "<g>" * 5000 + SVG_RECT + "</g>" * 5000, "nested-g-100000": "<g>" * 100000 + SVG_RECT + "</g>" * 100000,
        "nested-svg-3000": "<svg>" * 3000 + SVG_RECT + "</svg>" * 3000, "nested-a-3000": "<a>" * 3000 + SVG_RECT + "</a>" * 3000,
        "arc-radius-1e-300": '<path d="M10 10 A1e-300 1e-300 0 0 1 20 10"/>', "arc-radius-1e308": '<path d="M10 10 A1e308 1e308 0 0 1 20 10"/>',
        "arc-tiny-ends": '<path d="M10 10 A5 5 0 0 1 10 10.0000000001"/>', "path-nan": '<path d="M0 0 L nan 5"/>',
        "path-1e308": '<path d="M0 0 L1e308 5 L0 5"/>', "path-1e400": '<path d="M0 0 L1e400 5"/>',
        "scale-1e308": f'<g transform="scale(1e308)">{SVG_RECT}</g>', "scale-0": f'<g transform="scale(0)">{SVG_RECT}</g>',
        "matrix-zero": f'<g transform="matrix(0 0 0 0 0 0)">{SVG_RECT}</g>', "matrix-nan": f'<g transform="matrix(nan 0 0 1 0 0)">{SVG_RECT}</g>',
        "rotate-nan": f'<g transform="rotate(nan)">{SVG_RECT}</g>', "skew-89.99": f'<g transform="skewX(89.9999999)">{SVG_RECT}</g>',
        "scale-1e-300": f'<g transform="scale(1e-300)">{SVG_RECT}</g>', "translate-1e308": f'<g transform="translate(1e308,0)">{SVG_RECT}</g>',
        "rect-nan": '<rect x="0" y="0" width="nan" height="5"/>', "rect-rx-huge": '<rect width="10" height="10" rx="1e308"/>',
        "circle-negative": '<circle cx="5" cy="5" r="-1"/>', "circle-1e-300": '<circle cx="5" cy="5" r="1e-300"/>',
        "ellipse-rx-0": '<ellipse cx="5" cy="5" rx="0" ry="5"/>', "ellipse-flat": '<ellipse cx="5" cy="5" rx="1e-12" ry="5"/>',
        "polyline-one": '<polyline points="1,1"/>', "polygon-nan": '<polygon points="0,0 nan,1 2,2"/>',
        "polyline-odd": '<polyline points="0,0 1"/>', "line-zero": '<line x1="1" y1="1" x2="1" y2="1"/>',
        "text-only": "<text>hello</text>", "empty": "", "image-dev-zero": '<image xlink:href="/dev/zero" width="10" height="10"/>',
        "image-data": '<image xlink:href="data:image/png;base64,AAAA" width="10" height="10"/>',
        "style-import": f'<style>@import url(/dev/zero);</style>{SVG_RECT}', "symbol-self": '<symbol id="s"><use href="#s"/></symbol><use href="#s"/>',
        "symbol-zero-viewbox": f'<symbol id="s" viewBox="0 0 0 0">{SVG_RECT}</symbol><use href="#s"/>',
        "symbol-nan-viewbox": f'<symbol id="s" viewBox="nan 0 1 1">{SVG_RECT}</symbol><use href="#s" width="10" height="10"/>',
        "use-width-0": f'<symbol id="s" viewBox="0 0 10 10">{SVG_RECT}</symbol><use href="#s" width="0" height="0"/>',
        "clip-use-cycle": '<clipPath id="c"><use href="#c"/></clipPath><rect width="5" height="5" clip-path="url(#c)"/>',
        "pattern-cycle": '<pattern id="p"><rect width="5" height="5" fill="url(#p)"/></pattern><rect width="5" height="5" fill="url(#p)"/>',
        "path-1m-commands": '<path d="M0 0' + " l0.001 0" * 1_000_000 + '"/>', "circles-300k": '<circle cx="5" cy="5" r="1"/>' * 300_000,
        "bezier-degenerate": '<path d="M0 0 C0 0 0 0 0 0"/>', "bezier-cusp": '<path d="M0 0 C10 10 0 10 10 0"/>',
        "bezier-1e-12": '<path d="M0 0 C1e-12 0 1e-12 1e-12 0 1e-12"/>', "arc-flags-bad": '<path d="M0 0 A5 5 0 2 1 10 0"/>',
        "huge-css": '<rect width="10" height="10" style="' + "a:b;" * 200000 + '"/>', "unicode-ids": '<g id="\u2603"><use href="#\u2603"/></g>',
    }
    extras = {"viewbox-zero": ' viewBox="0 0 0 0"', "viewbox-nan": ' viewBox="nan 0 1 1"', "width-1e308": ' width="1e308mm"',
              "width-negative": ' width="-5mm"'}
    cases = [Case("svg", name, ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg=svg(body)),
                  bomb=name in ("use-self", "use-mutual", "use-self-href", "nested-g-100000", "path-1m-commands", "circles-300k",
                                "clip-use-cycle", "pattern-cycle", "symbol-self", "huge-css"), timeout=120)
             for name, body in bodies.items()]
    cases += [Case("svg", name, ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg=svg(SVG_RECT, extra)))
              for name, extra in extras.items()]
    cases.append(Case("svg", "use-bomb-1e9", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg=use_bomb()), bomb=True, timeout=120))
    cases.append(Case("svg", "use-bomb-1e5", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg=use_bomb(5)), bomb=True, timeout=120))
    cases.append(Case("svg", "use-bomb-symbol", ["segment", "{d}/d.svg", "--tol", "0.1"],
                      setup=files(d__svg=use_bomb().replace("<g id", "<symbol id").replace("</g>", "</symbol>")), bomb=True, timeout=120))
    doc = '<?xml version="1.0"?>\n'
    cases += [
        Case("svg", "xxe", ["segment", "{d}/d.svg", "--tol", "0.1"],
             setup=files(d__svg=doc + '<!DOCTYPE svg [<!ENTITY x SYSTEM "file:///etc/passwd">]>' + svg("<text>&x;</text>" + SVG_RECT))),
        Case("svg", "billion-laughs", ["segment", "{d}/d.svg", "--tol", "0.1"], bomb=True,
             setup=files(d__svg=doc + "<!DOCTYPE svg [<!ENTITY a0 'lol'>" + "".join(f"<!ENTITY a{k} '{('&a' + str(k - 1) + ';') * 10}'>" for k in range(1, 10))
                         + "]>" + svg("<text>&a9;</text>" + SVG_RECT))),
        Case("svg", "not-wellformed", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg="<svg><g></svg>")),
        Case("svg", "html-root", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg="<html><body/></html>")),
        Case("svg", "utf16", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg=svg(SVG_RECT).encode("utf-16"))),
        Case("svg", "binary", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg=np.random.default_rng(1).bytes(2000))),
        Case("svg", "fifo", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=fifo("d.svg"), bomb=True),
        Case("svg", "dev-zero", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=link("d.svg", "/dev/zero"), bomb=True),
        Case("svg", "dev-urandom", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=link("d.svg", "/dev/urandom"), bomb=True),
        Case("svg", "folder", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=folder("d.svg")),
        Case("svg", "symlink-loop", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=link("d.svg", "{d}/d.svg")),
        Case("svg", "empty-file", ["segment", "{d}/d.svg", "--tol", "0.1"], setup=files(d__svg="")),
        Case("svg", "program-use-self", ["program", "{d}/d.svg", "--tol", "0.1", "-o", "{d}/p.as"],
             setup=files(d__svg=svg('<g id="a"><use xlink:href="#a"/></g>'))),
        Case("svg", "run-use-bomb", ["run", "{d}/s.yaml", "--fast", "-o", "{d}/out"], bomb=True, timeout=120,
             setup=files(d__svg=use_bomb(), s__yaml=scenario(curve="{file: d.svg}"))),
    ]
    return cases


def dxf_cases() -> list[Case]:
    c: list[Case] = []
    seg = lambda name, setup, **kw: Case("dxf", name, ["segment", "{d}/d.dxf", "--tol", "0.1"], setup=files(d__dxf=setup), **kw)  # noqa: E731
    for value in ("nan", "inf", "-inf", "1e308", "1e400", "1e-320", "-1e308"):
        c.append(seg(f"line-{value}", dxf_line(value)))
    ph = float(PLACEHOLDER)
    entity_builds = {
        "arc-center": lambda doc, msp: msp.add_arc((ph, 0), 5, 0, 90),
        "arc-radius": lambda doc, msp: msp.add_arc((0, 0), ph, 0, 90),
        "arc-angle": lambda doc, msp: msp.add_arc((0, 0), 5, ph, 90),
        "circle-radius": lambda doc, msp: msp.add_circle((0, 0), ph),
        "ellipse-ratio": lambda doc, msp: msp.add_ellipse((0, 0), (10, 0), ratio=RATIO_PLACEHOLDER),
        "ellipse-major": lambda doc, msp: msp.add_ellipse((0, 0), (ph, 0), ratio=0.5),
        "ellipse-param": lambda doc, msp: msp.add_ellipse((0, 0), (10, 0), ratio=0.5, start_param=ph, end_param=1),
        "lwpolyline-bulge": lambda doc, msp: msp.add_lwpolyline([(0, 0, 0, 0, ph), (10, 0), (10, 10)], format="xyseb"),
        "lwpolyline-point": lambda doc, msp: msp.add_lwpolyline([(0, 0), (ph, 0), (10, 10)]),
        "spline-control": lambda doc, msp: msp.add_open_spline([(0, 0), (ph, 5), (10, 0), (15, 5)]),
        "spline-fit": lambda doc, msp: msp.add_spline(fit_points=[(0, 0), (ph, 5), (10, 0), (15, 5)]),
        "insert-scale": lambda doc, msp: (doc.blocks.new("B").add_line((0, 0), (1, 0)), msp.add_blockref("B", (0, 0), dxfattribs={"xscale": ph})),
        "insert-rotation": lambda doc, msp: (doc.blocks.new("B").add_line((0, 0), (1, 0)), msp.add_blockref("B", (0, 0), dxfattribs={"rotation": ph})),
        "insert-point": lambda doc, msp: (doc.blocks.new("B").add_line((0, 0), (1, 0)), msp.add_blockref("B", (ph, 0))),
        "extrusion": lambda doc, msp: msp.add_circle((0, 0), 5, dxfattribs={"extrusion": (0, 0, ph)}),
    }
    for name, build in entity_builds.items():
        values = ("nan", "inf", "1e308", "0", "-1", "1e-300") if name in ("ellipse-ratio", "arc-radius", "circle-radius", "insert-scale") \
            else ("nan", "inf", "1e308")
        for value in values:
            c.append(seg(f"{name}-{value}", dxf(build, {PLACEHOLDER: value, str(RATIO_PLACEHOLDER): value})))
    c.append(seg("ellipse-ratio-2", dxf(entity_builds["ellipse-ratio"], {str(RATIO_PLACEHOLDER): "2"})))
    builds = {
        "rect": dxf_rect,
        "spline-degree-50": lambda doc, msp: msp.add_open_spline([(i, i % 2) for i in range(60)], degree=50),
        "spline-one-point": lambda doc, msp: msp.add_open_spline([(0, 0)]),
        "spline-100k": lambda doc, msp: msp.add_open_spline([(i * 0.01, (i % 2) * 0.01) for i in range(100_000)]),
        "spline-equal-points": lambda doc, msp: msp.add_open_spline([(1, 1)] * 10),
        "lwpolyline-one": lambda doc, msp: msp.add_lwpolyline([(0, 0)]),
        "insert-self": lambda doc, msp: (doc.blocks.new("B").add_blockref("B", (0, 0)), msp.add_blockref("B", (0, 0))),
        "insert-missing": lambda doc, msp: msp.add_blockref("NOPE", (0, 0)),
        "minsert-32767": lambda doc, msp: (doc.blocks.new("B").add_line((0, 0), (1, 0)),
                                          msp.add_blockref("B", (0, 0)).grid(size=(32767, 32767), spacing=(1, 1))),
        "text-only": lambda doc, msp: msp.add_text("hello"), "hatch-only": lambda doc, msp: msp.add_hatch(),
        "empty": lambda doc, msp: None, "3dface": lambda doc, msp: msp.add_3dface([(0, 0, 0), (1, 0, 0), (1, 1, 1)]),
        "tilted-mixed": lambda doc, msp: (msp.add_circle((0, 0), 5, dxfattribs={"extrusion": (0, 1, 1)}), dxf_rect(doc, msp)),
        "polyline-3d-nan": lambda doc, msp: msp.add_polyline3d([(0, 0, 0), (ph, 0, 0), (5, 5, 0)]),
        "polyface": lambda doc, msp: msp.add_polyface().append_face([(0, 0, 0), (1, 0, 0), (1, 1, 0)]),
    }
    bombs = {"spline-100k", "lwpolyline-1m", "minsert-32767"}
    for name, build in builds.items():
        replace = {PLACEHOLDER: "nan"} if "nan" in name else None
        c.append(seg(name, dxf(build, replace), bomb=name in bombs, timeout=120))
    c.append(seg("nested-doubling-30", dxf_nested_blocks(30, 2), bomb=True, timeout=120))
    c.append(seg("nested-10x10", dxf_nested_blocks(10, 10), bomb=True, timeout=120))
    c.append(seg("nested-minsert", dxf_nested_blocks(4, 1, (100, 100)), bomb=True, timeout=120))
    c.append(seg("million-lines", million_lines_dxf(), bomb=True, timeout=300))
    c.append(seg("lwpolyline-1m", lwpolyline_dxf(), bomb=True, timeout=300))
    c.append(seg("units-miles", dxf(lambda doc, msp: (doc.header.__setitem__("$INSUNITS", 3), dxf_rect(doc, msp)))))
    c.append(seg("units-bogus", dxf(dxf_rect, {"$INSUNITS\n 70\n4": "$INSUNITS\n 70\n999"})))
    c.append(seg("codepage-bogus", dxf(dxf_rect, {"ANSI_1252": "ANSI_99999"})))
    c.append(seg("truncated", lambda p: (dxf(dxf_rect)(p), p.write_text(p.read_text()[:2000]))))
    c.append(seg("dwg", b"AC1032" + b"\0" * 1000))
    c.append(seg("binary-garbage", np.random.default_rng(2).bytes(5000)))
    c.append(seg("binary-dxf-header", b"AutoCAD Binary DXF\r\n\x1a\x00" + np.random.default_rng(3).bytes(2000)))
    c.append(seg("empty-file", ""))
    c.append(seg("text-garbage", "hello\nworld\n"))
    c.append(seg("group-code-garbage", "0\nSECTION\n2\nENTITIES\n0\nLINE\nzz\n0\n0\nENDSEC\n0\nEOF\n"))
    c.append(seg("huge-group-value", "0\nSECTION\n2\nENTITIES\n0\nLINE\n8\n" + "L" * 10_000_000 + "\n0\nENDSEC\n0\nEOF\n"))
    c.append(Case("dxf", "fifo", ["segment", "{d}/d.dxf", "--tol", "0.1"], setup=fifo("d.dxf"), bomb=True))
    c.append(Case("dxf", "dev-zero", ["segment", "{d}/d.dxf", "--tol", "0.1"], setup=link("d.dxf", "/dev/zero"), bomb=True))
    c.append(Case("dxf", "folder", ["segment", "{d}/d.dxf", "--tol", "0.1"], setup=folder("d.dxf")))
    c.append(Case("dxf", "symlink-loop", ["segment", "{d}/d.dxf", "--tol", "0.1"], setup=link("d.dxf", "{d}/d.dxf")))
    c.append(Case("dxf", "layer-missing", ["segment", "{d}/d.dxf", "--tol", "0.1", "--layer", "NOPE"], setup=files(d__dxf=dxf(dxf_rect))))
    c.append(Case("dxf", "join-tol-1e308", ["segment", "{d}/d.dxf", "--tol", "0.1", "--join-tol", "1e308"], setup=files(d__dxf=dxf(dxf_rect))))
    c.append(Case("dxf", "join-tol-nan", ["segment", "{d}/d.dxf", "--tol", "0.1", "--join-tol", "nan"], setup=files(d__dxf=dxf(dxf_rect))))
    c.append(Case("dxf", "join-tol-1e-300", ["segment", "{d}/d.dxf", "--tol", "0.1", "--join-tol", "1e-300"], setup=files(d__dxf=dxf(dxf_rect))))
    c.append(Case("dxf", "program-nested-bomb", ["program", "{d}/d.dxf", "--tol", "0.1", "-o", "{d}/p.as"],
                  setup=files(d__dxf=dxf_nested_blocks(10, 10)), bomb=True, timeout=120))
    c.append(Case("dxf", "run-nan", ["run", "{d}/s.yaml", "--fast", "-o", "{d}/out"],
                  setup=files(d__dxf=dxf_line("nan"), s__yaml=scenario(curve="{file: d.dxf}"))))
    return c


def program_cases() -> list[Case]:
    deep = "(" * 100_000 + "1" + ")" * 100_000
    bodies = {
        "sum-600": "  x = " + "+".join(["1"] * 600), "sum-100k": "  x = " + "+".join(["1"] * 100_000),
        "parens-100k": f"  x = {deep}", "parens-70": "  x = " + "(" * 70 + "1" + ")" * 70,
        "unary-100k": "  x = " + "-" * 100_000 + "1", "not-100k": "  x = " + "NOT " * 20_000 + "1",
        "string-doubling-40": '  $s = "ab"\n  FOR i = 1 TO 40\n    $s = $s + $s\n  END',
        "string-doubling-unrolled": '  $s = "ab"\n' + '  $s = $s + $s\n' * 40,
        "space-1e9": "  $s = $SPACE(1000000000)", "encode-width": '  $s = $ENCODE(/F999999999.0, 1)',
        "mid-huge": '  $s = $MID("abc", 1, 1000000000)', "chr-neg": "  $s = $CHR(-1)",
        "loop-1e9": "  FOR i = 1 TO 1000000000\n    x = i\n  END", "while-true": "  WHILE TRUE DO\n    x = 1\n  END",
        "goto-loop": "10 x = 1\n  GOTO 10", "array-1e9": "  a[1000000000] = 1", "array-neg": "  a[-1] = 1",
        "array-3d-huge": "  a[1000,1000,1000] = 1", "array-fill": "  FOR i = 1 TO 900000\n    a[i] = i\n  END",
        "div-zero": "  x = 1/0", "sqrt-neg": "  x = SQRT(-1)", "overflow": "  x = 1e15\n  FOR i = 1 TO 40\n    x = x*x\n  END",
        "pow-overflow": "  x = 10^400", "log-zero": "  x = LOG(0)", "trans-huge": "  LMOVE TRANS(1e15,0,0,0,0,0)",
        "trans-overflow": "  x = 1e15*1e15*1e15\n  LMOVE TRANS(x,0,300,0,180,0)", "speed-1e-200": "  SPEED 1e-15 MM/S ALWAYS\n" + AS_OK.split("\n", 2)[2].rsplit(".END", 1)[0],
        "speed-0": "  SPEED 0 ALWAYS\n  LMOVE TRANS(600,0,300,0,180,0)\n  LMOVE TRANS(650,0,300,0,180,0)",
        "accuracy-huge": "  ACCURACY 1e15 ALWAYS\n  LMOVE TRANS(600,0,300,0,180,0)",
        "signal-huge": "  SIGNAL 1000000000", "signal-nan": "  x = 0\n  SIGNAL x/0",
        "call-self": "  CALL t", "goto-missing": "  GOTO 99", "label-dup": "10 x = 1\n10 x = 2",
        "if-nested-10000": "  IF TRUE THEN\n" * 10_000 + "  x = 1\n" + "  END\n" * 10_000,
        "for-nested-5000": "".join(f"  FOR i{k} = 1 TO 1\n" for k in range(5000)) + "  END\n" * 5000,
        "long-string": '  $s = "' + "a" * 10_000_000 + '"', "long-line": "  x = 1 ; " + "c" * 10_000_000,
        "many-lines": "  x = 1\n" * 2_000_000, "unreachable": "  LMOVE TRANS(5000,0,300,0,180,0)\n  SIGNAL 1\n  LMOVE TRANS(5100,0,300,0,180,0)",
        "point-nan": "  POINT p = TRANS(0/0,0,0,0,0,0)", "decompose": "  DECOMPOSE a[0] = TRANS(1,2,3,4,5,6)",
        "here": "  HERE p", "draw-huge": "  DRAW 1e15, 0, 0", "twait-huge": "  TWAIT 1e15",
        "val-huge": '  x = VAL("1e999")', "string-compare-huge": '  $a = $SPACE(10000)\n  x = $a == $a',
    }
    bombs = {"sum-100k", "parens-100k", "unary-100k", "not-100k", "string-doubling-40", "string-doubling-unrolled", "space-1e9",
             "encode-width", "mid-huge", "loop-1e9", "while-true", "goto-loop", "array-1e9", "array-3d-huge", "array-fill",
             "if-nested-10000", "for-nested-5000", "long-string", "long-line", "many-lines", "twait-huge", "speed-1e-200"}
    c = [Case("program", name, ["check-program", "{d}/t.as"], setup=files(t__as=as_program(body)), bomb=name in bombs, timeout=120)
         for name, body in bodies.items()]
    for name in ("string-doubling-40", "speed-1e-200", "speed-0", "unreachable", "trans-huge", "loop-1e9", "twait-huge", "accuracy-huge"):
        c.append(Case("program", f"execute-{name}", ["execute", "{d}/t.as", "-o", "{d}/out"], setup=files(t__as=as_program(bodies[name])),
                      bomb=name in bombs, timeout=120))
        c.append(Case("program", f"convert-{name}", ["convert", "{d}/t.as", "--tol", "0.1"], setup=files(t__as=as_program(bodies[name])),
                      bomb=name in bombs, timeout=120))
    raw = {"empty": "", "garbage": np.random.default_rng(4).bytes(3000), "nul": b".PROGRAM t()\n\x00\x00\n.END\n",
           "utf16": AS_OK.encode("utf-16"), "no-end": ".PROGRAM t()\n  x = 1\n", "no-program": "x = 1\n",
           "many-programs": "".join(f".PROGRAM p{k}()\n  x = 1\n.END\n" for k in range(50_000)),
           "bad-name": ".PROGRAM \x1b[2J()\n.END\n", "only-end": ".END\n", "bom": "\ufeff" + AS_OK, "cr-only": AS_OK.replace("\n", "\r")}
    for name, text in raw.items():
        c.append(Case("program", f"raw-{name}", ["check-program", "{d}/t.as"], setup=files(t__as=text), bomb=name == "many-programs"))
    for kind, setup in (("fifo", fifo("t.as")), ("dev-zero", link("t.as", "/dev/zero")), ("dev-urandom", link("t.as", "/dev/urandom")),
                        ("folder", folder("t.as")), ("symlink-loop", link("t.as", "{d}/t.as")), ("proc", link("t.as", "/proc/self/status"))):
        for command in (["check-program"], ["execute", "-o", "{d}/out"], ["convert", "--tol", "0.1"]):
            argv = [command[0], "{d}/t.as", *command[1:]]
            c.append(Case("program", f"{command[0]}-{kind}", argv, setup=setup, bomb=kind in ("fifo", "dev-zero", "dev-urandom")))
    c.append(Case("program", "execute-model-dev-zero", ["execute", "{d}/t.as", "--model", "{d}/m.xml", "-o", "{d}/out"],
                  setup=both(files(t__as=AS_OK), link("m.xml", "/dev/zero")), bomb=True))
    c.append(Case("program", "execute-model-fifo", ["execute", "{d}/t.as", "--model", "{d}/m.xml", "-o", "{d}/out"],
                  setup=both(files(t__as=AS_OK), fifo("m.xml")), bomb=True))
    c.append(Case("program", "execute-model-garbage", ["execute", "{d}/t.as", "--model", "{d}/m.xml", "-o", "{d}/out"],
                  setup=files(t__as=AS_OK, m__xml="<mujoco><worldbody>" + "<body>" * 10000 + "</body>" * 10000 + "</worldbody></mujoco>")))
    c.append(Case("program", "check-model-folder", ["check-program", "{d}/t.as", "--model", "{d}"], setup=files(t__as=AS_OK)))
    return c


def json_cases() -> list[Case]:
    seg_ok = {"format": "coatsim.polysegment/1", "units": "mm", "closed": False, "tolerance_mm": 0.1,
              "segments": [{"kind": "line", "start": [0.0, 0.0], "end": [50.0, 0.0]}], "corners": []}

    def doc(**over) -> str:
        return json.dumps({**seg_ok, **over})

    texts = {
        "nested-100000": "[" * 100_000 + "]" * 100_000, "nested-obj-100000": '{"a":' * 100_000 + "1" + "}" * 100_000,
        "nested-in-stats": doc()[:-1] + ', "stats": ' + "[" * 100_000 + "]" * 100_000 + "}",
        "nan-radius": doc(segments=[{"kind": "arc", "start": [0, 0], "end": [10, 0], "center": [5, 0], "radius": float("nan"), "sweep": 3.14}]),
        "infinity": doc(segments=[{"kind": "line", "start": [0, 0], "end": [float("inf"), 0]}]),
        "1e400": doc()[:-1].replace("50.0", "1e400") + "}", "big-int": doc().replace("50.0", "9" * 100_000),
        "huge-coords": doc(segments=[{"kind": "line", "start": [0, 0], "end": [1e300, 0]}]),
        "radius-0": doc(segments=[{"kind": "arc", "start": [0, 0], "end": [0, 0], "center": [0, 0], "radius": 0, "sweep": 1}]),
        "radius-neg": doc(segments=[{"kind": "arc", "start": [0, 0], "end": [10, 0], "center": [5, 0], "radius": -5, "sweep": 3.14}]),
        "sweep-huge": doc(segments=[{"kind": "arc", "start": [5, 0], "end": [5, 0], "center": [0, 0], "radius": 5, "sweep": 1e15}]),
        "gap": doc(segments=[{"kind": "line", "start": [0, 0], "end": [10, 0]}, {"kind": "line", "start": [20, 0], "end": [30, 0]}]),
        "wrong-format": doc(format="coatsim.polysegment/99"), "no-segments": doc(segments=[]), "segments-dict": doc(segments={}),
        "kind-bad": doc(segments=[{"kind": "spline"}]), "strings": doc(segments=[{"kind": "line", "start": ["0", "0"], "end": ["1", "0"]}]),
        "bool-coords": doc(segments=[{"kind": "line", "start": [True, False], "end": [1, 0]}]),
        "tol-nan": doc(tolerance_mm=float("nan")), "tol-neg": doc(tolerance_mm=-1), "tol-1e-300": doc(tolerance_mm=1e-300),
        "many-segments": doc(segments=[{"kind": "line", "start": [i * 0.001, 0], "end": [(i + 1) * 0.001, 0]} for i in range(500_000)]),
        "duplicate-keys": doc()[:-1] + ', "segments": []}', "not-json": "hello", "empty": "", "array-root": "[]",
        "invalid-utf8": b'{"format": "\xff\xfe"}', "part-empty": json.dumps({"format": "coatsim.part/1", "contours": []}),
        "part-nested": json.dumps({"format": "coatsim.part/1", "contours": [{"format": "coatsim.part/1", "contours": []}]}),
        "corners-huge": doc(corners=[10**30]), "speed-limited-nan": doc(speed_limited=[[0, 1, float("nan")]]),
        "3d-as-2d": doc(segments=[{"kind": "line", "start": [0, 0, 0], "end": [1, 0, 5]}]),
    }
    c = [Case("json", name, ["program", "{d}/p.json", "-o", "{d}/p.as"], setup=files(p__json=text.encode() if isinstance(text, str) else text),
              bomb=name in ("nested-100000", "nested-obj-100000", "many-segments", "nested-in-stats", "big-int"))
         for name, text in texts.items()]
    for kind, setup in (("fifo", fifo("p.json")), ("dev-zero", link("p.json", "/dev/zero")), ("folder", folder("p.json")),
                        ("loop", link("p.json", "{d}/p.json"))):
        c.append(Case("json", kind, ["program", "{d}/p.json", "-o", "{d}/p.as"], setup=setup, bomb=kind in ("fifo", "dev-zero")))
    return c


def scenario_cases() -> list[Case]:
    c: list[Case] = []
    run = ["run", "{d}/s.yaml", "--fast", "-o", "{d}/out"]

    def case(name: str, *setups: Setup, bomb: bool = False, check: Optional[Check] = None) -> None:
        c.append(Case("scenario", name, run, setup=both(*setups), bomb=bomb, check=check, timeout=180))

    for kind, setup in (("fifo", fifo("c.csv")), ("dev-zero", link("c.csv", "/dev/zero")), ("folder", folder("c.csv")),
                        ("loop", link("c.csv", "{d}/c.csv")), ("missing", None), ("proc", link("c.csv", "/proc/self/status"))):
        case(f"curve-{kind}", files(s__yaml=scenario(curve="{file: c.csv}")), setup, bomb=kind in ("fifo", "dev-zero"))
    case("curve-xyz", files(s__yaml=scenario(curve="{file: c.csv}"), c__csv=csv_text(helix())), check=refused)
    case("curve-5col", files(s__yaml=scenario(curve="{file: c.csv}"), c__csv="0,0,0,0,0\n1,1,1,1,1\n2,0,0,0,0\n"))
    case("curve-npy3", files(s__yaml=scenario(curve="{file: c.npy}"), c__npy=npy(helix())), check=refused)
    case("curve-escape", files(s__yaml=scenario(curve="{file: ../../../../../../etc/passwd}")))
    case("curve-absolute-shadow", files(s__yaml=scenario(curve="{file: /etc/shadow}")))
    for kind, setup in (("fifo", fifo("m.stl")), ("dev-zero", link("m.stl", "/dev/zero")), ("folder", folder("m.stl")),
                        ("huge-count", files(m__stl=BINARY_STL_HUGE)), ("garbage", files(m__stl=np.random.default_rng(5).bytes(3000))),
                        ("ascii-nan", files(m__stl="solid s\nfacet normal 0 0 1\nouter loop\nvertex nan 0 0\nvertex 1 0 0\nvertex 0 1 0\nendloop\nendfacet\nendsolid s\n")),
                        ("ply-count", files(m__stl="ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\nend_header\n")),
                        ("empty", files(m__stl=""))):
        case(f"mesh-{kind}", files(s__yaml=scenario(workpiece="{kind: mesh, file: m.stl}")), setup,
             bomb=kind in ("fifo", "dev-zero", "huge-count", "ply-count"))
    c.append(Case("scenario", "mesh-ply-count-coat", ["coat", "{d}/t.csv", "--surface", "{d}/m.ply", "-o", "{d}/out"],
                  setup=files(t__csv=trajectory_csv(), m__ply="ply\nformat ascii 1.0\nelement vertex 4000000000\nproperty float x\n"
                              "property float y\nproperty float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n"), bomb=True))
    c.append(Case("scenario", "mesh-obj-faces-coat", ["coat", "{d}/t.csv", "--surface", "{d}/m.obj", "-o", "{d}/out"],
                  setup=files(t__csv=trajectory_csv(), m__obj="v 0 0 0\nv 1 0 0\nv 0 1 0\n" + "f 1 2 3\n" * 1_000_000), bomb=True, timeout=120))
    for kind, setup in (("fifo", fifo("f.csv")), ("dev-zero", link("f.csv", "/dev/zero")), ("folder", folder("f.csv")),
                        ("garbage", files(f__csv="u_mm,v_mm,rate\n" + "1,2\n" * 10))):
        case(f"footprint-table-{kind}", files(s__yaml=scenario(footprint="table:f.csv")), setup, bomb=kind in ("fifo", "dev-zero"))
    for kind, setup in (("fifo", fifo("m.xml")), ("dev-zero", link("m.xml", "/dev/zero")), ("folder", folder("m.xml"))):
        case(f"robot-{kind}", files(s__yaml=scenario(extra="robot: {model: m.xml}\n")), setup, bomb=kind in ("fifo", "dev-zero"))
    for kind, setup in (("fifo", fifo("v.as")), ("dev-zero", link("v.as", "/dev/zero")),
                        ("doubling", files(v__as=as_program('  $s = "ab"\n  FOR i = 1 TO 40\n    $s = $s + $s\n  END')))):
        case(f"variant-program-{kind}", files(s__yaml=scenario().replace("variants: [polysegment]",
                                                                         "variants: [{name: mine, program: v.as}, polysegment]")),
             setup, bomb=True)
    for value in ("1e-200", "1e308", "1e-300", ".nan", ".inf", "-1", "0"):
        case(f"speed-{value}", files(s__yaml=scenario(speed=value)), bomb=value in ("1e-200", "1e-300"))
    yaml_texts = {"tol-1e-300": scenario().replace("tolerance_mm: 0.1", "tolerance_mm: 1e-300"),
                  "spacing-1e-300": scenario().replace("spacing_mm: 2.5", "spacing_mm: 1e-300"),
                  "lead-in-1e308": scenario().replace("lead_in_mm: 10.0", "lead_in_mm: 1e308"),
                  "accuracy-1e308": scenario().replace("accuracy_mm: 0.5", "accuracy_mm: 1e308"),
                  "plate-1e308": scenario(workpiece="{kind: plate, size_mm: [1e308, 1e308]}"),
                  "plate-1e-300": scenario(workpiece="{kind: plate, size_mm: [1e-300, 1e-300]}"),
                  "cylinder-huge": scenario(workpiece="{kind: cylinder, radius_mm: 1e9, length_mm: 1e9}"),
                  "builtin-spiral-1e6": scenario(curve="{builtin: paper-spiral, params: {turns: 1000000}}"),
                  "builtin-sine-1e-6": scenario(curve="{builtin: sine, params: {wavelength: 1e-6}}"),
                  "builtin-points": scenario(curve="{builtin: ellipse, params: {a: 40, b: 20}}").replace("a: 40", "a: 40, points: 1000000000"),
                  "scale-1e308": scenario(curve="{builtin: ellipse, scale: 1e308}"), "offset-nan": scenario(curve="{builtin: ellipse, offset_mm: [.nan, 0]}"),
                  "name-weird": scenario().replace("name: hostile", "name: '../../etc'"), "unicode-name": scenario().replace("name: hostile", "name: h\u00e4"),
                  "gates-huge": scenario(extra="gates:\n" + "  - {metric: motion.stops, op: '==', threshold: 0}\n" * 20000),
                  "anchors-bomb": "a: &a [1,1,1,1,1,1,1,1,1,1]\nb: &b [*a,*a,*a,*a,*a,*a,*a,*a,*a,*a]\nc: &c [*b,*b,*b,*b,*b,*b,*b,*b,*b,*b]\n"
                                  "d: &d [*c,*c,*c,*c,*c,*c,*c,*c,*c,*c]\ne: [*d,*d,*d,*d,*d,*d,*d,*d,*d,*d]\n",
                  "deep": "name: x\ncurve: " + "[" * 100_000 + "]" * 100_000 + "\n", "tabs": "name:\tx\n", "binary": "\x00\x01\x02",
                  "python-tag": "name: !!python/object/apply:os.system ['echo pwned']\n", "empty": "", "list-root": "- a\n",
                  "huge": "name: x\n" + "# " + "c" * 2_000_000 + "\n", "footprint-huge-sigma": scenario(footprint="gaussian:sigma=1e308"),
                  "footprint-tiny-sigma": scenario(footprint="gaussian:sigma=1e-300")}
    for name, text in yaml_texts.items():
        case(f"yaml-{name}", files(s__yaml=text), bomb=name in ("tol-1e-300", "spacing-1e-300", "builtin-spiral-1e6", "builtin-sine-1e-6",
                                                                "anchors-bomb", "deep", "huge", "footprint-tiny-sigma", "builtin-points"))
    for kind, setup in (("fifo", fifo("s.yaml")), ("dev-zero", link("s.yaml", "/dev/zero")), ("folder", folder("s.yaml")),
                        ("loop", link("s.yaml", "{d}/s.yaml"))):
        case(f"scenario-{kind}", setup, bomb=kind in ("fifo", "dev-zero"))
    return c


def coat_cases() -> list[Case]:
    c: list[Case] = []
    coat = lambda *extra: ["coat", "{d}/t.csv", "--surface", "plate:100x60@50,0,0", "-o", "{d}/out", *extra]  # noqa: E731
    trajs = {"nan-row": trajectory_csv(bad={5: "nan," * 16 + "0"}), "inf-row": trajectory_csv(bad={5: "0.05,inf" + ",0" * 15}),
             "huge-row": trajectory_csv(bad={5: "0.05,1e308" + ",0" * 15}), "header-only": trajectory_csv(0),
             "one-row": trajectory_csv(1), "decimal-commas": trajectory_csv().replace(",", ";").replace(".", ","),
             "bad-header": "a,b,c\n1,2,3\n", "empty": "", "binary": "\x00" * 1000, "short-row": trajectory_csv(bad={5: "1,2"}),
             "time-backwards": trajectory_csv(bad={5: "-100,10,0,100,0,0,-1,200,1,10,0,0,0,0,0,0,0"}),
             "zero-axis": trajectory_csv(bad={5: "0.05,10,0,100,0,0,0,200,1,10,0,0,0,0,0,0,0"}),
             "spray-2": trajectory_csv(bad={5: "0.05,10,0,100,0,0,-1,200,2,10,0,0,0,0,0,0,0"}),
             "huge-time": trajectory_csv(bad={49: "1e15,98,0,100,0,0,-1,200,1,98,0,0,0,0,0,0,0"}),
             "unicode-minus": trajectory_csv().replace(",0,0,-1,", ",0,0,\u22121,"),
             "rows-1m": lambda p: p.write_text(trajectory_csv(1_000_000))}
    for name, text in trajs.items():
        c.append(Case("coat", f"trajectory-{name}", coat(), setup=files(t__csv=text), bomb=name in ("huge-time", "rows-1m"), timeout=120))
    for kind, setup in (("fifo", fifo("t.csv")), ("dev-zero", link("t.csv", "/dev/zero")), ("folder", folder("t.csv")),
                        ("loop", link("t.csv", "{d}/t.csv")), ("proc", link("t.csv", "/proc/self/status"))):
        c.append(Case("coat", f"trajectory-{kind}", coat(), setup=setup, bomb=kind in ("fifo", "dev-zero")))
    traj = files(t__csv=trajectory_csv())
    options = {"spacing-1e-300": ["--spacing", "1e-300"], "spacing-nan": ["--spacing", "nan"], "spacing-neg": ["--spacing", "-1"],
               "rate-nan": ["--rate", "nan"], "rate-1e308": ["--rate", "1e308"], "standoff-1e-300": ["--standoff", "1e-300"],
               "section-nan": ["--section", "nan,0,1,1"], "section-garbage": ["--section", "a,b"], "section-equal": ["--section", "1,1,1,1"],
               "section-huge": ["--section", "-1e308,0,1e308,0"], "edge-band-huge": ["--edge-band", "1e308"],
               "target-nan": ["--target-um", "nan"], "de-exponent-huge": ["--de-exponent", "1e308"],
               "footprint-garbage": ["--footprint", "gaussian:sigma=abc"], "footprint-tiny": ["--footprint", "gaussian:sigma=1e-300"],
               "footprint-huge": ["--footprint", "gaussian:sigma=1e308"], "footprint-unknown": ["--footprint", "magic"],
               "footprint-table-fifo": ["--footprint", "table:{d}/f.csv"], "roi-garbage": ["--roi", "magic"]}
    for name, extra in options.items():
        setup = both(traj, fifo("f.csv")) if "fifo" in name else traj
        c.append(Case("coat", name, coat(*extra), setup=setup, bomb=name in ("spacing-1e-300", "footprint-tiny", "footprint-table-fifo")))
    surfaces = {"plate-nan": "plate:nanx60@0,0,0", "plate-huge": "plate:1e308x1e308@0,0,0", "plate-tiny": "plate:1e-300x1e-300@0,0,0",
                "cylinder-axis": "cylinder:10x10@0,0,0,w", "garbage": "magic", "mesh-missing": "{d}/nothing.stl",
                "mesh-fifo": "{d}/m.stl", "mesh-dev-zero": "{d}/z.stl", "plate-at-nan": "plate:100x60@nan,0,0"}
    for name, spec in surfaces.items():
        setup = both(traj, fifo("m.stl"), link("z.stl", "/dev/zero"))
        c.append(Case("coat", f"surface-{name}", ["coat", "{d}/t.csv", "--surface", spec, "-o", "{d}/out"], setup=setup,
                      bomb=name in ("plate-huge", "mesh-fifo", "mesh-dev-zero")))
    return c


def sweep_cases() -> list[Case]:
    c: list[Case] = []
    base = scenario()
    sw = lambda name, text, bomb=False, **kw: c.append(  # noqa: E731
        Case("sweep", name, ["sweep", "{d}/s.yaml", "-o", "{d}/out", "--workers", "1"], setup=both(files(s__yaml=text, base__yaml=base), kw.pop("setup", None)),
             bomb=bomb, timeout=kw.pop("timeout", 120), **kw))
    six = "\n".join(f"  motion.{k}: [{', '.join(str(v) for v in range(1, 11))}]"
                    for k in ("speed_mm_s", "accuracy_mm", "lead_in_mm", "lead_out_mm"))
    six += "\n  segmentation.tolerance_mm: [0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0]\n  gun.standoff_mm: [10, 20, 30, 40, 50, 60, 70, 80, 90, 100]"
    sw("grid-1e6", sweep_file(six), bomb=True)
    twelve = six + "\n" + "\n".join(f"  gun.{k}: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]" for k in ("flow_mm3_s", "target_thickness_um")) + \
        "\n  coating.spacing_mm: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]\n  segmentation.corner_deg: [1, 2, 3, 4, 5, 6, 7, 8, 9, 10]"
    sw("grid-1e10", sweep_file(twelve), bomb=True)
    sw("points-100k", "base: base.yaml\npoints:\n" + "".join(f"  - {{motion.speed_mm_s: {100 + i}}}\n" for i in range(100_000)), bomb=True)
    sw("grid-bad-key", sweep_file("  motion.nope: [1, 2]"))
    sw("grid-bad-value", sweep_file("  motion.speed_mm_s: [abc]"))
    sw("grid-empty", sweep_file("  motion.speed_mm_s: []"))
    sw("grid-nested", sweep_file("  motion.speed_mm_s: " + "[" * 10000 + "]" * 10000))
    sw("base-self", sweep_file("  motion.speed_mm_s: [100]", base="s.yaml"))
    sw("base-missing", sweep_file("  motion.speed_mm_s: [100]", base="nothing.yaml"))
    sw("base-fifo", sweep_file("  motion.speed_mm_s: [100]", base="f.yaml"), setup=fifo("f.yaml"), bomb=True)
    sw("base-dev-zero", sweep_file("  motion.speed_mm_s: [100]", base="z.yaml"), setup=link("z.yaml", "/dev/zero"), bomb=True)
    sw("base-folder", sweep_file("  motion.speed_mm_s: [100]", base="."))
    sw("metrics-unknown", sweep_file("  motion.speed_mm_s: [100]", extra="metrics: [nope]\n"))
    sw("key-injection", sweep_file("  __class__.x: [1]"))
    sw("key-index-huge", sweep_file("  gates.99999999999999999999.threshold: [1]"))
    sw("value-1e308", sweep_file("  motion.speed_mm_s: [1e308]"))
    sw("value-tiny", sweep_file("  motion.speed_mm_s: [1e-200]"), bomb=True)
    sw("curve-fifo", sweep_file("  curve.file: [f.csv]", extra=""), setup=fifo("f.csv"), bomb=True)
    sw("curve-dev-zero", sweep_file("  curve.file: [z.csv]"), setup=link("z.csv", "/dev/zero"), bomb=True)
    for kind, setup in (("fifo", fifo("s.yaml")), ("dev-zero", link("s.yaml", "/dev/zero")), ("folder", folder("s.yaml"))):
        c.append(Case("sweep", f"sweep-file-{kind}", ["sweep", "{d}/s.yaml", "-o", "{d}/out"], setup=setup, bomb=kind != "folder"))
    c.append(Case("sweep", "scheduler-garbage", ["sweep", "{d}/s.yaml", "-o", "{d}/out", "--scheduler", "tcp://256.1.1.1:1"],
                  setup=files(s__yaml=sweep_file("  motion.speed_mm_s: [100]"), base__yaml=base), timeout=120))
    c.append(Case("sweep", "metric-option-unknown", ["sweep", "{d}/s.yaml", "-o", "{d}/out", "--metric", "nope"],
                  setup=files(s__yaml=sweep_file("  motion.speed_mm_s: [100]"), base__yaml=base)))
    return c


def all_cases() -> list[Case]:
    from hostile_more import more_cases  # the second set, in categories of its own

    return (curve_cases() + builtin_cases() + option_cases() + output_cases() + svg_cases() + dxf_cases() + program_cases()
            + json_cases() + scenario_cases() + coat_cases() + sweep_cases() + more_cases())
