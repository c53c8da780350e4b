"""More hostile inputs for scripts/hostile.py, in categories the first set did not cover: text
encodings and line ends, meshes that lie about their size or hold NaN, self-crossing meshes,
paths with line breaks, outputs into the input's own folder, YAML tags and merge bombs."""

from __future__ import annotations

import json
import struct
from pathlib import Path
from typing import Optional

from hostile_cases import (AS_OK, RECT, RECT_LENGTH, Case, Outcome, csv_text, files, length_is, scenario,
                           trajectory_csv, victim, victim_intact, both)

PLATE_OBJ = "v 0 0 0\nv 100 0 0\nv 100 100 0\nv 0 100 0\nf 1 2 3\nf 1 3 4\n"


def _glb(doc: dict, binary: bytes = b"") -> bytes:
    """A GLB container: the JSON chunk and an optional BIN chunk, 4-byte aligned."""
    text = json.dumps(doc).encode()
    text += b" " * (-len(text) % 4)
    binary += b"\0" * (-len(binary) % 4)
    chunks = struct.pack("<I4s", len(text), b"JSON") + text
    if binary:
        chunks += struct.pack("<I4s", len(binary), b"BIN\0") + binary
    return struct.pack("<4sII", b"glTF", 2, 12 + len(chunks)) + chunks


def _glb_lying(count: int) -> bytes:
    """A GLB whose accessors declare ``count`` vertices and faces over a 36-byte buffer."""
    doc = {"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
           "meshes": [{"primitives": [{"attributes": {"POSITION": 0}, "indices": 1}]}],
           "buffers": [{"byteLength": 36}], "bufferViews": [{"buffer": 0, "byteLength": 12 * count},
                                                            {"buffer": 0, "byteLength": 4 * count}],
           "accessors": [{"bufferView": 0, "componentType": 5126, "count": count, "type": "VEC3",
                          "min": [0, 0, 0], "max": [1, 1, 1]},
                         {"bufferView": 1, "componentType": 5125, "count": count, "type": "SCALAR"}]}
    return _glb(doc, struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0))


def _gltf_uri(uri: str) -> str:
    return json.dumps({"asset": {"version": "2.0"}, "scenes": [{"nodes": [0]}], "nodes": [{"mesh": 0}],
                       "meshes": [{"primitives": [{"attributes": {"POSITION": 0}}]}],
                       "buffers": [{"byteLength": 36, "uri": uri}], "bufferViews": [{"buffer": 0, "byteLength": 36}],
                       "accessors": [{"bufferView": 0, "componentType": 5126, "count": 3, "type": "VEC3",
                                      "min": [0, 0, 0], "max": [1, 1, 0]}]})


def _ply_binary(vertices: int, faces: int, body: bytes = b"") -> bytes:
    return (f"ply\nformat binary_little_endian 1.0\nelement vertex {vertices}\nproperty float x\nproperty float y\n"
            f"property float z\nelement face {faces}\nproperty list uchar int vertex_indices\nend_header\n").encode() + body


def _not_created(name: str):
    def check(d: Path, o: Outcome) -> Optional[str]:
        return f"wrong: {name} was created (a YAML tag ran code)" if (d / name).exists() else None
    return check


def _unchanged(name: str, text: str):
    def check(d: Path, o: Outcome) -> Optional[str]:
        return None if (d / name).read_text() == text else f"data loss: {name} (the input) was changed"
    return check


