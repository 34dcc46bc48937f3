#!/usr/bin/env python3
"""scripts/nerfstudio_colors.py end to end against stand-ins for Nerfstudio and torch
(tests/scripts/nerfstudio_standin): an opaque sphere rendered by the stand-in model in the data
parser's frame, for a COLMAP-style scene (transforms.json with applied_transform and
applied_scale), against `inim eia --scene` on the same sphere as an analytic scene: the same
hit count, the same colour (within 3 %) and the same display depth Z (within 10 %) on every
pixel both see, and black where neither does.

    /usr/bin/python3 tests/scripts/test_nerfstudio_recipe.py INIM_BINARY [SCRATCH_DIR]

Exit 77 (skipped) without numpy or oiiotool.
"""
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile
from pathlib import Path

try:
    import numpy as np
except ImportError:
    print("numpy missing (Debian python3-numpy): skipped")
    sys.exit(77)

ROOT = Path(__file__).resolve().parents[2]
STANDIN = Path(__file__).resolve().parent / "nerfstudio_standin"

# The sphere in the transforms.json frame (= inim's field frame, mm): 3 mm, behind the MLA.
CENTRE_MM, RADIUS_MM = np.array([0.6, -0.4, -8.0]), 3.0
LINEAR_GREY = 0.5  # a D65 emitter of luminance 0.5 is linear Rec.709 (0.5, 0.5, 0.5)
# ns-process-data's applied_transform for COLMAP scenes (swap y and z, flip one) and a scale.
APPLIED = np.array([[1.0, 0, 0, 0], [0, 0, 1.0, 0], [0, -1.0, 0, 0]])
APPLIED_SCALE = 2.0


def srgb_encode(v):
    return 12.92 * v if v <= 0.0031308 else 1.055 * v ** (1 / 2.4) - 0.055


def orientation():
    """The parser's own re-orientation of the poses (a turn about an oblique axis, a shift) and
    pose scale, as auto_orient_and_center_poses and auto_scale_poses would give."""
    a = np.radians(35.0)
    rz = np.array([[np.cos(a), -np.sin(a), 0], [np.sin(a), np.cos(a), 0], [0, 0, 1]])
    rx = np.array([[1, 0, 0], [0, np.cos(0.4), -np.sin(0.4)], [0, np.sin(0.4), np.cos(0.4)]])
    T = np.eye(4)
    T[:3, :3] = rx @ rz
    T[:3, 3] = [0.3, -1.2, 0.7]
    return T, 0.01


def write_scene(d):
    """transforms.json, dataparser_transforms.json and the stand-in config; the analytic scene."""
    T, s_pose = orientation()
    data = d / "data"
    data.mkdir()
    (data / "transforms.json").write_text(json.dumps(
        {"applied_transform": APPLIED.tolist(), "applied_scale": APPLIED_SCALE, "frames": []}))
    # Nerfstudio folds the applied transform and scale into what it saves (they map COLMAP's
    # frame): transform = orientation @ applied, scale = pose scale * applied scale.
    A = np.vstack([APPLIED, [0, 0, 0, 1]])
    run = d / "outputs" / "sphere" / "nerfacto" / "run"
    run.mkdir(parents=True)
    (run / "dataparser_transforms.json").write_text(json.dumps(
        {"transform": (T @ A)[:3].tolist(), "scale": s_pose * APPLIED_SCALE}))
    # The sphere where the parser puts the poses' frame: s_pose * (T x).
    centre = s_pose * (T[:3, :3] @ CENTRE_MM + T[:3, 3])
    (run / "config.yml").write_text(json.dumps(
        {"data": str(data), "centre": centre.tolist(), "radius": s_pose * RADIUS_MM,
         "srgb": [srgb_encode(LINEAR_GREY)] * 3, "eval_num_rays_per_chunk": 4096, "far_plane": 1000.0}))
    scene = d / "sphere.json"
    scene.write_text(json.dumps({
        "units": "mm",
        "materials": {"glow": {"type": "emitter", "spectrum": "D65", "scale": LINEAR_GREY}},
        "objects": [{"id": 1, "type": "sphere", "radius_mm": RADIUS_MM, "translate_mm": CENTRE_MM.tolist(),
                     "material": "glow"}]}))
    display = d / "display.json"
    display.write_text(json.dumps({
        "name": "small test display",
        "panel": {"name": "test panel", "resolution_px": [15 * 9 + 6, 15 * 9 + 6], "pixel_pitch_mm": 0.1,
                  "primaries": {"R": {"gaussian": {"mean_nm": 625, "fwhm_nm": 35}},
                                "G": {"gaussian": {"mean_nm": 530, "fwhm_nm": 35}},
                                "B": {"gaussian": {"mean_nm": 460, "fwhm_nm": 30}}},
                  "peak_luminance_cd_m2": 500},
        "mla": {"name": "test mla", "pitch_mm": 0.9, "focal_length_mm": 3.0, "substrate_thickness_mm": 1.0,
                "material": "PMMA"},
        "generation_gap_mm": 3.0, "reconstruction_gap_mm": 3.5, "ei_px": 9, "ei_count": [15, 15]}))
    return run / "config.yml", scene, display


