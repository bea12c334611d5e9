"""Prints drawn at ``ss`` x the scan's resolution, with the truth of the drawn ink."""

import cv2
import numpy as np


def drawn_scan(ink: np.ndarray, dpi: float, ss: int, darkness: float) -> tuple:
    """Grey image (area coverage of the supersampled drawing ``ink``, (h, w) uint8 0/1,
    ``darkness`` below the 0.92 paper, pixel noise 0.01), mm per px and the drawn
    ink's (length along x, width along y, hull area) [mm, mm^2]."""
    mm = 25.4 / dpi / ss
    h, w = ink.shape
    pts = cv2.findNonZero(ink).reshape(-1, 2)
    truth = (
        (np.ptp(pts[:, 0]) + 1) * mm,
        (np.ptp(pts[:, 1]) + 1) * mm,
        cv2.contourArea(cv2.convexHull(pts)) * mm * mm,
    )
    cover = cv2.resize(ink.astype(np.float32), (w // ss, h // ss), interpolation=cv2.INTER_AREA)
    grey = 0.92 - darkness * cover + np.random.default_rng(0).normal(0, 0.01, cover.shape)
    return grey.astype(np.float32), 25.4 / dpi, truth
