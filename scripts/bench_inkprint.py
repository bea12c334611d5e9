"""Benchmark: ink-print analysis vs decoding the same file (issue 4).

Letter-size synthetic scans at 300 and 600 dpi (two knobby prints, a label, a ruler,
grain): prints, side by side, the time to decode the PNG, to analyse it (with and
without the threshold sensitivity band), and their ratio (targets: analysis <= 2x
decode, <= 0.5 s at 300 dpi on one core); then batch throughput with 2 workers.

Run: python scripts/bench_inkprint.py
"""

from __future__ import annotations

import os
import sys
import tempfile
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent))

from inkprint import analyze_scan, read_scan
from inkprint.batch import Options, run_batch
from inkprint.synth import drum_and_plate_sheet, render_sheet, save_scan


def best(fn, repeat=5):
    times = []
    for _ in range(repeat):
        t0 = time.perf_counter()
        fn()
        times.append(time.perf_counter() - t0)
    return min(times)


def main() -> None:
    os.environ.setdefault("OMP_NUM_THREADS", "1")
    try:
        import cv2

        cv2.setNumThreads(1)  # one core, as the target says
    except ImportError:
        pass
    with tempfile.TemporaryDirectory() as tmp:
        tmp = Path(tmp)
        for dpi in (300, 600):
            spec = drum_and_plate_sheet(
                tire_radius=14.9,
                load=450.0,
                pressure=0.45,
                dpi=dpi,
                tread="knobby",
                label="bench",
                halo_spots=8,
            )
            img, _ = render_sheet(spec)
            path = save_scan(img, tmp / f"sheet{dpi}.png", dpi=dpi)
            scan = read_scan(path)
            t_dec = best(lambda path=path: read_scan(path))
            t_ana = best(lambda scan=scan: analyze_scan(scan, sensitivity=False))
            t_band = best(lambda scan=scan: analyze_scan(scan))
            print(
                f"{dpi} dpi letter ({img.shape[1]} x {img.shape[0]} px, {path.stat().st_size / 1e6:.1f} MB PNG)"
            )
            print(f"  decode (read_scan)                : {t_dec:6.3f} s")
            print(
                f"  analyse (no sensitivity band)     : {t_ana:6.3f} s   ratio to decode {t_ana / t_dec:4.2f}"
            )
            print(
                f"  analyse (with +-10 % band)        : {t_band:6.3f} s   ratio to decode {t_band / t_dec:4.2f}"
            )
        src = tmp / "batch"
        src.mkdir()
        spec = drum_and_plate_sheet(
            tire_radius=14.9, load=450.0, pressure=0.45, dpi=300, tread="file"
        )
        img, _ = render_sheet(spec)
        for i in range(16):
            save_scan(img[i:], src / f"s{i:02d}.png", dpi=300)
        for workers in (1, 2):
            t0 = time.perf_counter()
            run_batch(
                src,
                tmp / f"res{workers}.csv",
                options=Options(),
                workers=workers,
                progress=False,
                resume=False,
            )
            dt = time.perf_counter() - t0
            print(
                f"batch of 16 scans at 300 dpi, {workers} worker(s): {dt:5.2f} s -> {16 / dt:5.2f} scans/s"
            )


if __name__ == "__main__":
    main()
