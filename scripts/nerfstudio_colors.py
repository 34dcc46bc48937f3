#!/usr/bin/env python3
"""Colours inim's query rays with a trained Nerfstudio model (docs/external-fields.md).

    inim rays --for-field --out rays.npy [display, placement, --vcp-mm, --spp]
    python3 scripts/nerfstudio_colors.py outputs/SCENE/nerfacto/RUN/config.yml rays.npy colors.npy
    inim eia --field-colors colors.npy [the same options] --out eia.exr

Frames. inim's rays are in the frame of the scene's transforms.json (the camera poses' frame).
Nerfstudio's data parser recentres, rotates and rescales those poses; it saves the result as
dataparser_transforms.json ("transform", 3x4, and "scale") next to config.yml. When
transforms.json carries an "applied_transform" (and "applied_scale"), which ns-process-data
writes for every COLMAP-derived scene, the saved transform and scale include them (they map the
COLMAP reconstruction's frame, not the poses' frame), so they are divided out here.

Output, one row per ray: R G B A depth (float32). R G B is the straight (not multiplied by A)
sRGB-encoded colour of what the ray sees, A the accumulation (coverage), depth the expected
depth in field units; a ray with accumulation below MISS_ACCUMULATION is a miss (depth inf):
below half coverage a NeRF's median depth is undefined and its expected depth is noise. The
model renders over black (its background colour never reaches the EIA: inim composites A * RGB
over the display's black).

Needs Nerfstudio (torch) for rendering; the frame and row helpers need only numpy.
"""
import argparse
import json
import sys
from pathlib import Path

import numpy as np

MISS_ACCUMULATION = 0.5  # below it a ray is a miss (non-finite depth)
DEFAULT_FAR_PLANE = 1000.0  # Nerfacto's far plane, for models whose config has none


def parser_frame(dataparser_transforms, transforms):
    """(M, s): x_parser = s * (M[:, :3] @ x + M[:, 3]) for x in the transforms.json frame."""
    T = np.vstack([np.asarray(dataparser_transforms["transform"], np.float64), [0.0, 0.0, 0.0, 1.0]])
    s = float(dataparser_transforms["scale"])
    if "applied_transform" in transforms:
        A = np.vstack([np.asarray(transforms["applied_transform"], np.float64), [0.0, 0.0, 0.0, 1.0]])
        T = T @ np.linalg.inv(A)
    if "applied_scale" in transforms:
        s /= float(transforms["applied_scale"])
    return T[:3], s


def rays_in_parser_frame(rays, M, s, far_plane):
    """Origins, unit directions, nears, fars (finite, <= far_plane) in the parser frame, and the
    parser length of one field unit along each ray."""
    o = (rays[:, :3] @ M[:, :3].T + M[:, 3]) * s
    d = rays[:, 3:6] @ M[:, :3].T
    norm = np.linalg.norm(d, axis=1, keepdims=True)
    d = d / norm
    unit = s * norm  # parser length per field length along the ray
    near = rays[:, 6:7] * unit
    far = np.minimum(rays[:, 7:8] * unit, far_plane)  # inf (unbounded) -> the model's far plane
    return o, d, near, np.maximum(far, near), unit


def colour_rows(rgb_over_black, accumulation, expected_depth, unit):
    """Rows R G B A depth: straight colour, coverage, depth in field units (inf for a miss)."""
    acc = np.clip(accumulation.reshape(-1, 1), 0.0, 1.0)
    rgb = np.where(acc > 0.0, rgb_over_black / np.maximum(acc, 1e-12), 0.0)
    depth = np.where(acc >= MISS_ACCUMULATION, expected_depth.reshape(-1, 1) / unit, np.inf)
    return np.hstack([np.clip(rgb, 0.0, 1.0), acc, depth]).astype(np.float32)


