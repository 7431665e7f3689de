"""Compares Proxima's sprite overlaps with pygame's on the translation-only W9 queries.

Usage: pygame_sprites.py <sprite_answers executable> [<workload folder>]
(the folder defaults to PROXIMA_WORKLOADS, then to the executable's default folder)

For every translation-only query of sprites.txt (shared/bench/FORMATS.md, W9), Proxima's
count must equal pygame.mask.Mask.overlap_area, and Mask.overlap must find a pixel exactly
when the count is positive; that pixel must be set in both placed masks. Exit status 0 when
all agree, 1 otherwise, 77 (a skip) when pygame or the data is absent.
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', '..', 'support', 'python'))
from w9_sprite_masks import read_masks  # noqa: E402

SKIP = 77


def read_queries(path):
    """The lines of sprites.txt as tuples (maskA, xA, yA, maskB, xB, yB, turned)."""
    with open(path) as f:
        lines = f.read().split("\n")[1:]
    return [tuple(int(t) for t in line.split()[:6]) + (len(line.split()) > 6,) for line in lines if line.strip()]


def main():
    try:
        import pygame  # noqa: F401 (imported for pygame.mask)
        import pygame.mask
    except ImportError:
        print("pygame is not installed (Debian: apt-get install python3-pygame)")
        return SKIP
    exe = sys.argv[1]
    folder = sys.argv[2] if len(sys.argv) > 2 else os.environ.get("PROXIMA_WORKLOADS", "")
    run = subprocess.run([exe] + ([folder] if folder else []), capture_output=True, text=True)
    if run.returncode == SKIP:
        print(run.stderr.strip())
        return SKIP
    if run.returncode != 0:
        print("sprite_answers failed: " + run.stderr)
        return 1
    lines = run.stdout.splitlines()
    folder = lines[0].split(" ", 2)[2]  # "# folder <dir>": where the executable found the data
    answers = [tuple(int(t) for t in line.split()) for line in lines[1:]]
    return compare(answers, folder, pygame)


def compare(answers, folder, pygame):
    masks = read_masks(os.path.join(folder, "sprite_masks.txt"), pygame)
    queries = read_queries(os.path.join(folder, "sprites.txt"))
    failures = 0
    for k, count, fx, fy in answers:
        ma, xa, ya, mb, xb, yb, turned = queries[k]
        assert not turned
        a, b = masks[ma], masks[mb]
        offset = (xb - xa, yb - ya)
        area = a.overlap_area(b, offset)
        point = a.overlap(b, offset)
        ok = area == count and (point is not None) == (count > 0)
        if point is not None:
            px, py = point
            ok = ok and a.get_at((px, py)) == 1 and b.get_at((px - offset[0], py - offset[1])) == 1
        if not ok:
            failures += 1
            if failures <= 10:
                print("query %d: proxima count %d first (%d, %d); pygame overlap_area %d overlap %s"
                      % (k, count, fx, fy, area, point))
    print("%d translation-only queries compared with pygame %s, %d differ"
          % (len(answers), pygame.version.ver, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
