"""A stand-in for a SurfaceTopography topography, shared by the tests of measured inputs."""

import numpy as np


class FakeTopography:
    """What wearsim uses of a SurfaceTopography topography."""

    def __init__(self, heights, physical_sizes, unit=None):
        self._heights = heights
        self.physical_sizes = physical_sizes
        self.nb_grid_pts = heights.shape
        self.unit = unit
        self.has_undefined_data = bool(np.ma.is_masked(heights))

    def heights(self):
        return self._heights