def load_model(config_path):
    """The run's config and its trained model, in eval mode, rendering over black."""
    from nerfstudio.utils.eval_utils import eval_setup

    # "inference" loads no images (no data-manager worker processes), as ns-render does.
    config, pipeline, _, _ = eval_setup(config_path, test_mode="inference")
    model = pipeline.model
    model.eval()
    renderer = getattr(model, "renderer_rgb", None)
    if renderer is not None:
        renderer.background_color = "black"  # premultiplied colour: rgb = sum of weights * colours
    return config, model


def render(model, o, d, near, far):
    """rgb over black, accumulation and expected depth (parser frame) of each ray, in chunks of
    the model's eval_num_rays_per_chunk."""
    import torch
    from nerfstudio.cameras.rays import RayBundle

    n = len(o)
    rgb, acc, depth = np.zeros((n, 3)), np.zeros((n, 1)), np.zeros((n, 1))
    chunk = int(model.config.eval_num_rays_per_chunk)
    with torch.no_grad():
        for i in range(0, n, chunk):
            part = slice(i, min(n, i + chunk))

            def tensor(a):
                return torch.tensor(a[part], dtype=torch.float32, device=model.device)

            bundle = RayBundle(
                origins=tensor(o),
                directions=tensor(d),
                pixel_area=torch.ones_like(tensor(near)),
                camera_indices=torch.zeros_like(tensor(near), dtype=torch.long),
                nears=tensor(near),
                fars=tensor(far),
            )
            out = model(bundle)
            depth_key = "expected_depth" if "expected_depth" in out else "depth"
            rgb[part] = out["rgb"].cpu().numpy()
            acc[part] = out["accumulation"].cpu().numpy().reshape(-1, 1)
            depth[part] = out[depth_key].cpu().numpy().reshape(-1, 1)
    return rgb, acc, depth


def colour_rays(config_path, rays, dataparser_json=None, transforms_json=None):
    """The colour table (N x 5) of inim's query rays (N x 8)."""
    config_path = Path(config_path)
    config, model = load_model(config_path)
    dataparser_json = Path(dataparser_json or config_path.parent / "dataparser_transforms.json")
    if transforms_json is None:
        datamanager = config.pipeline.datamanager  # the dataset the model trained on
        data = Path(datamanager.data or datamanager.dataparser.data)
        transforms_json = data if data.suffix == ".json" else data / "transforms.json"
    M, s = parser_frame(json.loads(Path(dataparser_json).read_text()), json.loads(Path(transforms_json).read_text()))
    far_plane = float(getattr(model.config, "far_plane", DEFAULT_FAR_PLANE))
    o, d, near, far, unit = rays_in_parser_frame(rays.astype(np.float64), M, s, far_plane)
    rows = np.zeros((len(rays), 5), np.float32)
    rows[:, 4] = np.inf
    reach = rays[:, 7] >= rays[:, 6]  # far < near: the ray never reaches the VCP (not rendered)
    if reach.any():
        rgb, acc, depth = render(model, o[reach], d[reach], near[reach], far[reach])
        rows[reach] = colour_rows(rgb, acc, depth, unit[reach])
    return rows


def main(argv=None):
    ap = argparse.ArgumentParser(description="Colour inim's query rays with a Nerfstudio model.")
    ap.add_argument("config", help="the run's config.yml (outputs/.../config.yml)")
    ap.add_argument("rays", help="rays.npy from `inim rays --for-field`")
    ap.add_argument("out", help="colors.npy for `inim eia --field-colors`")
    ap.add_argument("--dataparser-transforms", help="default: dataparser_transforms.json next to config.yml")
    ap.add_argument("--transforms", help="the scene's transforms.json (default: the dataset the model trained on)")
    args = ap.parse_args(argv)
    rays = np.load(args.rays)
    if rays.ndim != 2 or rays.shape[1] != 8:
        sys.exit(f"{args.rays}: shape {rays.shape}, expected (N, 8) from `inim rays --for-field`")
    np.save(args.out, colour_rays(args.config, rays, args.dataparser_transforms, args.transforms))


if __name__ == "__main__":
    main()
