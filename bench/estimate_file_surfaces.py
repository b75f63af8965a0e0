"""Height maps for the static estimate's held-out check on surfaces read from files (not made by
wearsim's generator): 1024² periodic maps of side L/4 at the paper's pixel size with a different
spectrum (H = 0.8, a roll-off plateau below q_r = 2π/(L/16) instead of a cut-off, cut off at λ_s =
16 Δx) and skewed heights (h + 0.3 (h² − ⟨h²⟩)/σ, rescaled to h_rms = 0.005 L), as a profilometer map
of a ground surface would have. Writes top-1.npy, top-2.npy and bottom.npy into the folder given.

    python bench/estimate_file_surfaces.py DIR
"""

import sys
from pathlib import Path

import numpy as np

N, LENGTH, HURST, RMS = 1024, 0.25, 0.8, 0.005
DX = LENGTH / N


def height_map(seed: int) -> np.ndarray:
    rng = np.random.default_rng(seed)
    q = 2 * np.pi * np.fft.fftfreq(N, d=DX)
    qx, qy = np.meshgrid(q, q, indexing="ij")
    qq = np.hypot(qx, qy)
    q_r, q_s = 2 * np.pi / (1.0 / 16), 2 * np.pi / (16 * DX)
    psd = np.where(qq < q_r, q_r, qq) ** (-2 * (1 + HURST))
    psd[(qq > q_s) | (qq == 0)] = 0.0
    noise = np.fft.fft2(rng.standard_normal((N, N)))
    h = np.real(np.fft.ifft2(noise * np.sqrt(psd)))
    h = (h - h.mean()) / h.std()
    h = h + 0.3 * (h**2 - 1.0)
    return RMS * (h - h.mean()) / h.std()


if __name__ == "__main__":
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    for name, seed in [("top-1.npy", 11), ("top-2.npy", 12), ("bottom.npy", 13)]:
        np.save(out / name, height_map(seed))
        print("wrote", out / name)
