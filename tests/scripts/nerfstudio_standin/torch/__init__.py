"""Stand-in torch for the recipe tests: tensors are numpy arrays (see ../README.md)."""
import contextlib

import numpy as np

float32 = np.float32
long = np.int64
int = np.int32  # noqa: A001 (torch.int)


class Tensor(np.ndarray):
    def cpu(self):
        return self

    def numpy(self):
        return np.asarray(self)


def tensor(data, dtype=None, device=None):
    return np.array(data, dtype=dtype).view(Tensor)


def ones_like(a, dtype=None):
    return np.ones_like(a, dtype=dtype).view(Tensor)


def zeros_like(a, dtype=None):
    return np.zeros_like(a, dtype=dtype).view(Tensor)


@contextlib.contextmanager
def no_grad():
    yield