def encoding_cases() -> list[Case]:
    c: list[Case] = []
    rect = csv_text(RECT)
    seg = lambda name, setup, check=None: c.append(Case(  # noqa: E731
        "encoding", name, ["segment", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/out.json"], setup=setup,
        check=check or length_is(RECT_LENGTH, closed=True)))
    seg("utf16-bom", files(c__csv=rect.encode("utf-16")))
    seg("utf16-le-no-bom", files(c__csv=rect.encode("utf-16-le")))
    seg("utf32-bom", files(c__csv=rect.encode("utf-32")))
    seg("utf8-bom-crlf", files(c__csv=b"\xef\xbb\xbf" + rect.replace("\n", "\r\n").encode()))
    seg("mac-cr-header", files(c__csv=("x,y\r" + rect.replace("\n", "\r")).encode()))
    seg("mixed-line-ends", files(c__csv="".join(line + ("\r\n", "\r", "\n")[k % 3]
                                                for k, line in enumerate(rect.splitlines())).encode()))
    seg("latin1-header", files(c__csv=("x (mm),y (mm) \xe9\n" + rect).encode("latin-1")))
    seg("form-feed-lines", files(c__csv=rect.replace("\n", "\x0c").encode()))
    seg("unicode-line-separator", files(c__csv=rect.replace("\n", "\u2028").encode()))
    seg("vertical-tab-separator", files(c__csv=rect.replace(",", "\x0b").encode()))
    seg("huge-line-100mb-digits", files(c__csv=lambda p: p.write_bytes(b"1" * 100_000_000)), check=lambda d, o: None)
    seg("huge-line-spaces", files(c__csv=lambda p: p.write_bytes(b"0,0" + b" " * 50_000_000 + b"\n10,0\n10,10\n")),
        check=lambda d, o: None)
    seg("million-rows-crlf", files(c__csv=lambda p: p.write_bytes(
        "".join(f"{i * 0.01:.2f},{(i % 100) * 0.01:.2f}\r\n" for i in range(1_000_000)).encode())), check=lambda d, o: None)
    for name, data in (("utf16", AS_OK.encode("utf-16")), ("crlf", AS_OK.replace("\n", "\r\n").encode()),
                       ("mac-cr", AS_OK.replace("\n", "\r").encode())):
        c.append(Case("encoding", f"program-{name}", ["check-program", "{d}/t.as"], setup=files(t__as=data)))
    for name, data in (("utf16", scenario().encode("utf-16")), ("crlf", scenario().replace("\n", "\r\n").encode()),
                       ("mac-cr", scenario().replace("\n", "\r").encode())):
        c.append(Case("encoding", f"scenario-{name}", ["run", "{d}/s.yaml", "--fast", "-o", "{d}/out"],
                      setup=files(s__yaml=data), timeout=180))
    return c


def mesh_cases() -> list[Case]:
    c: list[Case] = []
    plan = lambda name, setup, ext, bomb=False: c.append(Case(  # noqa: E731
        "mesh", name, ["plan", f"{{d}}/m.{ext}", "-o", "{d}/paths.json"], setup=setup, bomb=bomb, timeout=120))
    plan("glb-lying-1e9", files(m__glb=_glb_lying(1_000_000_000)), "glb", bomb=True)
    plan("glb-lying-1e6", files(m__glb=_glb_lying(1_000_000)), "glb", bomb=True)
    plan("glb-truncated", files(m__glb=_glb_lying(3)[:40]), "glb")
    plan("glb-length-lie", files(m__glb=_glb_lying(3)[:8] + struct.pack("<I", 2**31) + _glb_lying(3)[12:]), "glb")
    plan("gltf-uri-dev-zero", files(m__gltf=_gltf_uri("/dev/zero")), "gltf", bomb=True)
    plan("gltf-uri-traversal", files(m__gltf=_gltf_uri("../../../../../../etc/passwd")), "gltf")
    plan("gltf-uri-http", files(m__gltf=_gltf_uri("http://256.0.0.1/x.bin")), "gltf")
    plan("gltf-data-uri-bad", files(m__gltf=_gltf_uri("data:application/octet-stream;base64,!!!!")), "gltf")
    plan("ply-binary-lying", files(m__ply=_ply_binary(2_000_000_000, 2_000_000_000, b"\0" * 64)), "ply", bomb=True)
    plan("ply-face-lying", files(m__ply=_ply_binary(3, 2_000_000_000, struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0))),
         "ply", bomb=True)
    plan("ply-list-255", files(m__ply=_ply_binary(3, 1, struct.pack("<9f", 0, 0, 0, 1, 0, 0, 0, 1, 0) + b"\xff" + b"\0" * 8)),
         "ply")
    plan("obj-nan", files(m__obj=PLATE_OBJ.replace("v 100 0 0", "v nan 0 0")), "obj")
    plan("obj-inf", files(m__obj=PLATE_OBJ.replace("v 100 0 0", "v inf 0 0")), "obj")
    plan("obj-1e308", files(m__obj=PLATE_OBJ.replace("v 100 0 0", "v 1e308 0 0")), "obj")
    plan("obj-index-out-of-range", files(m__obj=PLATE_OBJ + "f 1 2 99\n"), "obj")
    plan("obj-negative-index", files(m__obj=PLATE_OBJ + "f -1 -2 -999\n"), "obj")
    plan("obj-self-crossing", files(m__obj=PLATE_OBJ + "v 50 -50 -50\nv 50 150 -50\nv 50 150 50\nv 50 -50 50\n"
                                    "f 5 6 7\nf 5 7 8\n"), "obj")
    plan("obj-all-one-point", files(m__obj="v 1 1 1\n" * 3 + "f 1 2 3\n" * 100), "obj")
    plan("obj-no-faces", files(m__obj="v 0 0 0\nv 1 0 0\nv 0 1 0\n"), "obj")
    plan("obj-tiny-1e-300", files(m__obj=PLATE_OBJ.replace("100", "1e-300")), "obj")
    plan("obj-huge-line", files(m__obj=lambda p: p.write_bytes(b"v " + b"1" * 50_000_000 + b" 0 0\n")), "obj", bomb=True)
    plan("stl-binary-count-lie", files(m__stl=b"\0" * 80 + (2**32 - 1).to_bytes(4, "little") + b"\0" * 50), "stl", bomb=True)
    plan("stl-ascii-nan-normal", files(m__stl="solid s\nfacet normal nan nan nan\nouter loop\nvertex 0 0 0\nvertex 100 0 0\n"
                                       "vertex 0 100 0\nendloop\nendfacet\nendsolid s\n"), "stl")
    c.append(Case("mesh", "coat-obj-nan", ["coat", "{d}/t.csv", "--surface", "{d}/m.obj", "-o", "{d}/out"],
                  setup=files(t__csv=trajectory_csv(), m__obj=PLATE_OBJ.replace("v 100 0 0", "v nan 0 0"))))
    c.append(Case("mesh", "coat-glb-lying", ["coat", "{d}/t.csv", "--surface", "{d}/m.glb", "-o", "{d}/out"],
                  setup=files(t__csv=trajectory_csv(), m__glb=_glb_lying(1_000_000_000)), bomb=True))
    return c


