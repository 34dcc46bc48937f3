"""Stand-in of nerfstudio.utils.eval_utils.eval_setup whose model renders an analytic sphere.

config.yml here is JSON: {"data": dataset dir, "centre": [x, y, z], "radius": r (parser
frame), "srgb": [r, g, b], "eval_num_rays_per_chunk": n, "far_plane": f}.
"""
import json
from pathlib import Path
from types import SimpleNamespace

import numpy as np

import torch


class RGBRenderer:
    def __init__(self, background_color="last_sample"):
        self.background_color = background_color


class SphereModel:
    """Nerfacto-like outputs: accumulation never exactly 0 (0.02 on a miss), finite depths
    everywhere, `depth` the median depth (here the sphere's far side) and `expected_depth` the
    entry distance; colour composited over a grey background unless rendering over black."""

    MISS_ACCUMULATION = 0.02

    def __init__(self, cfg):
        self.config = SimpleNamespace(eval_num_rays_per_chunk=int(cfg["eval_num_rays_per_chunk"]),
                                      far_plane=float(cfg["far_plane"]))
        self.device = "cpu"
        self.centre = np.asarray(cfg["centre"], np.float64)
        self.radius = float(cfg["radius"])
        self.srgb = np.asarray(cfg["srgb"], np.float64)
        self.renderer_rgb = RGBRenderer()
        self.chunks = 0

    def eval(self):
        return self

    def __call__(self, bundle):
        n = len(bundle)
        if n > self.config.eval_num_rays_per_chunk:
            raise ValueError(f"{n} rays in one call, above eval_num_rays_per_chunk")
        for name in ("pixel_area", "camera_indices", "nears", "fars"):
            if getattr(bundle, name) is None or getattr(bundle, name).shape != (n, 1):
                raise ValueError(f"RayBundle.{name} must have shape ({n}, 1)")
        near, far = np.asarray(bundle.nears)[:, 0], np.asarray(bundle.fars)[:, 0]
        if not (np.isfinite(far).all() and (far <= self.config.far_plane).all() and (far >= near).all()):
            raise ValueError("fars must be finite, >= nears and <= the far plane")
        o, d = np.asarray(bundle.origins, np.float64), np.asarray(bundle.directions, np.float64)
        if np.abs(np.linalg.norm(d, axis=1) - 1.0).max() > 1e-5:
            raise ValueError("directions must be unit vectors")
        oc = self.centre - o
        tca = np.einsum("ij,ij->i", oc, d)
        b2 = np.einsum("ij,ij->i", oc, oc) - tca * tca
        th = np.sqrt(np.maximum(self.radius**2 - b2, 0.0))
        t0 = tca - th
        hit = (b2 <= self.radius**2) & (t0 >= near) & (t0 <= far)
        acc = np.where(hit, 1.0, self.MISS_ACCUMULATION)[:, None]
        premultiplied = np.where(hit[:, None], self.srgb[None, :], 0.0)
        bg = np.zeros(3) if self.renderer_rgb.background_color == "black" else np.full(3, 0.9)
        rgb = premultiplied + (1.0 - acc) * bg
        expected = np.where(hit, t0, 0.5 * (near + far))[:, None]
        median = np.where(hit, tca + th, far)[:, None]
        self.chunks += 1
        t = lambda a: torch.tensor(a, dtype=torch.float32)
        return {"rgb": t(rgb), "accumulation": t(acc), "depth": t(median), "expected_depth": t(expected)}


def eval_setup(config_path, eval_num_rays_per_chunk=None, test_mode="test"):
    """(config, pipeline, checkpoint_path, step), as Nerfstudio 1.x returns them."""
    if test_mode != "inference":
        raise RuntimeError(f"test_mode={test_mode!r}: the real eval_setup would load the dataset and start "
                           "data-manager worker processes; use test_mode='inference'")
    cfg = json.loads(Path(config_path).read_text())
    if eval_num_rays_per_chunk:
        cfg["eval_num_rays_per_chunk"] = eval_num_rays_per_chunk
    model = SphereModel(cfg)
    datamanager = SimpleNamespace(data=None, dataparser=SimpleNamespace(data=Path(cfg["data"])))
    config = SimpleNamespace(pipeline=SimpleNamespace(datamanager=datamanager, model=model.config))
    pipeline = SimpleNamespace(model=model, datamanager=datamanager)
    return config, pipeline, Path(config_path).parent / "nerfstudio_models", 30000