def run(cmd, **kw):
    p = subprocess.run([str(c) for c in cmd], capture_output=True, text=True, **kw)
    if p.returncode != 0:
        sys.exit(f"FAILED: {' '.join(map(str, cmd))}\n{p.stdout}{p.stderr}")
    return p.stdout + p.stderr


def read_exr(path):
    """(H, W, C) floats and channel names, through oiiotool --dumpdata."""
    text = run(["oiiotool", "--dumpdata", path])
    pixels = {}
    for m in re.finditer(r"Pixel \((\d+), (\d+)\):((?: -?[0-9.e+-]+|\s+-?nan|\s+-?inf)+)", text):
        pixels[(int(m.group(2)), int(m.group(1)))] = [float(v) for v in m.group(3).split()]
    h = max(k[0] for k in pixels) + 1
    w = max(k[1] for k in pixels) + 1
    img = np.zeros((h, w, len(next(iter(pixels.values())))))
    for (y, x), v in pixels.items():
        img[y, x] = v
    names = re.search(r"channel list: (.*)", run(["oiiotool", "--info", "-v", path])).group(1)
    return img, [c.strip() for c in names.split(",")]


def hits(summary):
    return int(re.search(r"scene:\s+(\d+) rays hit it", summary).group(1))


def main():
    inim = Path(sys.argv[1])
    if shutil.which("oiiotool") is None:
        print("oiiotool missing (Debian openimageio-tools): skipped")
        return 77
    d = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp(prefix="inim_ns_recipe_"))
    d.mkdir(parents=True, exist_ok=True)
    config, scene, display = write_scene(d)
    env = dict(os.environ, PYTHONPATH=f"{STANDIN}{os.pathsep}{os.environ.get('PYTHONPATH', '')}")
    # Importing the recipe runs nothing (Nerfstudio's worker processes re-import the main module).
    quiet = run([sys.executable, "-c", "import sys; sys.path.insert(0, sys.argv[1]); import nerfstudio_colors",
                 ROOT / "scripts"], env=env)
    if quiet:
        sys.exit(f"FAILED: importing scripts/nerfstudio_colors.py did something:\n{quiet}")
    common = ["--display", display, "--spp", "2", "--exposure", "1", "--aovs"]
    run([inim, "rays", "--for-field", "--display", display, "--spp", "2", "--out", d / "rays.npy"])
    run([sys.executable, ROOT / "scripts" / "nerfstudio_colors.py", config, d / "rays.npy", d / "colors.npy"], env=env)
    rows = np.load(d / "colors.npy")
    rays = np.load(d / "rays.npy")
    assert rows.shape == (len(rays), 5), rows.shape
    s_ns = run([inim, "eia", *common, "--field-colors", d / "colors.npy", "--out", d / "ns.exr"])
    s_direct = run([inim, "eia", *common, "--scene", scene, "--out", d / "direct.exr"])
    failures = []
    h_ns, h_direct = hits(s_ns), hits(s_direct)
    print(f"hits: recipe {h_ns}, analytic scene {h_direct}")
    if h_ns != h_direct or h_direct == 0:
        failures.append(f"hit counts differ: {h_ns} vs {h_direct}")
    ns, ch = read_exr(d / "ns.exr")
    direct, ch2 = read_exr(d / "direct.exr")
    assert ch == ch2 and ch[:3] == ["R", "G", "B"], (ch, ch2)
    a, z = ch.index("A"), ch.index("Z")
    both = (ns[..., a] > 0) & (direct[..., a] > 0)
    neither = (ns[..., a] == 0) & (direct[..., a] == 0)
    rgb_ns, rgb_direct = ns[both][:, :3].mean(0), direct[both][:, :3].mean(0)
    print(f"mean colour where both see the sphere ({both.sum()} px): recipe {rgb_ns}, analytic {rgb_direct}")
    if not both.any() or np.abs(rgb_ns / rgb_direct - 1).max() > 0.03:
        failures.append("colours differ by more than 3 %")
    if both.any():
        zerr = np.abs(ns[both][:, z] - direct[both][:, z]) / np.abs(direct[both][:, z])
        print(f"display depth Z: worst relative difference {zerr.max():.3g}")
        if zerr.max() > 0.10:
            failures.append("depth Z differs by more than 10 %")
    if not neither.any() or np.abs(ns[neither][:, :3]).max() > 0.0:
        failures.append("light where no ray hits the sphere (a background leaked)")
    cy, cx = np.array(ns.shape[:2]) // 2
    print(f"centre pixel: recipe {ns[cy, cx, :3]}, analytic {direct[cy, cx, :3]}")
    for f in failures:
        print("FAIL:", f)
    if not failures and len(sys.argv) <= 2:
        shutil.rmtree(d)
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
