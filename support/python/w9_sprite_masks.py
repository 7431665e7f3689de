"""The W9 sprite masks (shared/bench/FORMATS.md, sprite_masks.txt) as pygame masks, shared by
the pygame sprite test (tests/d2/pygame_sprites.py) and benchmark (bench/sprites_pygame.py)."""


def read_masks(path, pygame):
    """The masks of sprite_masks.txt as pygame masks, in id order (pixel (x, y) set iff bit
    3 - x mod 4 of hex digit x div 4 of row y is 1)."""
    with open(path) as f:
        lines = f.read().split("\n")
    count = int(dict(kv.split("=") for kv in lines[0].split()[2:])["count"])
    masks, at = [], 1
    for _ in range(count):
        _, _, w, h = lines[at].split()
        w, h = int(w), int(h)
        mask = pygame.mask.Mask((w, h))
        for y in range(h):
            row = lines[at + 1 + y]
            bits = bin(int(row, 16))[2:].zfill(4 * len(row))
            for x in range(w):
                if bits[x] == "1":
                    mask.set_at((x, y), 1)
        masks.append(mask)
        at += 1 + h
    return masks