def path_cases() -> list[Case]:
    c: list[Case] = []
    rect = csv_text(RECT)
    c.append(Case("paths", "input-name-newline", ["segment", "{d}/a\nb.csv", "--tol", "0.1", "-o", "{d}/out.json"],
                  setup=files(**{"a\nb.csv": rect}), check=length_is(RECT_LENGTH, closed=True)))
    c.append(Case("paths", "output-name-newline", ["segment", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/o\nut.json"],
                  setup=files(c__csv=rect)))
    c.append(Case("paths", "missing-name-escape", ["segment", "{d}/\x1b[2Jx.csv", "--tol", "0.1"]))
    c.append(Case("paths", "name-255-bytes", ["segment", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/" + "a" * 300 + ".json"],
                  setup=files(c__csv=rect)))
    c.append(Case("paths", "input-dash-name", ["segment", "--tol", "0.1", "-o", "{d}/out.json", "--", "{d}/-x.csv"],
                  setup=files(**{"-x.csv": rect})))
    c.append(Case("paths", "execute-into-input-folder", ["execute", "{d}/t.as", "-o", "{d}"],
                  setup=files(t__as=AS_OK, **{"trajectory.csv": "precious user data\n"}),
                  check=victim_intact("trajectory.csv")))
    c.append(Case("paths", "segment-out-is-input-relative", ["segment", "c.csv", "--tol", "0.1", "-o", "./sub/../c.csv"],
                  setup=files(c__csv=rect, sub__keep=""), check=_unchanged("c.csv", rect)))
    c.append(Case("paths", "program-out-is-input-link", ["program", "{d}/c.csv", "--tol", "0.1", "-o", "{d}/l.as"],
                  setup=both(files(c__csv=rect), lambda d: (d / "l.as").symlink_to(d / "c.csv")),
                  check=_unchanged("c.csv", rect)))
    c.append(Case("paths", "coat-into-input-folder", ["coat", "{d}/trajectory.csv", "--surface", "plate:130x90@700,0,100",
                                                      "-o", "{d}"],
                  setup=both(files(trajectory__csv=trajectory_csv()), victim("thickness.npz")),
                  check=victim_intact("thickness.npz")))
    c.append(Case("paths", "run-into-scenario-folder", ["run", "{d}/s.yaml", "--fast", "-o", "{d}"],
                  setup=both(files(s__yaml=scenario()), victim("report.html")), check=victim_intact("report.html"),
                  timeout=180))
    return c


def yaml_cases() -> list[Case]:
    c: list[Case] = []
    merge = "a: &a {x: 1, y: 2}\n" + "".join(f"k{i}: &k{i}\n  <<: [{', '.join(['*a'] + [f'*k{j}' for j in range(i)][:9])}]\n"
                                           for i in range(30))
    texts = {
        "python-tag": scenario() + "extra: !!python/object/apply:os.system [\"touch pwned\"]\n",
        "python-name-tag": scenario().replace("name: hostile", "name: !!python/name:os.system"),
        "merge-bomb": scenario() + merge,
        "tab-indent": scenario().replace("segmentation: {tolerance_mm: 0.1}", "segmentation:\n\ttolerance_mm: 0.1"),
        "key-1mb": scenario() + "k" * 1_000_000 + ": 1\n",
        "anchor-redefined": scenario() + "x: &a 1\ny: &a 2\nz: *a\n",
        "binary-tag": scenario() + "blob: !!binary " + "QUFB" * 200_000 + "\n",
        "set-tag": scenario() + "s: !!set {a, b}\n",
        "timestamp-name": scenario().replace("name: hostile", "name: 2001-12-14t21:59:43.10-05:00"),
        "bool-variants": scenario().replace("variants: [polysegment]", "variants: yes"),
        "doc-separator": scenario() + "---\n" + scenario(),
    }
    for name, text in texts.items():
        c.append(Case("yaml", name, ["run", "{d}/s.yaml", "--fast", "-o", "{d}/out"], setup=files(s__yaml=text),
                      check=_not_created("pwned"), bomb=name in ("merge-bomb", "key-1mb", "binary-tag"), timeout=180))
    return c


def more_cases() -> list[Case]:
    return encoding_cases() + mesh_cases() + path_cases() + yaml_cases()
