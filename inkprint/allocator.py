"""Keep freed image buffers in the process for reuse (glibc ``mallopt``).

An analysis makes and drops many temporary arrays of the sheet's size (masks,
labels, distance maps: 2-30 MB each). glibc hands each of those out as a fresh
``mmap`` and returns it on ``free`` until its adaptive threshold has grown, so a
fresh process touches new pages again and again: on a 300 dpi letter sheet
``inkprint analyze`` spent 0.25 s of its 0.7 s in the kernel faulting pages in.
:func:`keep_freed_memory` raises the thresholds once, at a process's start (the CLI
and the batch workers call it; a library call does not change its host process):
freed buffers stay in the heap and are reused (system time 0.25 s -> 0.08 s).
Every thread allocates from that one heap (the threads measuring a sheet's prints
had heaps of their own, faulted in anew), and it is grown ahead at the start and
marked for transparent huge pages (``madvise``; what glibc's ``hugetlb`` tunable
does, which only the environment can set): where a 2 MB page faults in, 512 small
pages did one by one (``inkprint analyze`` on a 300 dpi letter sheet: 26 000 ->
7 000 page faults, 40 ms less system time, peak memory 168 -> 135 MB).
Elsewhere than glibc (macOS, Windows, musl) it does nothing.
"""

from __future__ import annotations

__all__ = ["keep_freed_memory"]

# mallopt parameters (glibc malloc.h)
_M_TRIM_THRESHOLD = -1
_M_TOP_PAD = -2
_M_MMAP_THRESHOLD = -3
_M_ARENA_MAX = -8
#: buffers up to this size [bytes] come from the heap (glibc's cap for the
#: threshold is HEAP_MAX / 2 = 32 MB on 64-bit)
MMAP_THRESHOLD = 32 * 1024 * 1024
#: the heap is trimmed back to the system only above this much free memory [bytes]
TRIM_THRESHOLD = 256 * 1024 * 1024
#: extra memory asked for on each heap growth [bytes]
TOP_PAD = 64 * 1024 * 1024
#: the heap is grown ahead in pieces it hands out (below ``MMAP_THRESHOLD``) [bytes]:
#: few, as the first page of each is written before it is marked (a small page)
_HEAP_PIECE = MMAP_THRESHOLD - 1024 * 1024
#: ... by this much [bytes], marked for huge pages (a 300 dpi letter sheet's
#: analysis uses about 90 MB of it; beyond it, small pages as before)
HUGE_HEAP = 4 * _HEAP_PIECE

_done = False


def _libc(ctypes):
    """glibc by its soname; ``ctypes.util.find_library`` only when that fails (it
    imports subprocess and tempfile and runs ``ldconfig``: 12 ms of a 0.5 s
    ``inkprint analyze``)."""
    try:
        return ctypes.CDLL("libc.so.6")
    except OSError:
        import ctypes.util

        return ctypes.CDLL(ctypes.util.find_library("c") or "libc.so.6")


def _huge_heap(libc, ctypes) -> None:
    """Grow the heap by :data:`HUGE_HEAP` (and glibc's top pad), mark the stretch
    for transparent huge pages and free it: the heap keeps it (the trim threshold
    is above it), untouched until arrays are made in it. Nothing on a kernel
    without huge pages, or when the pieces do not lie in one stretch."""
    import mmap

    advice = getattr(mmap, "MADV_HUGEPAGE", None)
    if advice is None:
        return
    libc.malloc.restype, libc.malloc.argtypes = ctypes.c_void_p, (ctypes.c_size_t,)
    libc.free.restype, libc.free.argtypes = None, (ctypes.c_void_p,)
    libc.sbrk.restype, libc.sbrk.argtypes = ctypes.c_void_p, (ctypes.c_ssize_t,)
    libc.madvise.restype = ctypes.c_int
    libc.madvise.argtypes = (ctypes.c_void_p, ctypes.c_size_t, ctypes.c_int)
    pieces = [libc.malloc(_HEAP_PIECE) for _ in range(HUGE_HEAP // _HEAP_PIECE)]
    try:
        if not all(pieces):
            return
        lo, hi = min(pieces), max(pieces) + _HEAP_PIECE
        end = libc.sbrk(0) or hi  # the heap's end: its top pad too
        if hi - lo > 2 * HUGE_HEAP or not hi <= end <= hi + 2 * TOP_PAD:
            return  # not one stretch of the heap (another allocator?): leave it
        page = mmap.PAGESIZE
        start = -(-lo // page) * page
        libc.madvise(start, (end - start) // page * page, advice)
    finally:
        for p in reversed(pieces):
            if p:
                libc.free(p)


def keep_freed_memory() -> bool:
    """Raise glibc's mmap and trim thresholds for this process, give it one heap
    for all its threads and grow that heap ahead on huge pages (once).

    Returns
    -------
    bool
        Whether the allocator was tuned (False off glibc or when ``mallopt`` refuses).
    """
    global _done
    if _done:
        return True
    import ctypes
    import sys

    if not sys.platform.startswith("linux"):
        return False
    try:
        libc = _libc(ctypes)
        mallopt = libc.mallopt
    except (OSError, AttributeError):
        return False
    mallopt.argtypes, mallopt.restype = (ctypes.c_int, ctypes.c_int), ctypes.c_int
    ok = all(
        mallopt(p, v) == 1
        for p, v in (
            (_M_MMAP_THRESHOLD, MMAP_THRESHOLD),
            (_M_TRIM_THRESHOLD, TRIM_THRESHOLD),
            (_M_TOP_PAD, TOP_PAD),
            (_M_ARENA_MAX, 1),
        )
    )
    if ok:
        try:
            _huge_heap(libc, ctypes)
        except (OSError, AttributeError):  # a libc without sbrk / madvise: small pages
            pass
    _done = ok
    return ok
