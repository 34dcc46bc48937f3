"""Stand-in of nerfstudio.cameras.rays.RayBundle: the same field names and defaults."""
from dataclasses import dataclass, field
from typing import Any, Dict, Optional


@dataclass
class RayBundle:
    origins: Any  # (*batch, 3)
    directions: Any  # (*batch, 3), unit
    pixel_area: Any  # (*batch, 1)
    camera_indices: Optional[Any] = None  # (*batch, 1)
    nears: Optional[Any] = None  # (*batch, 1)
    fars: Optional[Any] = None  # (*batch, 1)
    metadata: Dict[str, Any] = field(default_factory=dict)
    times: Optional[Any] = None

    def __len__(self):
        return int(self.origins.shape[0])
