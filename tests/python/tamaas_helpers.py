"""tamaas set-up shared by the cross-checks (imported only after tamaas is known to be importable)."""

import numpy as np
import tamaas as tm


def tamaas_model(n, ny=None, length_y=1.0):
    """A 2-D periodic tamaas model of side 1 (× ``length_y``) on n × n (× ``ny``) points, E = 1,
    ν = 0.3 (wearsim's half-space)."""
    ny = n if ny is None else ny
    model = tm.ModelFactory.createModel(tm.model_type.basic_2d, [1.0, length_y], [n, ny])
    model.E = 1.0
    model.nu = 0.3
    return model


def tamaas_labels(contact, diagonal):
    """Pixel → cluster map from tamaas's periodic FloodFill (its -1/N indices unwrapped), −1 outside."""
    nx, ny = contact.shape
    labels = -np.ones(contact.shape, dtype=np.int64)
    for c, cluster in enumerate(tm.FloodFill.getClusters(contact, diagonal)):
        for i, j in cluster.points:
            labels[i % nx, j % ny] = c
    return labels


def same_partition(a, b):
    """Whether two label maps describe the same partition (their label pairs form a bijection)."""
    pairs = set(zip(a.ravel().tolist(), b.ravel().tolist()))
    return len(pairs) == len({p[0] for p in pairs}) == len({p[1] for p in pairs})
